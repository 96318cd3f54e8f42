// Browser test of the Compare tab's experiment (Debian Chromium): Table I run on the page in a
// pool of workers equals `logic-lfd bench table1 --json` on the same tasks and seed once the
// wall-clock fields are zeroed; the CSV has one row per method × level; a click on an episode
// replays it on the Run tab; Cancel stops every worker of the pool.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { existsSync, statSync } from 'node:fs';
import { readFile } from 'node:fs/promises';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { currentFrame, openApp, root, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

/** The CLI: target/release or target/debug, whichever exists, the newer if both. */
function cli() {
  const found = ['release', 'debug']
    .map((p) => join(root, 'target', p, 'logic-lfd'))
    .filter((p) => existsSync(p))
    .sort((a, b) => statSync(b).mtimeMs - statSync(a).mtimeMs);
  assert.ok(found.length, 'build the CLI first: cargo build -p logic-lfd --bin logic-lfd');
  return found[0];
}

/** Table I without its wall-clock fields: every first plan's time and its search and binding
 * parts (`plan_ms`, `search_ms`, `bind_ms` of each cell) become 0, keeping how many there are. */
function zeroed(table) {
  const zero = (v) => v.map(() => 0);
  return { ...table, cells: table.cells.map((c) => ({ ...c, plan_ms: zero(c.plan_ms), search_ms: zero(c.search_ms), bind_ms: zero(c.bind_ms) })) };
}

async function download(page, selector) {
  const [d] = await Promise.all([page.waitForEvent('download'), page.click(selector)]);
  return readFile(await d.path(), 'utf8');
}

async function runExperiment(page, tasks, seed) {
  await page.click('#tab-compare');
  await page.waitForSelector('#experiment-run');
  await page.fill('#experiment-tasks', String(tasks));
  await page.fill('#experiment-seed', String(seed));
  await page.click('#experiment-run');
}

describe('compare experiment', () => {
  test('B1 tasks 0–5, seed 1: the exported JSON is bench table1 --json but for the wall clock; CSV per method × level; a row replays', async () => {
    const cliRun = promisify(execFile)(cli(), ['bench', 'table1', '--tasks', '6', '--seed', '1', '--benchmarks', 'b1', '--json'], { maxBuffer: 1 << 24 });
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&autoplay=0');
    await runExperiment(page, 6, 1);
    await page.waitForSelector('#experiment[data-done="true"]', { timeout: 120000 });
    assert.equal(await page.textContent('#experiment-progress-text'), '6/6 tasks');
    const cliTable = JSON.parse((await cliRun).stdout);
    const pageTable = JSON.parse(await download(page, '#experiment-json'));
    assert.deepEqual(zeroed(pageTable), zeroed(cliTable));
    // The first plan's time is split into search and binding for every planning run.
    for (const c of pageTable.cells) assert.equal(c.search_ms.length, c.plan_ms.length);

    const lines = (await download(page, '#experiment-csv')).trim().split('\n');
    assert.match(lines[0], /^benchmark,method,level,successes,tasks,success_rate,ci95_low,ci95_high,.*replans_after_first_mean,failures_logic,failures_motion,failures_budget$/);
    const rows = lines.slice(1).map((l) => l.split(','));
    const methods = ['linear', 'tamp', 'logic-lfd (paper)', 'logic-lfd (prioritised)'];
    const levels = ['l1', 'l2', 'l3', 'l4'];
    assert.deepEqual(rows.map((r) => `${r[1]}|${r[2]}`).sort(), methods.flatMap((m) => levels.map((l) => `${m}|${l}`)).sort());
    for (const m of methods) {
      const cell = cliTable.cells.find((c) => (c.method === 'logic-lfd' ? `logic-lfd (${c.mode})` : c.method) === m);
      const mine = rows.filter((r) => r[1] === m);
      assert.equal(mine.reduce((a, r) => a + Number(r[3]), 0), cell.successes, `${m}: successes over the levels`);
      assert.equal(mine.reduce((a, r) => a + Number(r[4]), 0), cell.tasks, `${m}: tasks over the levels`);
      for (const r of mine) assert.ok(Number(r[6]) <= Number(r[5]) && Number(r[5]) <= Number(r[7]), `${m} ${r[2]}: the rate lies in its interval`);
    }
    // Linear never replans: re-plans after the first are 0 for it.
    assert.deepEqual(pageTable.cells[0].replans, [0, 0, 0, 0, 0, 0]);

    // The results: the success table, the box plot and one episode row per task and method.
    assert.equal(await page.locator('#experiment-success tbody tr').count(), 16 + 4);
    assert.ok((await page.locator('#experiment-boxplot g[data-method]').count()) >= 3);
    assert.equal(await page.locator('#experiment-episodes tbody tr').count(), 24);
    await page.locator('#experiment-results').scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(screenshots, 'compare-1440.png') });
    await page.setViewportSize({ width: 1024, height: 768 });
    await page.locator('#experiment-success').scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(screenshots, 'compare-1024.png') });

    // A click on TAMP's episode from task 2 replays it on the Run tab: that task, seed and method.
    const row = page.locator('#experiment-episodes tr[data-index="2"][data-run="1"]');
    const won = (await row.locator('td').nth(3).textContent()).startsWith('✓');
    await row.click();
    await page.waitForSelector('#panel-run:not([hidden])', { timeout: 60000 });
    await page.waitForFunction(() => window.lfd.frame()?.status.kind === 'done' || window.lfd.frame()?.status.kind === 'failed', null, { timeout: 60000 });
    const f = await currentFrame(page);
    assert.equal(f.status.kind, won ? 'done' : 'failed');
    assert.equal(await page.inputValue('#method'), 'tamp');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Cancel stops every worker of the pool', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&autoplay=0');
    await runExperiment(page, 200, 3);
    await page.waitForFunction(() => /^[1-9]\d*\/200 tasks$/.test(document.querySelector('#experiment-progress-text')?.textContent ?? ''), null, { timeout: 60000 });
    const during = page.workers().filter((w) => w.url().includes('experiment-worker')).length;
    assert.ok(during >= 1, 'the pool runs in workers of its own');
    await page.click('#experiment-cancel');
    await page.waitForSelector('#experiment[data-done="cancelled"]', { timeout: 5000 });
    const stopped = await page.textContent('#experiment-progress-text');
    await new Promise((r) => setTimeout(r, 1500));
    assert.deepEqual(page.workers().filter((w) => w.url().includes('experiment-worker')), [], 'no worker of the pool is left');
    assert.equal(await page.textContent('#experiment-progress-text'), stopped, 'the progress stands still');
    assert.match(await page.textContent('#experiment-note'), /Cancelled after \d+\/200 tasks/);
    assert.equal(await page.isEnabled('#experiment-run'), true);
    assert.equal(await page.isDisabled('#experiment-json'), true, 'a cancelled run exports nothing');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('on a phone (390 × 844, touch) the experiment runs and its results fit the width', async () => {
    const page = await ctx.browser.newPage({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
    await page.goto(`${ctx.server.url}?benchmark=b1&seed=1&autoplay=0`);
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
    await runExperiment(page, 2, 1);
    await page.waitForSelector('#experiment[data-done="true"]', { timeout: 60000 });
    const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
    assert.ok(overflow <= 0, `the page scrolls sideways by ${overflow} px`);
    await page.locator('#experiment-results').scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(screenshots, 'compare-phone.png') });
    await page.close();
  });
});
