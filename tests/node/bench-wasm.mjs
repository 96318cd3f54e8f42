// Native against wasm on the hot paths, side by side in one run (not a test: `npm run bench:wasm
// -- [--warmup W] [--warmup-secs S] [--runs N] [--budget S] [--only id,…] [--pkg DIR]
// [--logistics NAME] [--tiering]`).
//
// Both sides run the same Rust code on the same inputs (crate/src/experiments/hot_paths.rs): the
// native side through `logic-lfd bench wasm-rows --json` (env LOGIC_LFD_BIN, else
// target/release/logic-lfd), the wasm side through the npm package's `benchRows` (pkg/node, or
// --pkg), each timing inside its own build with its own clock: the best of N runs (default 100;
// fewer once the row has spent --budget seconds, default 3; at least 3) after at least W untimed
// warm-up runs (default 2) and at least S seconds of them.
// The wasm side runs V8's optimising compiler from the first call (`--no-liftoff`), so the rows
// compare compiled code with compiled code, as a page or server reaches once its hot code has
// tiered up. With --tiering, V8 keeps its default: baseline code first, a hot function compiled
// again by the optimising tier in the background after it has run a while (S defaults to 1 s
// there; a row of a few microseconds still times baseline code after a handful of runs, and on a
// loaded machine the background compiles can lag by seconds).
// The rows' digests (plan costs, expansions, facts) must agree, so both sides did the same work.
// Then one row per planning problem for the whole `plan()` call from JavaScript (options and the
// outcome object cross the boundary), the page benchmark's replans through the JavaScript
// `Session` of the page's first-load module and of the npm package, and the gzipped sizes of the
// wasm modules and of the page's first load (web/dist, measured as tests/e2e/bench.mjs does, when
// the page is built).
import { execFileSync } from 'node:child_process';
import v8 from 'node:v8';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { gzipSync } from 'node:zlib';
import { pageSizes } from '../e2e/page-size.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const arg = (name, d) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : d;
};
const TIERING = process.argv.includes('--tiering');
// Before any wasm module is compiled (the modules are imported below).
if (!TIERING) v8.setFlagsFromString('--no-liftoff');
const WARMUP = Math.max(1, Number(arg('warmup', 2)));
const WARMUP_SECS = Math.max(0, Number(arg('warmup-secs', TIERING ? 1 : 0)));
// Many short runs: on a shared machine a run often loses its core for a while, on both sides.
const RUNS = Number(arg('runs', 100));
const BUDGET = Number(arg('budget', 3));
const ONLY = arg('only', '');
const PKG = arg('pkg', join(root, 'pkg/node'));
const LOGISTICS = arg('logistics', 'probLOGISTICS-10-0');
// The vendored IPC benchmarks; `--ipc DIR` points at another copy with the same folders.
const IPC = arg('ipc', join(root, 'tests/data/ipc'));

const lfd = await import(new URL(`file://${join(PKG, 'index.mjs')}`).href);
const read = (dir, file) => readFileSync(join(IPC, dir, file), 'utf8');
const inputs = {
  blocksDomain: read('blocks', 'domain.pddl'),
  blocks8: read('blocks', 'probBLOCKS-8-0.pddl'),
  blocks9: read('blocks', 'probBLOCKS-9-0.pddl'),
  logisticsDomain: read('logistics00', 'domain.pddl'),
  logistics: read('logistics00', `${LOGISTICS}.pddl`),
  logisticsName: LOGISTICS,
};
const only = ONLY ? ONLY.split(',') : [];

const bin = process.env.LOGIC_LFD_BIN || join(root, 'target/release/logic-lfd');
if (!existsSync(bin)) throw new Error(`${bin} missing: cargo build --release -p logic-lfd --bin logic-lfd`);
const nativeArgs = ['bench', 'wasm-rows', '--ipc', IPC, '--logistics', LOGISTICS, '--warmup', String(WARMUP), '--warmup-secs', String(WARMUP_SECS), '--runs', String(RUNS), '--budget', String(BUDGET), '--json'];
if (only.length) nativeArgs.push('--only', only.join(','));
process.stderr.write('bench:wasm: native rows…\n');
const native = JSON.parse(execFileSync(bin, nativeArgs, { encoding: 'utf8', maxBuffer: 1 << 26 }));
process.stderr.write('bench:wasm: wasm rows…\n');
const wasm = lfd.benchRows(inputs, { warmup: WARMUP, warmupSecs: WARMUP_SECS, runs: RUNS, budgetSecs: BUDGET, only });

const fmt = (ms) => (ms >= 100 ? `${(ms / 1e3).toFixed(2)} s` : ms >= 0.1 ? `${ms.toFixed(2)} ms` : `${(ms * 1e3).toFixed(1)} µs`);
const tier = TIERING ? "V8's default tiering" : 'optimising tier from the first call';
console.log(`logic-lfd ${lfd.version()}: native (${bin.replace(root, '')}) against wasm (${PKG.replace(root, '')}, node ${process.version}, ${tier}), best of ≤ ${RUNS} after ≥ ${WARMUP} warm-up run${WARMUP > 1 ? 's' : ''} and ≥ ${WARMUP_SECS} s of them\n`);
console.log('| work | native | wasm (node) | wasm / native |');
console.log('|---|---:|---:|---:|');
const ratios = [];
for (const n of native) {
  const w = wasm.find((r) => r.id === n.id);
  if (!w) throw new Error(`wasm has no row ${n.id}`);
  if (w.digest !== n.digest) throw new Error(`${n.id}: different work natively (${n.digest}) and in wasm (${w.digest})`);
  const ratio = w.best_ms / n.best_ms;
  ratios.push(ratio);
  console.log(`| ${n.label} | ${fmt(n.best_ms)} | ${fmt(w.best_ms)} | ${ratio.toFixed(2)}× |`);
}
const geo = Math.exp(ratios.reduce((a, r) => a + Math.log(r), 0) / ratios.length);
console.log(`| geometric mean | | | ${geo.toFixed(2)}× |`);

// The whole `plan()` call from JavaScript (parse + ground + search + the outcome object), the
// same discipline: WARMUP warm-up runs and WARMUP_SECS of them, best of RUNS (fewer once BUDGET
// seconds are spent, at least 3).
function warmUp(f) {
  const t0 = performance.now();
  for (let i = 0; i < WARMUP || performance.now() - t0 < WARMUP_SECS * 1e3; i++) f();
}
function bestOf(f) {
  warmUp(f);
  const t0 = performance.now();
  let best = Infinity;
  for (let i = 0; i < RUNS && (i < 3 || performance.now() - t0 < BUDGET * 1e3); i++) {
    const t = performance.now();
    f();
    best = Math.min(best, performance.now() - t);
  }
  return best;
}
/** @type {[string, string, string, { search: string, heuristic: string }][]} */
const calls = [
  ['astar-lmcut-blocks-8-0', inputs.blocksDomain, inputs.blocks8, { search: 'astar', heuristic: 'lmcut' }],
  ['astar-lmcut-blocks-9-0', inputs.blocksDomain, inputs.blocks9, { search: 'astar', heuristic: 'lmcut' }],
  ['gbfs-hff-blocks-9-0', inputs.blocksDomain, inputs.blocks9, { search: 'lazy-gbfs', heuristic: 'hff' }],
  ['gbfs-hff-logistics', inputs.logisticsDomain, inputs.logistics, { search: 'lazy-gbfs', heuristic: 'hff' }],
];
const timedCalls = calls.filter(([id]) => native.some((n) => n.id === id));
if (timedCalls.length) {
  console.log('\n| `plan()` from JavaScript | native row | `plan()` call | call / native |');
  console.log('|---|---:|---:|---:|');
  for (const [id, d, p, o] of timedCalls) {
    const n = native.find((r) => r.id === id);
    const ms = bestOf(() => {
      const r = lfd.plan(d, p, { ...o, timeLimitMs: 600_000 });
      if (!r.ok) throw new Error(`${id}: ${r.message}`);
    });
    console.log(`| ${n.label} | ${fmt(n.best_ms)} | ${fmt(ms)} | ${(ms / n.best_ms).toFixed(2)}× |`);
  }
}

// The page benchmark's scenario through the JavaScript `Session` of the page's first-load module
// (pkg/page, what the page's worker runs) and of the npm package: each replan's best time over the
// passes (after WARMUP warm-up passes), as the frames' `lastReplan.timeMs` report it; the median.
async function sessionReplans(mod) {
  const pass = () => {
    const times = [];
    for (const seed of [1, 2, 3]) {
      const s = new mod.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed });
      const inject = [[1, 'l3'], [4, 'l4'], [7, 'l3']];
      let f = s.frame();
      let last = null;
      while (!['done', 'failed'].includes(f.status.kind)) {
        if (inject.length && f.t > inject[0][0]) s.inject(inject.shift()[1]);
        f = s.step(1 / 60);
        const r = f.lastReplan;
        if (r && r.tick !== last) {
          last = r.tick;
          times.push(r.timeMs);
        }
      }
      s.free();
    }
    return times;
  };
  const t0w = performance.now();
  const best = pass();
  for (let i = 1; i < WARMUP || performance.now() - t0w < WARMUP_SECS * 1e3; i++) pass();
  const t0 = performance.now();
  for (let i = 0; i < RUNS && (i < 3 || performance.now() - t0 < BUDGET * 1e3); i++) {
    pass().forEach((ms, k) => (best[k] = Math.min(best[k], ms)));
  }
  const s = [...best].sort((a, b) => a - b);
  return { median: s[s.length >> 1], n: s.length };
}
const pageRow = native.find((r) => r.id === 'page-replans-b1');
const pageJs = join(root, 'pkg/page/logic_lfd.js');
if (pageRow && existsSync(pageJs)) {
  const page = await import(new URL(`file://${pageJs}`).href);
  page.initSync({ module: readFileSync(join(root, 'pkg/page/logic_lfd_bg.wasm')) });
  console.log('\n| the page benchmark\'s B1 replans through `Session` (median of each replan\'s best) | native row | module | module / native |');
  console.log('|---|---:|---:|---:|');
  for (const [what, mod] of [["page's first-load module (pkg/page)", page], ['npm package (pkg/node)', lfd]]) {
    const r = await sessionReplans(mod);
    console.log(`| ${what}, ${r.n} replans | ${fmt(pageRow.best_ms)} | ${fmt(r.median)} | ${(r.median / pageRow.best_ms).toFixed(2)}× |`);
  }
}

const gz = (f) => gzipSync(readFileSync(f), { level: 9 }).length;
const kib = (b) => `${(b / 1024).toFixed(1)} KiB`;
console.log('\n| size | bytes | gzipped |\n|---|---:|---:|');
for (const [what, f] of [
  ['npm package module (pkg/node, pkg/web)', join(PKG, 'logic_lfd_bg.wasm')],
  ["page's first-load module (pkg/page/logic_lfd_bg.wasm)", join(root, 'pkg/page/logic_lfd_bg.wasm')],
  ["page's Teach-mode module (pkg/page/logic_lfd_teach_bg.wasm)", join(root, 'pkg/page/logic_lfd_teach_bg.wasm')],
]) {
  if (existsSync(f)) console.log(`| ${what} | ${readFileSync(f).length} | ${kib(gz(f))} |`);
}
const dist = join(root, 'web/dist');
if (existsSync(dist)) {
  const s = await pageSizes(dist);
  console.log(`| page first load (web/dist without its lazy chunks) | | ${kib(s.gz - s.lazyGz)} |`);
  console.log(`| whole page (web/dist) | ${s.raw} | ${kib(s.gz)} |`);
}
