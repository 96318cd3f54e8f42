// Timing of the LQT-CP pipeline in wasm under node (not a test: `node tests/node/bench-lqt.mjs
// [--runs N]`): the whole `lqt()` call — JSON case in, batch solution, feedback gains and rollouts,
// output object out — for the shared example and for the same case made 3-D with more steps and
// basis functions (the size of the page's skills). Prints the median and the 10th/90th percentiles
// of N runs after a few warm-up runs, and the same for one closed-loop B1 episode (`runEpisode`).
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
const arg = (name, d) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? Number(process.argv[i + 1]) : d;
};
const RUNS = arg('runs', 50);
const caseText = readFileSync(fileURLToPath(new URL('../data/lqt/lqt-cp-example.json', import.meta.url)), 'utf8');
const example = JSON.parse(caseText);

/** The example stretched: `dim` dimensions, `steps` steps, `nFct` RBFs; targets scaled in time. */
function scaled(dim, steps, nFct) {
  const c = structuredClone(example);
  const pad = (v, fill) => Array.from({ length: dim }, (_, i) => v[i] ?? fill);
  c.dim = dim;
  c.n_steps = steps;
  c.basis = { type: 'rbf', n_fct: nFct, centers: Array.from({ length: nFct }, (_, i) => i / (nFct - 1)), lambda: example.basis.lambda };
  c.x0 = Array.from({ length: dim * c.order }, () => 0);
  c.targets = example.targets.map((t) => ({
    ...t,
    t: Math.round((t.t / (example.n_steps - 1)) * (steps - 1)),
    pos: pad(t.pos, 0.2),
    ...(t.vel ? { vel: pad(t.vel, 0) } : {}),
  }));
  // The reference as docs/formats.md describes it: μ = 0, q = 0, then each target sets pos (and vel).
  const nx = dim * c.order;
  const mu = Array.from({ length: steps }, () => Array(nx).fill(0));
  const q = Array.from({ length: steps }, () => Array(nx).fill(0));
  for (const t of c.targets) {
    for (let d = 0; d < dim; d++) {
      mu[t.t][d] = t.pos[d];
      q[t.t][d] = t.w_pos;
      if (t.vel) {
        mu[t.t][dim + d] = t.vel[d];
        q[t.t][dim + d] = t.w_vel;
      }
    }
  }
  c.reference = { mu, q_diag: q };
  c.feedback = { x_init: c.x0.map((v, i) => (i === 0 ? v + 0.05 : v)), perturbation: { after_step: Math.floor(steps / 3), delta: c.x0.map((_, i) => (i < dim ? 0.05 : 0)) } };
  return c;
}

function time(label, f) {
  for (let i = 0; i < 3; i++) f();
  const t = [];
  for (let i = 0; i < RUNS; i++) {
    const t0 = performance.now();
    f();
    t.push(performance.now() - t0);
  }
  t.sort((a, b) => a - b);
  const q = (p) => t[Math.min(t.length - 1, Math.floor(p * t.length))];
  console.log(`${label.padEnd(58)} median ${q(0.5).toFixed(3)} ms  (p10 ${q(0.1).toFixed(3)}, p90 ${q(0.9).toFixed(3)}, ${RUNS} runs)`);
}

console.log(`logic-lfd ${lfd.version()} (wasm in node ${process.version})`);
time('lqt: shared example (2-D, 60 steps, 8 RBF), JSON text', () => lfd.lqt(caseText));
time('lqt: shared example, object', () => lfd.lqt(example));
for (const [dim, steps, nFct] of [
  [3, 100, 10],
  [3, 200, 15],
]) {
  const c = scaled(dim, steps, nFct);
  // Fails loudly if the stretched case is not valid (the timing would mean nothing).
  lfd.lqt(c);
  time(`lqt: ${dim}-D, ${steps} steps, ${nFct} RBF, with feedback rollouts`, () => lfd.lqt(c));
}
time('runEpisode: B1, L3, seed 1 (whole closed-loop episode)', () => lfd.runEpisode('{"benchmark":"b1","level":"l3","seed":1}'));
