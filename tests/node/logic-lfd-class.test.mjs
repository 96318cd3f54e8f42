// The npm `LogicLfd` class: read once, query many times. Its replans are the results of the
// stateless `logicLfd` on the same inputs (byte for byte, search times aside) on the kitchen and
// delivery examples over seeded disturbed states, LogicIn and validation agree with them, errors
// are thrown with located diagnostics, any call after free() throws, and many replans in a row
// give the same answers.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
/** What the class throws for bad input. */
const located = (e) => /** @type {import('logic-lfd').LogicLfdError} */ (e);
const read = (p) => readFileSync(fileURLToPath(new URL(`../../domains/${p}`, import.meta.url)), 'utf8');

const DOMAINS = ['kitchen', 'delivery'].map((name) => ({
  name,
  setup: { domain: read(`${name}/domain.pddl`), problem: read(`${name}/problem.pddl`), demo: read(`${name}/demo.plan`) },
  disturbed: read(`${name}/disturbed.facts`),
}));

/** A result as JSON with its wall-clock search times set to 0 (the only part that may differ). */
const stable = (r) =>
  JSON.stringify({
    ...r,
    stats: { ...r.stats, timeMs: 0 },
    scratch: r.scratch && { ...r.scratch, stats: { ...r.scratch.stats, timeMs: 0 } },
  });

/** Seeded disturbed states as fact lists, plus the example's disturbed state and the init. */
function states(d, count = 8) {
  const drawn = lfd.logicLfdPerturb({ ...d.setup, count, seed: 7 });
  assert.equal(drawn.ok, true, drawn.message);
  return [...drawn.states.map((s) => s.facts), d.disturbed, null];
}

// Greedy searches in prioritised mode: A* there is seconds on some kitchen states.
const OPTIONS = [
  { mode: 'paper', search: 'lazy-gbfs', heuristic: 'hff', compare: true },
  { mode: 'paper' },
  { mode: 'prioritised', search: 'gbfs' },
];

describe('LogicLfd', () => {
  for (const d of DOMAINS) {
    test(`${d.name}: replan gives logicLfd's result on every state, in both modes`, () => {
      const c = new lfd.LogicLfd(d.setup);
      try {
        for (const state of states(d)) {
          for (const o of OPTIONS) {
            const text = state === null ? undefined : Array.isArray(state) ? state.join('\n') : state;
            const fn = lfd.logicLfd({ ...d.setup, ...o, state: text });
            const cls = c.replan(state, o);
            assert.equal(fn.ok, true, fn.message);
            assert.equal(fn.valid, true);
            assert.equal(stable(cls), stable(fn), `${d.name} ${JSON.stringify(o)}`);
            assert.equal(c.logicIn(state), fn.logicIn);
            // Without the lifted replay: the same answer, `valid` left open.
            const unchecked = c.replan(state, { ...o, validate: false });
            assert.equal(unchecked.valid, null);
            assert.equal(stable({ ...unchecked, valid: true }), stable(cls));
          }
        }
        assert.deepEqual(c.demo, lfd.logicLfd(d.setup).demo);
      } finally {
        c.free();
      }
    });

    test(`${d.name}: validate replays plans from the state on the lifted domain`, () => {
      const c = new lfd.LogicLfd(d.setup);
      const out = c.replan(d.disturbed);
      const v = c.validate(d.disturbed, out.plan);
      assert.deepEqual([v.valid, v.stepsApplied, v.cost], [true, out.plan.length, out.cost], v.message);
      assert.equal(c.validate(d.disturbed, out.plan.join('\n')).valid, true);
      // Backwards, the plan fails at its first step; a malformed step is a diagnostic.
      const back = c.validate(d.disturbed, [...out.plan].reverse());
      assert.equal(back.valid, false);
      assert.equal(back.failedStep, 1);
      assert.ok(back.falseLiterals.length > 0);
      const malformed = c.validate(null, '(fly)');
      assert.equal(malformed.valid, false);
      assert.equal(malformed.diagnostics[0].source, 'plan');
      c.free();
    });
  }

  test('a state with a fact no action adds is planned from as observed', () => {
    const d = DOMAINS[0];
    const c = new lfd.LogicLfd(d.setup);
    // The pantry has no door in the model, so nothing can close it: a fact no action adds.
    const state = `${d.disturbed}\n(closed pantry)`;
    const cls = c.replan(state);
    assert.equal(cls.ok, true, cls.message);
    assert.equal(cls.valid, true);
    assert.ok(cls.state.includes('(closed pantry)'));
    assert.ok(!cls.fluents.includes('(closed pantry)'));
    assert.equal(stable(cls), stable(lfd.logicLfd({ ...d.setup, state })));
    assert.equal(c.validate(state, cls.plan).valid, true);
    c.free();
  });

  test('a bad state or option gives the same result as logicLfd; logicIn throws it', () => {
    const d = DOMAINS[0];
    const files = { state: 'now.facts' };
    const c = new lfd.LogicLfd({ ...d.setup, files });
    const state = '(robot-at chef counter)\n  (item-at carrot garage)\n';
    const col = state.split('\n')[1].indexOf('garage') + 1;
    const out = c.replan(state);
    assert.deepEqual([out.ok, out.kind], [false, 'state']);
    assert.deepEqual([out.diagnostics[0].file, out.diagnostics[0].line, out.diagnostics[0].col], ['now.facts', 2, col]);
    assert.equal(stable(out), stable(lfd.logicLfd({ ...d.setup, files, state })));
    assert.throws(
      () => c.logicIn(state),
      (e) => e instanceof Error && e.message === out.message && located(e).kind === 'state' && located(e).diagnostics[0].line === 2,
    );
    assert.throws(() => c.validate(state, []), (e) => located(e).diagnostics[0].col === col);
    const bad = c.replan(d.disturbed, { search: 'dfs' });
    assert.deepEqual([bad.ok, bad.kind, bad.diagnostics[0].source], [false, 'options', 'options']);
    assert.equal(stable(bad), stable(lfd.logicLfd({ ...d.setup, state: d.disturbed, search: 'dfs' })));
    assert.match(c.replan(null, { state: 'x' }).message, /unknown options key `state`/);
    c.free();
  });

  test('construction errors are thrown with located diagnostics', () => {
    const d = DOMAINS[0];
    const files = { domain: 'k/domain.pddl', problem: 'k/problem.pddl', demo: 'k/demo.plan' };
    const thrown = (setup, kind, source, file, line) =>
      assert.throws(
        () => new lfd.LogicLfd(setup),
        (thrown) => {
          const e = located(thrown);
          assert.ok(e instanceof Error);
          assert.equal(e.kind, kind, e.message);
          const g = e.diagnostics[0];
          assert.deepEqual([g.source, g.file, g.line], [source, file, line], e.message);
          assert.equal(e.message, line ? `${g.file}:${g.line}:${g.col}: ${g.message}` : g.message);
          return true;
        },
      );
    const domain = d.setup.domain.replace('(:requirements :strips', '(:requirements :bogus :strips');
    thrown({ ...d.setup, domain, files }, 'parse', 'domain', files.domain, 9);
    const demo = d.setup.demo.replace('(move chef counter fridge)', '(walk chef counter fridge)');
    thrown({ ...d.setup, demo, files }, 'demo', 'demo', files.demo, 5);
    thrown({ ...d.setup, mode: 'paper' }, 'options', 'options', '', 0);
    // Wrong JS types are TypeErrors naming the parameter, as for logicLfd.
    assert.throws(() => new lfd.LogicLfd('x'), (e) => e instanceof TypeError && /LogicLfd: input must be an object/.test(e.message));
    assert.throws(() => new lfd.LogicLfd({ ...d.setup, demo: 3 }), (e) => e instanceof TypeError && /input.demo must be a string/.test(e.message));
    const c = new lfd.LogicLfd(d.setup);
    assert.throws(() => c.replan(42), (e) => e instanceof TypeError && /replan: state must be a string or an array of strings, null or undefined, got number/.test(e.message));
    assert.throws(() => c.replan(['(hand-empty chef)', 1]), /got an array holding a number/);
    assert.throws(() => c.validate(null, 5), (e) => e instanceof TypeError && /validate: plan must be a string or an array of strings, got number/.test(e.message));
    assert.throws(() => c.replan(null, 'astar'), (e) => e instanceof TypeError && /options must be an object/.test(e.message));
    c.free();
  });

  test('any call after free() throws a clear error; free() twice is harmless', () => {
    const d = DOMAINS[1];
    const c = new lfd.LogicLfd(d.setup);
    assert.equal(c.replan(null).ok, true);
    c.free();
    c.free();
    const freed = (fn, name) =>
      assert.throws(fn, (e) => e instanceof Error && e.message === `${name}: this LogicLfd was freed (free() was called); create a new one`);
    freed(() => c.replan(d.disturbed), 'LogicLfd.replan');
    freed(() => c.logicIn(null), 'LogicLfd.logicIn');
    freed(() => c.validate(null, []), 'LogicLfd.validate');
    freed(() => c.demo, 'LogicLfd.demo');
  });

  test('many replans on one instance give the same answers, and results share the frozen demo', () => {
    const d = DOMAINS[1];
    const c = new lfd.LogicLfd(d.setup);
    const all = states(d, 20);
    const first = all.map((s) => stable(c.replan(s, { search: 'lazy-gbfs' })));
    for (let round = 0; round < 10; round++) {
      all.forEach((s, i) => assert.equal(stable(c.replan(s, { search: 'lazy-gbfs' })), first[i], `round ${round}`));
    }
    const a = c.replan(null);
    const b = c.replan(d.disturbed);
    assert.equal(a.demo, b.demo);
    assert.equal(a.demo, c.demo);
    assert.ok(Object.isFrozen(a.demo) && Object.isFrozen(a.demo.states[0]) && Object.isFrozen(a.fluents));
    assert.throws(() => a.demo.actions.push('(x)'), TypeError);
    c.free();
  });
});

test("the package README's LogicLfd example runs and prints what it says", () => {
  const md = readFileSync(fileURLToPath(new URL('../../npm/README.md', import.meta.url)), 'utf8');
  const section = md.slice(md.indexOf('## Logic-LfD on your own domain'));
  const [courier, example] = [...section.matchAll(/```js\n([\s\S]*?)```/g)].map((m) => m[1].replace(/^import .*$/m, '').replace('await init();', ''));
  const logged = [];
  const console = { log: (...a) => logged.push(a), error: (...a) => logged.push(['error', ...a]) };
  // The class example goes on with the courier task of the first one.
  const code = `${courier}\nconsole.log('--');\n${example}`;
  new Function('logicLfd', 'logicLfdPerturb', 'LogicLfd', 'console', code)(lfd.logicLfd, lfd.logicLfdPerturb, lfd.LogicLfd, console);
  const mine = logged.slice(logged.findIndex((l) => l[0] === '--') + 1);
  assert.deepEqual(mine.slice(0, 4), [
    [7],
    [4],
    [4, ['(load p2 mill)', '(drive mill farm)', '(deliver p2 farm)']],
    [true],
  ]);
  assert.equal(mine[4][0], 'unsolvable');
  assert.match(mine[4][1], /no action can make the goal literal\(s\) \(delivered p2\) true/);
  assert.equal(mine.length, 5);
  // The comments say what each line prints.
  assert.match(example, /\/\/ 7: L_0 … L_6/);
  assert.match(example, /\/\/ 4 \[ '\(load p2 mill\)', '\(drive mill farm\)', '\(deliver p2 farm\)' \]/);
});
