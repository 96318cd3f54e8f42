// A task folder that is not a benchmark (B1 in the paper's naming, domains/b1-paper-naming) opened
// on the page: served beside it (?folder=URL), picked as a directory, as several files and as a
// saved run; run to success under an L3; its PDDL in the PDDL tab; Save, Load and Link; and a
// broken folder's error naming the file.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { currentFrame, finish, openApp, root, screenshots, useBrowser } from './harness.mjs';
import { dragBody, dropPoint } from './ux-helpers.mjs';

const ctx = useBrowser({ withScreenshots: true });

const DIR = join(root, 'domains', 'b1-paper-naming');
/** The folder's files by name. */
const FILES = Object.fromEntries(readdirSync(DIR).map((n) => [n, readFileSync(join(DIR, n), 'utf8')]));
const SORTING_DIR = join(root, 'domains', 'sorting');
const SORTING = Object.fromEntries(readdirSync(SORTING_DIR).map((n) => [n, readFileSync(join(SORTING_DIR, n), 'utf8')]));
const TOWER = ['(on-block a b)', '(on-block b c)', '(on-block c d)'];

/** Serves `files` (name → text) at `/task-folders/NAME/` beside the page; other names are 404. */
async function serveFolder(page, name, files) {
  await page.route(`**/task-folders/${name}/*`, (route) => {
    const file = decodeURIComponent(new URL(route.request().url()).pathname.split('/').pop() ?? '');
    if (!(file in files)) return route.fulfill({ status: 404, body: 'not found' });
    return route.fulfill({ status: 200, contentType: file.endsWith('.json') ? 'application/json' : 'text/plain', body: files[file] });
  });
}

/** Opens the page on `query` after routing the folder `name` (the page fetches it on load). */
async function openWithFolder(name, files, query) {
  const page = await ctx.browser.newPage({ viewport: { width: 1440, height: 900 } });
  const errors = [];
  page.on('console', (m) => {
    // The folder's absent optional files (demo.plan, README.md) are 404s the browser logs.
    if (m.type() === 'error' && !/404/.test(m.text())) errors.push(m.text());
  });
  page.on('pageerror', (e) => errors.push(String(e)));
  await serveFolder(page, name, files);
  await page.goto(`${ctx.server.url}${query}`);
  await page.waitForSelector('#app[data-ready="true"]', { timeout: 60000 });
  return { page, errors };
}

/** Waits until the robot has executed `n` actions of its plan. */
async function executing(page, n) {
  await page.waitForFunction((k) => (window.lfd.frame()?.executing ?? -1) >= k, n, { timeout: 60000, polling: 100 });
}

/** A saved run: clicks Save and returns the downloaded JSON's text and path. */
async function save(page) {
  const download = page.waitForEvent('download');
  await page.click('#save-scene');
  const d = await download;
  const path = await d.path();
  return { name: d.suggestedFilename(), text: readFileSync(path, 'utf8') };
}

const fileOf = (name, text, mimeType = 'text/plain') => ({ name, mimeType, buffer: Buffer.from(text) });

describe('task folder on the page', () => {
  test('the gallery tasks in the benchmark select open from beside the page and run to success', async () => {
    const page = await ctx.browser.newPage({ viewport: { width: 1440, height: 900 } });
    const errors = [];
    page.on('console', (m) => {
      // A gallery folder's absent optional files (demo.plan) are 404s the browser logs.
      if (m.type() === 'error' && !/404/.test(m.text())) errors.push(m.text());
    });
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`${ctx.server.url}?benchmark=b1&autoplay=0`);
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 60000 });
    const goals = {
      'tasks/sorting': ['(on r1 r2)', '(at r2 red-tray)', '(on b1 b2)', '(at b2 blue-tray)'],
      'tasks/shelf-tower': ['(on a b)', '(on b c)', '(onshelf c)', '(ontable d)'],
    };
    for (const [value, goal] of Object.entries(goals)) {
      await page.selectOption('#benchmark', value);
      await page.waitForFunction((v) => document.getElementById('task-tag')?.textContent?.includes(v), value, { timeout: 60000 });
      assert.equal(await page.inputValue('#benchmark'), 'folder');
      if ((await page.getAttribute('#play', 'aria-pressed')) !== 'true') await page.click('#play');
      const f = await finish(page);
      assert.equal(f.status.kind, 'done', `${value}: ${f.status.message}`);
      for (const g of goal) assert.ok(f.facts.includes(g), `${value}: ${g} missing from ${f.facts.join(' ')}`);
    }
    await page.screenshot({ path: join(screenshots, 'gallery-shelf-tower-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Teach records in the open folder; Run runs the taught task there and keeps the folder', async () => {
    const { page, errors } = await openWithFolder('sorting', SORTING, '?folder=task-folders/sorting&autoplay=0');
    await page.click('#tab-teach');
    await page.click('#teach-record');
    await page.waitForFunction(() => window.lfdTeach.state() !== null);
    assert.equal(await page.evaluate(() => window.lfdTeach.state().folder), 'task-folders/sorting');
    assert.match(await page.textContent('#status'), /Teaching task-folders\/sorting/);
    // r2 from the pile into the red tray: the folder domain's actions, with its regions.
    await dragBody(page, 'r2', await dropPoint(page, [0.39, 0.32]));
    await page.waitForFunction(() => !window.lfdTeach.busy() && window.lfdTeach.state()?.segments.length === 2, null, { timeout: 20000, polling: 50 });
    assert.deepEqual(
      await page.evaluate(() => window.lfdTeach.state().segments.map((s) => s.action)),
      ['(unstack panda r2 b2 pile)', '(place panda r2 red-tray)'],
    );
    await page.click('#teach-stop');
    await page.waitForSelector('#teach-run-box:not([hidden])');
    assert.equal(await page.evaluate(() => window.lfdTeach.info().folder), 'task-folders/sorting');
    await page.screenshot({ path: join(screenshots, 'teach-folder-stopped.png') });
    await page.click('#teach-run');
    await page.waitForFunction(() => document.querySelector('#tab-run').classList.contains('active'));
    const f = await finish(page, 60000);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.ok(f.facts.includes('(at r2 red-tray)'), f.facts.join(' '));
    // The Run ran the taught task in the folder's workcell; the folder stays open. The benchmark
    // select names the taught task, the goal is its own, the top bar keeps to one row and the
    // link keeps the folder.
    assert.equal(await page.inputValue('#benchmark'), 'taught');
    assert.match(await page.getAttribute('#benchmark option[value="taught"]', 'title'), /sorting/);
    assert.ok(await page.$('#benchmark option[value="folder"]'), 'the folder stays open');
    assert.equal(await page.isDisabled('#blocks'), true);
    assert.match(await page.textContent('#goal'), /r2 at red-tray/);
    assert.ok((await page.$eval('.topbar', (e) => e.getBoundingClientRect().height)) < 50);
    assert.equal(new URL(page.url()).searchParams.get('folder'), 'task-folders/sorting');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('?folder=URL opens a folder of its own names: it runs, survives an L3, shows its PDDL and keeps its link', async () => {
    const { page, errors } = await openWithFolder('paper-naming', FILES, '?folder=task-folders/paper-naming');
    assert.equal(await page.inputValue('#benchmark'), 'folder');
    assert.match(await page.textContent('#task-tag'), /task folder · task-folders\/paper-naming/);
    assert.match(await page.textContent('#benchmark option[value="folder"]'), /folder · paper-naming/);
    const first = await currentFrame(page);
    assert.ok(first.demo.every((a) => /^\((pick-up|put-down|put-on|take-off) /.test(a)), first.demo.join(' '));

    await executing(page, 2);
    await page.click('#inject-l3');
    await page.waitForFunction(() => window.lfd.marks().some((m) => m.kind === 'l3'), null, { timeout: 10000 });
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);
    for (const g of TOWER) assert.ok(f.facts.includes(g), `${g} missing from ${f.facts.join(' ')}`);
    assert.ok(f.replans >= 2, `replans: ${f.replans}`);
    await page.screenshot({ path: join(screenshots, 'folder-run-1440.png') });

    // The PDDL tab holds the folder's own domain and problem.
    await page.click('#tab-pddl');
    const visible = '#panel-pddl .cm-host:not([hidden]) .cm-content';
    await page.waitForFunction((sel) => document.querySelector(sel)?.textContent.includes('take-off'), visible, { timeout: 30000 });
    await page.click('#pddl-tab-problem');
    await page.waitForFunction((sel) => document.querySelector(sel)?.textContent.includes('on-block'), visible);
    await page.screenshot({ path: join(screenshots, 'folder-pddl-1440.png') });

    // The link keeps the folder's URL (and no benchmark).
    await page.click('#permalink');
    await page.waitForFunction(() => new URLSearchParams(location.search).get('folder') === 'task-folders/paper-naming');
    assert.equal(new URLSearchParams(new URL(page.url()).search).get('benchmark'), null);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a picked directory runs; Save writes the run with its files and Load restores the folder; Link says Save', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0');
    // The benchmark select's last item opens the directory picker.
    const chooser = page.waitForEvent('filechooser');
    await page.selectOption('#benchmark', 'open-folder');
    const picker = await chooser;
    assert.equal(await picker.element().getAttribute('id'), 'folder-dir');
    await picker.setFiles(DIR);
    await page.waitForFunction(() => document.getElementById('task-tag')?.textContent?.includes('b1-paper-naming'), null, { timeout: 60000 });
    assert.equal(await page.inputValue('#benchmark'), 'folder');
    assert.ok(await page.isDisabled('#blocks'));
    await page.click('#play');
    await executing(page, 1);
    await page.click('#inject-l3');
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);

    // An uploaded folder has no address: Link says so and offers Save.
    await page.click('#permalink');
    await page.waitForSelector('#notice:not([hidden])');
    assert.match(await page.textContent('#notice'), /A link cannot carry the files of \.\/b1-paper-naming.*Save keeps the run/);

    const saved = await save(page);
    assert.equal(saved.name, 'b1-paper-naming-run.json');
    const log = JSON.parse(saved.text);
    assert.equal(log.folder.dir, './b1-paper-naming');
    assert.deepEqual(log.folder.files, FILES);
    assert.ok(log.events.some((e) => e.event === 'inject' && e.level === 'l3'));
    await page.close();

    // A fresh page loads the saved run: the folder comes back and the run replays to its end.
    const again = await openApp(ctx.browser, ctx.server, '?benchmark=b2&autoplay=0');
    await again.page.setInputFiles('#load-file', fileOf(saved.name, saved.text, 'application/json'));
    await again.page.waitForFunction(() => document.getElementById('task-tag')?.textContent?.includes('b1-paper-naming'), null, { timeout: 60000 });
    const replayed = await currentFrame(again.page);
    assert.equal(replayed.status.kind, 'done');
    assert.deepEqual(replayed.facts, f.facts);
    assert.equal(await again.page.inputValue('#benchmark'), 'folder');
    assert.deepEqual(errors, []);
    assert.deepEqual(again.errors, []);
    await again.page.close();
  });

  test('several files and a zip open as a folder; Compare runs its methods on the open folder', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0');
    await page.setInputFiles(
      '#load-file',
      Object.entries(FILES).map(([n, t]) => fileOf(n, t)),
    );
    await page.waitForFunction(() => document.getElementById('task-tag')?.textContent?.includes('task folder · ./upload'), null, { timeout: 60000 });
    const { zipSync, strToU8 } = await import('fflate');
    const zip = zipSync(Object.fromEntries(Object.entries(FILES).map(([n, t]) => [`mine/${n}`, strToU8(t)])));
    await page.setInputFiles('#load-file', { name: 'mine.zip', mimeType: 'application/zip', buffer: Buffer.from(zip) });
    await page.waitForFunction(() => document.getElementById('task-tag')?.textContent?.includes('task folder · ./mine'), null, { timeout: 60000 });

    await page.click('#tab-compare');
    await page.selectOption('#compare-level', 'l3');
    await page.click('#compare-run');
    await page.waitForSelector('.compare[data-done="true"]', { timeout: 300000 });
    assert.match(await page.textContent('#compare-note'), /^task folder \.\/mine · seed 1 · Scramble at /);
    const rows = await page.$$eval('#compare-table tbody tr', (trs) => trs.map((tr) => [tr.querySelector('th')?.textContent, tr.children[1]?.textContent]));
    const lfd = rows.filter(([name]) => name?.startsWith('Logic-LfD'));
    assert.ok(lfd.length >= 1 && lfd.every(([, r]) => r?.includes('success')), JSON.stringify(rows));
    await page.screenshot({ path: join(screenshots, 'folder-compare-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('the PDDL tab of a generated N-block task holds its own problem, not the template', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&blocks=7&autoplay=0');
    await page.click('#tab-pddl');
    await page.click('#pddl-tab-problem');
    const visible = '#panel-pddl .cm-host:not([hidden]) .cm-content';
    // Seven blocks a … g (the template has four, a … d).
    await page.waitForFunction((sel) => /\(:objects[^)]*\bg\b/.test(document.querySelector(sel)?.textContent ?? ''), visible, { timeout: 60000 });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a broken folder is refused naming the file; the Run keeps what it had', async () => {
    // Served without motions.json: the page says which file is missing and opens the benchmark paused.
    const rest = { ...FILES };
    delete rest['motions.json'];
    const served = await openWithFolder('incomplete', rest, '?folder=task-folders/incomplete');
    const text = await served.page.textContent('#status-text');
    assert.match(text, /^Could not open the task folder task-folders\/incomplete: task-folders\/incomplete\/motions\.json: missing: a task folder holds domain\.pddl, problem\.pddl, motions\.json/);
    assert.equal(await served.page.inputValue('#benchmark'), 'b1');
    await served.page.close();

    // Picked files with a broken scene: the error names scene.json; the B1 run goes on as before.
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0');
    const before = await currentFrame(page);
    const broken = { ...FILES, 'scene.json': FILES['scene.json'].replace('"bodies"', '"bodies": 3, "x"') };
    await page.setInputFiles(
      '#load-file',
      Object.entries(broken).map(([n, t]) => fileOf(n, t)),
    );
    await page.waitForSelector('#notice.error:not([hidden])', { timeout: 60000 });
    assert.match(await page.textContent('#notice'), /The task folder \.\/upload was not opened: \.\/upload\/scene\.json: /);
    assert.match(await page.textContent('#status-text'), /Could not open the task folder: \.\/upload\/scene\.json: /);
    assert.equal(await page.inputValue('#benchmark'), 'b1');
    assert.equal(await page.isHidden('#task-tag'), true);
    await page.screenshot({ path: join(screenshots, 'folder-error-1440.png') });
    const after = await currentFrame(page);
    assert.deepEqual(after.world, before.world);
    assert.deepEqual(errors, []);
    await page.close();
  });
});
