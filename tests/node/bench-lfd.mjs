// Timing of Logic-LfD on PDDL domains in wasm under node, against the native CLI when there is
// one (not a test: `npm run bench:lfd -- [--count N] [--seed S] [--domains a,b]`).
//
// For each domain: the demonstration (the domain's demo.plan, or for an IPC problem the plan the
// package's own `plan()` finds with A*/LM-cut, or lazy GBFS/h_FF when that takes more than 30 s),
// `count` states drawn with `logicLfdPerturb` (seed `seed`), then per state one `logicLfd` call in
// paper mode with lazy GBFS + h_FF and `compare: true` (from scratch with the same search).
//
// Columns: "call" is the whole `logicLfd` call (parsing, grounding and the search: the function is
// stateless, so every call re-reads the texts); "search" is `stats.timeMs`, the search alone, which
// is what the native CLI's `summary.median_lfd_ms` measures (it parses and grounds once);
// "LogicLfd.replan" is one call of the class, which read the texts once (the state's atoms, LogicIn,
// the search, the lifted replay of the plan and the result object), timed after a warm-up pass over
// the same states (median over three passes), and its ratio to the native per-call median
// (target ≤ 2×).
// The native column comes from `logic-lfd lfd D P DEMO --perturb N --seed S --mode paper --search
// lazy-gbfs --heuristic hff --json` (env LOGIC_LFD_BIN, else target/release/logic-lfd), when that
// binary has the `lfd` command; its states are checked to be the ones wasm drew.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
const root = fileURLToPath(new URL('../../', import.meta.url));
const arg = (name, d) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : d;
};
const COUNT = Number(arg('count', 200));
const SEED = Number(arg('seed', 1));
const ONLY = arg('domains', '');

const DOMAINS = [
  { name: 'kitchen', dir: 'domains/kitchen', problem: 'problem.pddl', demo: 'demo.plan' },
  { name: 'delivery', dir: 'domains/delivery', problem: 'problem.pddl', demo: 'demo.plan' },
  { name: 'blocks probBLOCKS-8-0', dir: 'tests/data/ipc/blocks', problem: 'probBLOCKS-8-0.pddl' },
  { name: 'gripper prob05', dir: 'tests/data/ipc/gripper', problem: 'prob05.pddl' },
  { name: 'logistics00 probLOGISTICS-6-0', dir: 'tests/data/ipc/logistics00', problem: 'probLOGISTICS-6-0.pddl' },
  { name: 'depot-typed p03', dir: 'tests/data/ipc/depot-typed', problem: 'p03.pddl' },
].filter((d) => !ONLY || ONLY.split(',').some((o) => d.name.includes(o)));

const median = (xs) => {
  if (!xs.length) return NaN;
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
};
const fmt = (x, digits = 2) => (Number.isFinite(x) ? x.toFixed(digits) : 'n/a');

/** The native binary, if it has `lfd --perturb`. */
function nativeBin() {
  const bin = process.env.LOGIC_LFD_BIN || join(root, 'target/release/logic-lfd');
  if (!existsSync(bin)) return null;
  try {
    const help = execFileSync(bin, ['lfd', '--help'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
    return help.includes('--perturb') ? bin : null;
  } catch {
    return null;
  }
}

/** The demonstration of an IPC problem: the package's own optimal plan, or a greedy one. */
function demoFor(domain, problem) {
  const optimal = lfd.plan(domain, problem, { search: 'astar', heuristic: 'lmcut', timeLimitMs: 30_000 });
  if (optimal.ok) return { text: optimal.plan.join('\n'), how: 'astar/lmcut' };
  const greedy = lfd.plan(domain, problem, { search: 'lazy-gbfs', heuristic: 'hff', timeLimitMs: 120_000 });
  if (!greedy.ok) throw new Error(`no demonstration: ${greedy.message}`);
  return { text: greedy.plan.join('\n'), how: 'lazy-gbfs/hff' };
}

const bin = nativeBin();
const tmp = mkdtempSync(join(tmpdir(), 'bench-lfd-'));
const rows = [];
for (const d of DOMAINS) {
  const dir = join(root, d.dir);
  const domainFile = join(dir, 'domain.pddl');
  const problemFile = join(dir, d.problem);
  const domain = readFileSync(domainFile, 'utf8');
  const problem = readFileSync(problemFile, 'utf8');
  let demoFile;
  let demo;
  let how = 'demo.plan';
  if (d.demo) {
    demoFile = join(dir, d.demo);
    demo = readFileSync(demoFile, 'utf8');
  } else {
    ({ text: demo, how } = demoFor(domain, problem));
    demoFile = join(tmp, `${d.name.replace(/\W+/g, '-')}.plan`);
    writeFileSync(demoFile, `${demo}\n`);
  }
  const texts = { domain, problem, demo };
  const drawn = lfd.logicLfdPerturb({ ...texts, count: COUNT, seed: SEED });
  if (!drawn.ok) throw new Error(`${d.name}: ${drawn.message}`);
  const call = [];
  const search = [];
  const scratch = [];
  let failed = 0;
  for (const s of drawn.states) {
    const t0 = performance.now();
    const out = lfd.logicLfd({ ...texts, state: s.facts.join('\n'), mode: 'paper', search: 'lazy-gbfs', heuristic: 'hff', compare: true });
    const ms = performance.now() - t0;
    if (!out.ok || !out.valid) failed++;
    call.push(ms - (out.scratch?.stats.timeMs ?? 0)); // the call without the from-scratch search
    search.push(out.stats.timeMs);
    scratch.push(out.scratch?.stats.timeMs ?? NaN);
  }
  const cls = new lfd.LogicLfd(texts);
  const options = { mode: 'paper', search: 'lazy-gbfs', heuristic: 'hff' };
  for (const s of drawn.states) cls.replan(s.facts, options);
  // Three timed passes: the median over all their calls is steadier on a shared machine. Each
  // state is replanned without the lifted replay (the native time's work) and with it.
  const replan = [];
  const replanValid = [];
  const unchecked = { ...options, validate: false };
  for (let pass = 0; pass < 3; pass++) {
    for (const s of drawn.states) {
      let t0 = performance.now();
      const fast = cls.replan(s.facts, unchecked);
      replan.push(performance.now() - t0);
      t0 = performance.now();
      const out = cls.replan(s.facts, options);
      replanValid.push(performance.now() - t0);
      if (!out.ok || !out.valid) throw new Error(`${d.name}: LogicLfd.replan: ${out.message}`);
      if (fast.plan.join() !== out.plan.join()) throw new Error(`${d.name}: validate changed the plan`);
    }
  }
  cls.free();
  const demoLen = lfd.logicLfd(texts).demo.actions.length;
  let native = { lfd: NaN, scratch: NaN, same: 'n/a' };
  if (bin) {
    const json = JSON.parse(
      execFileSync(
        bin,
        ['lfd', domainFile, problemFile, demoFile, '--perturb', String(COUNT), '--seed', String(SEED), '--mode', 'paper', '--search', 'lazy-gbfs', '--heuristic', 'hff', '--json'],
        { encoding: 'utf8', maxBuffer: 1 << 28 },
      ),
    );
    const same = json.states.length === drawn.states.length && json.states.every((s, i) => JSON.stringify([...s.facts].sort()) === JSON.stringify(drawn.states[i].facts));
    native = { lfd: json.summary.median_lfd_ms, scratch: json.summary.median_scratch_ms, same: same ? 'yes' : 'NO' };
  }
  const row = {
    name: d.name,
    how,
    demoLen,
    nativeLfd: native.lfd,
    nativeScratch: native.scratch,
    wasmSearch: median(search),
    wasmCall: median(call),
    classReplan: median(replan),
    classReplanValid: median(replanValid),
    scratchSearch: median(scratch),
    speedup: median(scratch) / median(search),
    same: native.same,
    failed,
  };
  rows.push(row);
  console.error(`${d.name}: demo ${demoLen} (${how}), ${drawn.states.length} states, ${failed} without a valid plan`);
}

const lines = [
  `Logic-LfD, ${COUNT} states per domain (logicLfdPerturb seed ${SEED}), paper mode, lazy GBFS + h_FF; medians in ms.`,
  '"wasm search" is `stats.timeMs` (the search alone, comparable with native); "wasm call" is the whole',
  'stateless `logicLfd` call without its from-scratch search (parse + ground + LogicIn/search + validate).',
  '"from-scratch" is the same search to G from the same state (`compare: true`, `scratch.stats.timeMs`);',
  'speed-up = from-scratch search / Logic-LfD search, wasm. "failed": states without a valid merged plan (wasm).',
  '"LogicLfd.replan" is one call of the class with `validate: false` (texts read once; state, LogicIn, search, result:',
  'the work the native time measures), median of three passes after a warm-up; "replan/native" is its ratio to the',
  'native Logic-LfD median (target ≤ 2); "with replay" is the default call, which also replays the plan on the lifted domain.',
  '',
  '| domain | demo length | Logic-LfD median ms native | wasm search | wasm/native | wasm call | LogicLfd.replan | replan/native | with replay | from-scratch median native | from-scratch median wasm | speed-up (scratch/lfd) | same states | failed |',
  '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|',
  ...rows.map((r) =>
    `| ${r.name} | ${r.demoLen} (${r.how}) | ${fmt(r.nativeLfd, 3)} | ${fmt(r.wasmSearch, 3)} | ${fmt(r.wasmSearch / r.nativeLfd)} | ${fmt(r.wasmCall, 2)} | ${fmt(r.classReplan, 3)} | ${fmt(r.classReplan / r.nativeLfd)} | ${fmt(r.classReplanValid, 3)} | ${fmt(r.nativeScratch, 3)} | ${fmt(r.scratchSearch, 3)} | ${fmt(r.speedup, 1)} | ${r.same} | ${r.failed} |`,
  ),
  '',
  bin ? `native: ${bin}` : 'native: n/a (no logic-lfd binary with `lfd --perturb`; set LOGIC_LFD_BIN or build target/release/logic-lfd)',
];
console.log(lines.join('\n'));
