// Measures the page's targets in Chromium (reported in the README, never asserted):
//   * the whole page's size gzipped (wasm + JS + CSS + HTML of web/dist);
//   * time from navigation to interactive (the wasm loaded in the worker and the first frame drawn);
//   * the worker's closed-loop tick (Session::step, replans included) over a B1 run with drags;
//   * Logic-LfD replanning time in wasm on B1 (from the frames' lastReplan.timeMs).
// Usage: node tests/e2e/bench.mjs [--benchmark b1] [--runs 3] [--blocks N]
// (--blocks: the benchmark's generated N-block tower task instead of its template.)
import { dist, launch, openPage, serve } from './harness.mjs';
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
};
console.log(JSON.stringify(summary, null, 2));
console.log('\n| file | bytes | gzipped |\n|---|---:|---:|');
for (const r of size.rows) console.log(`| ${r.file} | ${r.raw} | ${r.gz} |`);
