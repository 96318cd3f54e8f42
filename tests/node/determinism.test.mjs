// Native/wasm determinism: the same seed gives byte-identical episode JSON from the
// native CLI (`logic-lfd run … --json`) and from the wasm package (`runEpisode`), and across two
// runs of each. The only fields allowed to differ are the wall-clock planning times
// (`planning_ms`, `log.replans[].time_ms`): they are masked to 0 textually on the CLI's output and
// written as 0 by `runEpisode({ canonical: true })`; every other byte must match, including every
// float of the final world (poses, joint angles) and of the log.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
const root = fileURLToPath(new URL('../..', import.meta.url));

/**
 * The native CLI: `$LOGIC_LFD_BIN`, else target/debug, brought up to date with the sources first
 * (cargo does nothing when it is), so the comparison never runs a stale binary against a fresh
 * wasm build.
 */
function cli() {
  if (process.env.LOGIC_LFD_BIN) return process.env.LOGIC_LFD_BIN;
  const target = process.env.CARGO_TARGET_DIR ?? join(root, 'target');
  execFileSync('cargo', ['build', '-p', 'logic-lfd', '--bin', 'logic-lfd', '--locked'], { cwd: root, stdio: 'inherit' });
  return join(target, 'debug', 'logic-lfd');
}
const BIN = cli();

/** Replaces the wall-clock fields with 0.0 (what serde_json writes for 0f64), leaving all else. */
function maskTimes(json) {
  return json
    .replace(/"time_ms":-?[0-9.eE+-]+/g, '"time_ms":0.0')
    .replace(/"bind_ms":-?[0-9.eE+-]+/g, '"bind_ms":0.0')
    .replace(/"planning_ms":\[[^\]]*\]/g, (m) => m.replace(/-?[0-9][0-9.eE+-]*/g, '0.0'));
}

/** One native episode, masked. */
function native({ benchmark, level, method, mode, seed }) {
  const out = execFileSync(
    BIN,
    ['run', '--benchmark', benchmark, '--level', level, '--method', method, '--mode', mode, '--seed', String(seed), '--json'],
    { cwd: root, encoding: 'utf8', maxBuffer: 64 << 20 },
  );
  return maskTimes(out.trimEnd());
}

/** One wasm episode, canonical (times written as 0). */
function wasm(o) {
  return lfd.runEpisode(JSON.stringify({ ...o, canonical: true }));
}

// Every benchmark at every level (and undisturbed) with Logic-LfD in paper mode, a second seed at
// L3, plus the other methods and the prioritised mode on a few of them. DETERMINISM_FULL=1 runs
// every benchmark × level at both seeds (≈ 2× longer).
const full = process.env.DETERMINISM_FULL === '1';
const cases = [];
for (const benchmark of ['b1', 'b2', 'b3'])
  for (const level of ['none', 'l1', 'l2', 'l3', 'l4'])
    for (const seed of [1, 7])
      if (seed === 1 || full || level === 'l3') cases.push({ benchmark, level, method: 'logic-lfd', mode: 'paper', seed });
for (const [benchmark, level, method, mode, seed] of [
  ['b1', 'l3', 'logic-lfd', 'prioritised', 3],
  ['b2', 'l2', 'logic-lfd', 'prioritised', 4],
  ['b3', 'l4', 'logic-lfd', 'prioritised', 5],
  ['b1', 'l3', 'tamp', 'paper', 2],
  ['b3', 'l1', 'tamp', 'paper', 6],
  ['b1', 'l2', 'rlds', 'paper', 8],
  ['b2', 'l3', 'linear', 'paper', 9],
])
  cases.push({ benchmark, level, method, mode, seed });

/** The first differing position, with context, for a readable failure. */
function firstDiff(a, b) {
  let i = 0;
  while (i < a.length && a[i] === b[i]) i++;
  return `at byte ${i}: native …${a.slice(Math.max(0, i - 80), i + 80)}…\n wasm …${b.slice(Math.max(0, i - 80), i + 80)}…`;
}

describe('native and wasm give byte-identical episode JSON', () => {
  test('masking the CLI output equals runEpisode canonical output on a hand check', () => {
    assert.equal(
      maskTimes('{"planning_ms":[0.12,3e-5],"x":{"time_ms":1.5,"bind_ms":0.7,"t":2.5}}'),
      '{"planning_ms":[0.0,0.0],"x":{"time_ms":0.0,"bind_ms":0.0,"t":2.5}}',
    );
  });

  for (const c of cases) {
    const name = `${c.benchmark} ${c.level} ${c.method} ${c.mode} seed ${c.seed}`;
    test(name, () => {
      const n1 = native(c);
      const w1 = wasm(c);
      assert.ok(n1.length > 1000 && n1.includes('"final_world"'), `native output too short: ${n1.slice(0, 200)}`);
      assert.ok(n1 === w1, `native and wasm differ ${firstDiff(n1, w1)}`);
      assert.ok(native(c) === n1, 'two native runs differ');
      assert.ok(wasm(c) === w1, 'two wasm runs differ');
      // Not tautological: another seed gives another episode (the seed reaches the world).
      if (c.level !== 'none' && c.seed === 1) assert.notEqual(wasm({ ...c, seed: 2 }), w1);
    });
  }

  test('runEpisode refuses bad options with a message naming the field', () => {
    assert.throws(() => lfd.runEpisode('{"benchmark":"b9"}'), /benchmark/);
    assert.throws(() => lfd.runEpisode('{"level":"l7"}'), /level/);
    assert.throws(() => lfd.runEpisode('{"sede":1}'), /sede/);
    assert.throws(() => lfd.runEpisode('not json'), /options/);
    assert.throws(() => lfd.runEpisode('{"scene":"{}"}'), /./);
    // Without `canonical` the times are the wall clock's (still valid JSON with the same shape).
    const r = JSON.parse(lfd.runEpisode('{"benchmark":"b1","seed":1}'));
    assert.equal(r.success, true);
    assert.equal(r.planning_ms.length, r.replans);
  });
});
