// Shared set-up for the browser tests: a static server for web/dist (no dev server, so the test
// sees exactly what `npm start` serves) and Debian's Chromium driven by playwright-core.
import { createServer } from 'node:http';
import { after, before } from 'node:test';
import { mkdir } from 'node:fs/promises';
import { readFile, stat } from 'node:fs/promises';
import { extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

export const root = fileURLToPath(new URL('../..', import.meta.url));
export const dist = join(root, 'web', 'dist');
export const screenshots = join(root, 'tests', 'e2e', 'screenshots');

const types = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.pddl': 'text/plain; charset=utf-8',
};

/** Serves web/dist on 127.0.0.1 at a free port; resolves to { url, close }. */
export async function serve() {
  const server = createServer(async (req, res) => {
    try {
      const path = decodeURIComponent(new URL(req.url ?? '/', 'http://x').pathname);
      let file = normalize(join(dist, path));
      if (!file.startsWith(dist)) throw new Error('outside');
      if ((await stat(file)).isDirectory()) file = join(file, 'index.html');
      const body = await readFile(file);
      res.writeHead(200, { 'content-type': types[extname(file)] ?? 'application/octet-stream' });
      res.end(body);
    } catch {
      res.writeHead(404).end('not found');
    }
  });
  await new Promise((r) => server.listen(0, '127.0.0.1', () => r(undefined)));
  const { port } = /** @type {import('node:net').AddressInfo} */ (server.address());
  return { url: `http://127.0.0.1:${port}/`, close: () => new Promise((r) => server.close(r)) };
}

export const chromiumArgs = [
  '--no-sandbox',
  '--headless',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

export async function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium',
    args: chromiumArgs,
  });
}

/**
 * Registers the file's before/after hooks: one static server and one Chromium for the whole test
 * file (and the screenshots folder when `screenshots` is set). Returns `{ server, browser }`,
 * filled in once the `before` hook has run.
 */
export function useBrowser({ withScreenshots = false } = {}) {
  const ctx = /** @type {{ server: any, browser: any }} */ ({ server: undefined, browser: undefined });
  before(async () => {
    ctx.server = await serve();
    ctx.browser = await launch();
    if (withScreenshots) await mkdir(screenshots, { recursive: true });
  });
  after(async () => {
    await ctx.browser?.close();
    await ctx.server?.close();
  });
  return ctx;
}

/** A new page that records console errors and uncaught exceptions into `errors`. */
export async function openPage(browser, url, { width = 1440, height = 900 } = {}) {
  const page = await browser.newPage({ viewport: { width, height } });
  const errors = [];
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
  });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  return { page, errors };
}

/** Opens the page with URL parameters and waits until the worker is ready and the first frame drawn. */
export async function openApp(browser, server, query = '', viewport = undefined) {
  const r = await openPage(browser, `${server.url}${query}`, viewport);
  await r.page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
  return r;
}

/** The page's current frame. */
export async function currentFrame(page) {
  return page.evaluate(() => window.lfd.frame());
}

/** Waits until the run is done or failed and returns the last frame. */
export async function finish(page, timeout = 120000) {
  await page.waitForFunction(
    () => {
      const f = window.lfd.frame();
      return f && (f.status.kind === 'done' || f.status.kind === 'failed');
    },
    null,
    { timeout, polling: 200 },
  );
  return currentFrame(page);
}

/** An IPC blocks-world file of the vendored benchmarks (`tests/data/ipc`). */
export const ipcBlocks = (f) => readFile(join(root, 'tests', 'data', 'ipc', 'blocks', f), 'utf8');

/** A blocks-world problem with `n` blocks in one tower, goal the reversed tower: blind BFS cannot finish. */
export function bigBlocks(n) {
  const b = Array.from({ length: n }, (_, i) => `b${i}`);
  const init = ['(handempty)', `(ontable ${b[0]})`, `(clear ${b[n - 1]})`, ...b.slice(1).map((x, i) => `(on ${x} ${b[i]})`)];
  const goal = b.slice(0, -1).map((x, i) => `(on ${x} ${b[i + 1]})`);
  return `(define (problem big-${n}) (:domain BLOCKS)\n (:objects ${b.join(' ')})\n (:init ${init.join(' ')})\n (:goal (and ${goal.join(' ')})))\n`;
}

/** The scene's clear colour (web/src/view.ts), as [r, g, b]. */
export const BACKGROUND = [0x14, 0x17, 0x1c];

/**
 * The colour [r, g, b] the page shows at client point (x, y): a 1-pixel screenshot (what is
 * composited on screen, whatever the WebGL drawing buffer keeps), decoded in the page.
 */
export async function pixelAt(page, x, y) {
  const png = await page.screenshot({ clip: { x: Math.round(x), y: Math.round(y), width: 1, height: 1 } });
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas').getContext('2d');
    if (!c) throw new Error('no 2d context');
    c.drawImage(img, 0, 0);
    return [...c.getImageData(0, 0, 1, 1).data.slice(0, 3)];
  }, png.toString('base64'));
}

/** Sum of the channel differences of two colours. */
export const colourDistance = (a, b) => a.reduce((s, v, i) => s + Math.abs(v - b[i]), 0);

/** Opens the PDDL tab and types `domain` and `problem` into its editors (replacing their texts). */
export async function typeIntoEditor(page, domain, problem) {
  const visible = '#panel-pddl .cm-host:not([hidden]) .cm-content';
  await page.click('#tab-pddl');
  // The benchmark's own texts arrive first; the typed text replaces them.
  await page.waitForFunction((sel) => document.querySelector(sel)?.textContent.includes('define'), visible);
  for (const [which, text] of [['domain', domain], ['problem', problem]]) {
    await page.click(`#pddl-tab-${which}`);
    await page.click(visible);
    await page.keyboard.press('ControlOrMeta+A');
    // Typed as one input event (key by key, the editor's bracket closing would double parentheses).
    await page.keyboard.insertText(text);
  }
  await page.click('#pddl-tab-domain');
  const head = domain.slice(0, 200).replace(/\s+/g, ' ').trim().slice(0, 40);
  await page.waitForFunction(([sel, h]) => document.querySelector(sel)?.textContent.replace(/\s+/g, ' ').includes(h), [visible, head]);
}

/** Runs the Compare tab on a scripted disturbance `level` at `at` s and waits for its table. */
export async function runScriptedCompare(page, level, at) {
  await page.click('#tab-compare');
  await page.waitForSelector('#compare-run');
  await page.selectOption('#compare-level', level);
  await page.fill('#compare-at', String(at));
  await page.click('#compare-run');
  await page.waitForSelector('.compare[data-done="true"]', { timeout: 240000 });
}

/** The Compare tab's results table, one object per method row. */
export async function compareRows(page) {
  return page.$$eval('#compare-table tbody tr', (trs) =>
    trs.map((tr) => ({
      name: tr.querySelector('th')?.textContent,
      result: tr.children[1]?.textContent,
      replans: Number(tr.children[3]?.textContent),
      reason: tr.querySelector('.reason')?.textContent ?? '',
      disturbance: tr.querySelector('.reason')?.getAttribute('title') ?? '',
    })),
  );
}
