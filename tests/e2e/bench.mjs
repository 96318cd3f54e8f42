// Measures the page's targets in Chromium (reported in the README, never asserted):
//   * the whole page's size gzipped (wasm + JS + CSS + HTML of web/dist);
//   * time from navigation to interactive (the wasm loaded in the worker and the first frame drawn);
//   * the worker's closed-loop tick (Session::step, replans included) over a B1 run with drags;
//   * Logic-LfD replanning time in wasm on B1 (from the frames' lastReplan.timeMs);
//   * Cancel: five clicks while B1 executes, the times until the worker drops the plan and until
//     the page hears back (clocks compared through performance.timeOrigin); and, while a 60-block
//     blind BFS runs in the PDDL editor's worker, the main thread's longest stall, a click's
//     handling time and the robot's ticks in 1.5 s (beside the same with no search), and the time
//     Cancel takes to stop that search.
// Usage: node tests/e2e/bench.mjs [--benchmark b1] [--runs 3] [--blocks N]
// (--blocks: the benchmark's generated N-block tower task instead of its template.)
import { bigBlocks, dist, ipcBlocks, launch, openPage, serve } from './harness.mjs';
import { pageSizes } from './page-size.mjs';

const arg = (k, d) => {
  const i = process.argv.indexOf(`--${k}`);
  return i > 0 ? process.argv[i + 1] : d;
};
const benchmark = arg('benchmark', 'b1');
const runs = Number(arg('runs', '3'));
const blocks = arg('blocks', undefined);
if (blocks !== undefined && !/^\d+$/.test(blocks)) throw new Error(`--blocks must be a whole number, got ${blocks}`);
// A taller tower takes longer to build: the run's time limit grows with it.
const doneTimeout = 120000 * Math.max(1, Number(blocks ?? 4) / 4);

const sizes = () => pageSizes(dist);

const pct = (xs, p) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor((p / 100) * s.length))] : NaN;
};

const server = await serve();
const browser = await launch();
const size = await sizes();
const results = [];
for (let r = 0; r < runs; r++) {
  const { page } = await openPage(browser, `${server.url}?benchmark=${benchmark}&seed=${r + 1}${blocks ? `&blocks=${blocks}` : ''}`);
  await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
  const interactiveMs = await page.evaluate(() => window.lfd.loadedAt);
  // Disturb the run so that Logic-LfD replans: L3 twice (unseen states), L4 once (a new block).
  for (const [t, level] of [[1, 'l3'], [4, 'l4'], [7, 'l3']]) {
    await page.waitForFunction((t) => (window.lfd.frame()?.t ?? 0) > t, t, { timeout: 60000 });
    await page.click(`#inject-${level}`);
  }
  await page.waitForFunction(() => ['done', 'failed'].includes(window.lfd.frame()?.status.kind), null, { timeout: doneTimeout });
  const out = await page.evaluate(() => ({
    steps: window.lfd.stepTimes(),
    replans: window.lfd.replans().map(([, ms]) => ms),
    status: window.lfd.frame().status,
  }));
  results.push({ interactiveMs, ...out });
  await page.close();
}

/** Five Cancel clicks while B1 executes: ms from click to the worker dropping the plan, and to the reply. */
async function cancelTimes() {
  // Quarter speed: the episode outlasts the five cancels.
  const { page } = await openPage(browser, `${server.url}?benchmark=b1&seed=2&speed=0.25`);
  await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
  const applied = [];
  const replied = [];
  for (let round = 0; round < 5; round++) {
    await page.waitForFunction(() => window.lfd.frame()?.executing != null && window.lfd.frame().status.kind === 'executing', null, {
      timeout: 60000,
      polling: 10,
    });
    await page.waitForSelector('#cancel:not([disabled])', { timeout: 60000 });
    const before = await page.evaluate(() => window.lfd.lastCancel());
    await page.click('#cancel');
    await page.waitForFunction((prev) => window.lfd.lastCancel() !== null && window.lfd.lastCancel().clickedAt !== prev?.clickedAt, before, {
      polling: 10,
    });
    const c = await page.evaluate(() => window.lfd.lastCancel());
    applied.push(c.appliedAt - c.clickedAt);
    replied.push(c.repliedAt - c.clickedAt);
  }
  await page.close();
  return { applied, replied };
}

/** The page while the editor's worker runs a search that cannot finish, beside the page at rest. */
async function editorSearch() {
  const { page } = await openPage(browser, `${server.url}?benchmark=b1&seed=1`);
  await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
  await page.evaluate(([d, p]) => window.lfd.setPddl(d, p), [await ipcBlocks('domain.pddl'), bigBlocks(60)]);
  await page.selectOption('#pddl-search', 'bfs');
  await page.selectOption('#pddl-heuristic', 'blind');
  await page.click('#pddl-plan');
  await page.waitForSelector('#pddl-cancel:not([hidden])');
  const probe = () =>
    page.evaluate(async () => {
      const tick0 = window.lfd.frame().tick;
      let maxGap = 0;
      let last = performance.now();
      const end = last + 1500;
      while (performance.now() < end) {
        await new Promise((r) => setTimeout(r, 5));
        const now = performance.now();
        maxGap = Math.max(maxGap, now - last);
        last = now;
      }
      const t0 = performance.now();
      document.getElementById('help').click();
      await new Promise((r) => requestAnimationFrame(r));
      const clickMs = performance.now() - t0;
      document.getElementById('help-close').click();
      return { maxGap, clickMs, ticks: window.lfd.frame().tick - tick0 };
    });
  const busy = await probe();
  const cancelMs = await page.evaluate(async () => {
    const t0 = performance.now();
    document.getElementById('pddl-cancel').click();
    while (!document.getElementById('pddl-stopped')) await new Promise((r) => setTimeout(r, 0));
    return performance.now() - t0;
  });
  const quiet = await probe();
  await page.close();
  return { busy, quiet, cancelMs };
}

const cancel = await cancelTimes();
const editor = await editorSearch();
await browser.close();
await server.close();

const steps = results.flatMap((r) => r.steps);
const replans = results.flatMap((r) => r.replans);
const summary = {
  benchmark,
  blocks: blocks === undefined ? null : Number(blocks),
  runs,
  page_gzip_kb: +(size.gz / 1024).toFixed(1),
  page_raw_kb: +(size.raw / 1024).toFixed(1),
  initial_load_gzip_kb: +((size.gz - size.lazyGz) / 1024).toFixed(1),
  interactive_ms_median: +pct(results.map((r) => r.interactiveMs), 50).toFixed(0),
  tick_ms_median: +pct(steps, 50).toFixed(3),
  tick_ms_p95: +pct(steps, 95).toFixed(3),
  tick_ms_max: +Math.max(...steps).toFixed(3),
  replan_ms_median: +pct(replans, 50).toFixed(3),
  replan_ms_max: replans.length ? +Math.max(...replans).toFixed(3) : null,
  replans: replans.length,
  outcomes: results.map((r) => r.status.kind),
  cancel_applied_ms: cancel.applied.map((t) => +t.toFixed(1)),
  cancel_replied_ms: cancel.replied.map((t) => +t.toFixed(1)),
  editor_search_max_stall_ms: +editor.busy.maxGap.toFixed(1),
  editor_idle_max_stall_ms: +editor.quiet.maxGap.toFixed(1),
  editor_search_click_ms: +editor.busy.clickMs.toFixed(1),
  editor_idle_click_ms: +editor.quiet.clickMs.toFixed(1),
  editor_search_robot_ticks_1500ms: editor.busy.ticks,
  editor_idle_robot_ticks_1500ms: editor.quiet.ticks,
  editor_search_cancel_ms: +editor.cancelMs.toFixed(1),
};
console.log(JSON.stringify(summary, null, 2));
console.log('\n| file | bytes | gzipped |\n|---|---:|---:|');
for (const r of size.rows) console.log(`| ${r.file} | ${r.raw} | ${r.gz} |`);
