// Logic-LfD on any PDDL domain through the npm package (`logicLfd`, `logicLfdPerturb`): the
// kitchen and delivery examples of domains/, merged plans checked by the package's own validator
// on a problem whose :init is S_C, LogicIn on the demonstration's states, both modes, located
// errors, budgets, seeded states and argument types.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
const read = (p) => readFileSync(fileURLToPath(new URL(`../../domains/${p}`, import.meta.url)), 'utf8');

const DOMAINS = ['kitchen', 'delivery'].map((name) => ({
  name,
  domain: read(`${name}/domain.pddl`),
  problem: read(`${name}/problem.pddl`),
  demo: read(`${name}/demo.plan`),
  disturbed: read(`${name}/disturbed.facts`),
  interrupted: read(`${name}/interrupted.plan`),
}));
const input = (d, extra = {}) => ({ domain: d.domain, problem: d.problem, demo: d.demo, ...extra });

/** The problem text with its `(:init …)` replaced by `facts`. */
function withInit(problem, facts) {
  const start = problem.indexOf('(:init');
  let depth = 0;
  let end = start;
  for (; end < problem.length; end++) {
    if (problem[end] === ';') end = problem.indexOf('\n', end);
    if (problem[end] === '(') depth++;
    if (problem[end] === ')' && --depth === 0) break;
  }
  return `${problem.slice(0, start)}(:init ${facts.join(' ')})${problem.slice(end + 1)}`;
}

/** Checks a successful result: its parts agree, and the package's validator accepts the plan
 * on the problem whose initial state is S_C (with the static facts). */
function checkPlan(d, out, what) {
  const info = `${d.name} ${what}: ${out.message}`;
  assert.equal(out.ok, true, info);
  assert.equal(out.kind, 'plan', info);
  assert.equal(out.message, '');
  assert.deepEqual(out.diagnostics, []);
  assert.equal(out.valid, true, info);
  assert.deepEqual(out.plan, [...out.prefix, ...out.suffix], info);
  if (out.k === null) assert.deepEqual(out.suffix, [], info);
  else assert.deepEqual(out.suffix, out.demo.actions.slice(out.k), info);
  assert.equal(out.cost, out.plan.length, info); // unit costs
  if (out.source === 'logic-in') {
    assert.equal(out.k, out.logicIn);
    assert.deepEqual(out.prefix, []);
  }
  const v = lfd.validate(d.domain, withInit(d.problem, [...out.state, ...out.statics]), out.plan.join('\n'));
  assert.equal(v.valid, true, `${info}: ${v.message}`);
  assert.equal(v.stepsApplied, out.plan.length);
}

describe('logicLfd', () => {
  for (const d of DOMAINS) {
    test(`${d.name}: a disturbed state, an interrupted demo and the initial state give valid merged plans`, () => {
      const disturbed = lfd.logicLfd(input(d, { state: d.disturbed, compare: true }));
      checkPlan(d, disturbed, 'disturbed');
      assert.equal(disturbed.logicIn, null);
      assert.equal(disturbed.source, 'multi-goal');
      assert.ok(disturbed.prefix.length > 0);
      assert.ok(disturbed.stats.expanded > 0 && disturbed.stats.timeMs >= 0);
      // The state is S_C's fluents, the statics and fluents come from the grounded task.
      assert.ok(disturbed.statics.length > 0);
      for (const f of disturbed.state) assert.ok(disturbed.fluents.includes(f), f);
      for (const f of disturbed.statics) assert.ok(!disturbed.fluents.includes(f), f);
      assert.ok(disturbed.applicable.length > 0);
      // From scratch with the same search: a plan too, also valid.
      assert.equal(disturbed.scratch.ok, true);
      assert.equal(disturbed.scratch.cost, disturbed.scratch.plan.length);
      const v = lfd.validate(d.domain, withInit(d.problem, [...disturbed.state, ...disturbed.statics]), disturbed.scratch.plan.join('\n'));
      assert.equal(v.valid, true, v.message);

      const interrupted = lfd.logicLfd(input(d, { after: d.interrupted }));
      checkPlan(d, interrupted, 'interrupted');
      assert.equal(interrupted.scratch, null);

      const init = lfd.logicLfd(input(d));
      checkPlan(d, init, 'init');
      assert.equal(init.logicIn, 0);
      assert.equal(init.k, 0);
      assert.equal(init.source, 'logic-in');
      assert.deepEqual(init.plan, init.demo.actions);
    });

    test(`${d.name}: LogicIn on each demonstration state L_k is the latest usable k`, () => {
      const { demo, statics } = lfd.logicLfd(input(d));
      let blocked = 0;
      assert.equal(demo.states.length, demo.actions.length + 1);
      assert.equal(demo.costs.length, demo.states.length);
      demo.costs.forEach((c, k) => assert.equal(c, demo.actions.length - k));
      for (let k = 0; k < demo.states.length; k++) {
        const have = new Set(demo.states[k]);
        // The oracle: the latest j with L_j ⊆ L_k from which the package's validator accepts the
        // rest of the demonstration (with negative preconditions a subset can block it: kitchen's
        // L_2 = L_1 without (closed fridge), and a_3 needs the fridge open).
        let latest = k;
        for (let j = k + 1; j < demo.states.length; j++) {
          if (!demo.states[j].every((f) => have.has(f))) continue;
          const rest = demo.actions.slice(j).join('\n');
          if (lfd.validate(d.domain, withInit(d.problem, [...demo.states[k], ...statics]), rest).valid) latest = j;
          else blocked++;
        }
        const out = lfd.logicLfd(input(d, { state: demo.states[k].join('\n') }));
        assert.deepEqual(out.state, demo.states[k]);
        assert.equal(out.logicIn, latest, `L_${k}`);
        if (latest === demo.actions.length) {
          assert.equal(out.source, 'goal-holds');
          assert.deepEqual(out.plan, []);
        } else {
          assert.equal(out.source, 'logic-in');
          assert.equal(out.k, latest);
          assert.deepEqual(out.plan, demo.actions.slice(latest));
        }
        checkPlan(d, out, `L_${k}`);
      }
      if (d.name === 'kitchen') assert.ok(blocked > 0, 'kitchen has subsets its suffix cannot run from');
    });

    test(`${d.name}: prioritised is never costlier than paper (A*, LM-cut)`, () => {
      // The disturbed state and drawn states that start from a random L_k (odd draws): near the
      // start an optimal prioritised search can take long, so each gets 5 s and a budget skips it.
      const drawn = lfd.logicLfdPerturb(input(d, { count: 12, seed: 3, maxSteps: 4 }));
      assert.equal(drawn.ok, true, drawn.message);
      const states = [d.disturbed, ...drawn.states.filter((_, i) => i % 2).map((s) => s.facts.join('\n'))];
      let compared = 0;
      for (const [i, state] of states.entries()) {
        const o = { state, search: 'astar', heuristic: 'lmcut', timeLimitMs: 5000 };
        const paper = lfd.logicLfd(input(d, { ...o, mode: 'paper' }));
        const prio = lfd.logicLfd(input(d, { ...o, mode: 'prioritised' }));
        checkPlan(d, paper, `paper #${i}`);
        if (prio.kind === 'budget') continue;
        checkPlan(d, prio, `prioritised #${i}`);
        assert.ok(prio.cost <= paper.cost, `#${i}: prioritised ${prio.cost} > paper ${paper.cost}`);
        compared++;
      }
      assert.ok(compared >= 4, `${compared} states compared`);
    });

    test(`${d.name}: after a demonstration prefix, S_C is L_k`, () => {
      const { demo } = lfd.logicLfd(input(d));
      for (const k of [1, 5, demo.actions.length - 1]) {
        const out = lfd.logicLfd(input(d, { after: demo.actions.slice(0, k).join('\n') }));
        assert.deepEqual(out.state, demo.states[k]);
        assert.ok(out.logicIn >= k);
        checkPlan(d, out, `after ${k}`);
      }
    });
  }

  test('errors are located at line:col in the domain, the problem, the demo and the state', () => {
    const d = DOMAINS[0];
    const files = { domain: 'k/domain.pddl', problem: 'k/problem.pddl', demo: 'k/demo.plan', state: 'k/state.facts' };
    const expect = (out, kind, source, file, line, col, re) => {
      assert.equal(out.ok, false);
      assert.equal(out.kind, kind, out.message);
      assert.equal(out.diagnostics.length, 1);
      const g = out.diagnostics[0];
      assert.deepEqual([g.source, g.file, g.line, g.col], [source, file, line, col], JSON.stringify(g));
      assert.match(g.message, re);
      assert.equal(out.message, `${file}:${line}:${col}: ${g.message}`);
    };
    // Domain: an unknown requirement on line 9.
    const domain = d.domain.replace('(:requirements :strips', '(:requirements :bogus :strips');
    const bad = lfd.logicLfd({ ...input(d), domain, files });
    expect(bad, 'parse', 'domain', files.domain, 9, 18, /bogus/);
    assert.equal(bad.demo, null);
    // Problem: an undeclared object.
    const problem = d.problem.replace('(item-at potato pantry)', '(item-at potato attic)');
    const line = d.problem.split('\n').findIndex((l) => l.includes('(item-at potato pantry)')) + 1;
    const col = problem.split('\n')[line - 1].indexOf('attic') + 1;
    expect(lfd.logicLfd({ ...input(d), problem, files }), 'parse', 'problem', files.problem, line, col, /attic/);
    // Demo: an unknown action on its first step (line 5, after four comment lines).
    const demo = d.demo.replace('(move chef counter fridge)', '(walk chef counter fridge)');
    expect(lfd.logicLfd({ ...input(d), demo, files }), 'demo', 'demo', files.demo, 5, 2, /walk/);
    // State: an undeclared object on line 2.
    const state = '(robot-at chef counter)\n  (item-at carrot garage)\n';
    const s = lfd.logicLfd({ ...input(d), state, files });
    expect(s, 'state', 'state', files.state, 2, state.split('\n')[1].indexOf('garage') + 1, /garage/);
    assert.notEqual(s.demo, null); // the domain, problem and demo did parse
    assert.equal(s.logicIn, null);
    // Any well-formed atoms are a state, a static fact the problem does not have included: here
    // one passage and nothing else, from which the goal is out of reach, its literals named.
    const lost = lfd.logicLfd({ ...input(d), state: '(adjacent pantry table)' });
    assert.deepEqual([lost.ok, lost.kind, lost.diagnostics], [false, 'unsolvable', []]);
    assert.match(lost.message, /no action can make the goal literal\(s\) .*\(closed fridge\) true/);
    // `after` reports the step that does not apply, with its false precondition.
    const after = lfd.logicLfd({ ...input(d), after: '(move chef counter fridge)\n(pick chef carrot fridge)', files });
    expect(after, 'state', 'state', files.state, 2, 1, /step 2 `\(pick chef carrot fridge\)` is not applicable: false precondition \(not \(closed fridge\)\)/);
  });

  test('a demonstration step that does not apply is named with its false precondition', () => {
    const d = DOMAINS[0];
    // Without opening the fridge, step 2 picks the carrot through the shut door.
    const demo = d.demo.replace('(open chef fridge)\n', '');
    const out = lfd.logicLfd({ ...input(d), demo });
    assert.equal(out.ok, false);
    assert.equal(out.kind, 'demo');
    const g = out.diagnostics[0];
    assert.deepEqual([g.source, g.file, g.line, g.col], ['demo', 'demo.plan', 6, 1]);
    assert.match(g.message, /demonstration step 2 `\(pick chef carrot fridge\)` is not applicable: false precondition \(not \(closed fridge\)\)/);
    // A demonstration that stops short of the goal.
    const short = lfd.logicLfd({ ...input(d), demo: d.demo.split('\n').slice(0, 10).join('\n') });
    assert.equal(short.kind, 'demo');
    assert.match(short.message, /does not reach the goal/);
  });

  test('a node budget too small for the search gives kind budget', () => {
    const d = DOMAINS[0];
    const out = lfd.logicLfd(input(d, { state: d.disturbed, maxExpanded: 1 }));
    assert.equal(out.ok, false);
    assert.equal(out.kind, 'budget');
    assert.match(out.message, /budget/);
    assert.deepEqual(out.plan, []);
    assert.equal(out.k, null);
    assert.equal(out.valid, null, "no plan, nothing replayed");
    // The state and LogicIn are still reported.
    assert.ok(out.state.length > 0);
    // LogicIn needs no search: the same budget is enough from L_3.
    const demo = lfd.logicLfd(input(d)).demo;
    assert.equal(lfd.logicLfd(input(d, { state: demo.states[3].join(' '), maxExpanded: 1 })).ok, true);
    // A time budget of 0 ms.
    assert.equal(lfd.logicLfd(input(d, { state: d.disturbed, timeLimitMs: 0 })).kind, 'budget');
  });

  test('bad options are values of kind options; unknown keys are named', () => {
    const d = DOMAINS[1];
    const opt = (extra, re) => {
      const out = lfd.logicLfd(input(d, extra));
      assert.equal(out.ok, false);
      assert.equal(out.kind, 'options', JSON.stringify(extra));
      assert.equal(out.diagnostics[0].source, 'options');
      assert.match(out.message, re);
    };
    opt({ mode: 'fast' }, /fast/);
    opt({ search: 'dijkstra' }, /dijkstra/);
    opt({ heuristic: 'hcea' }, /hcea/);
    opt({ maxExpanded: -1 }, /maxExpanded/);
    opt({ maxExpanded: 'many' }, /maxExpanded/);
    opt({ timeLimitMs: 'soon' }, /timeLimitMs/);
    opt({ compare: 1 }, /compare/);
    opt({ validate: 'no' }, /`validate` must be a boolean, got string/);
    opt({ max_expanded: 10 }, /unknown input key `max_expanded`/);
    opt({ files: { domain: 'd.pddl', plan: 'x' } }, /unknown files key `plan`/);
    opt({ files: 'x' }, /files/);
    // prioritized (US spelling) is read too.
    assert.equal(lfd.logicLfd(input(d, { mode: 'prioritized', state: d.disturbed })).ok, true);
  });

  test('a wrong-typed input throws a TypeError naming the parameter', () => {
    const d = DOMAINS[1];
    const typeError = (fn, re) => assert.throws(fn, (e) => e instanceof TypeError && re.test(e.message), re.source);
    typeError(() => lfd.logicLfd(42), /^logicLfd: input must be an object, got number$/);
    typeError(() => lfd.logicLfd(), /^logicLfd: input must be an object, got undefined$/);
    typeError(() => lfd.logicLfd(null), /^logicLfd: input must be an object, got null$/);
    typeError(() => lfd.logicLfd([d.domain]), /^logicLfd: input must be an object, got array$/);
    typeError(() => lfd.logicLfd('domain'), /^logicLfd: input must be an object, got string$/);
    typeError(() => lfd.logicLfd({ ...input(d), domain: 5 }), /^logicLfd: input\.domain must be a string, got number$/);
    typeError(() => lfd.logicLfd({ domain: d.domain, demo: d.demo }), /^logicLfd: input\.problem must be a string, got undefined$/);
    typeError(() => lfd.logicLfd({ ...input(d), demo: ['(load p1 van1 depot)'] }), /^logicLfd: input\.demo must be a string, got array$/);
    typeError(() => lfd.logicLfd({ ...input(d), state: 5 }), /^logicLfd: input\.state must be a string, got number$/);
    typeError(() => lfd.logicLfd({ ...input(d), after: {} }), /^logicLfd: input\.after must be a string, got object$/);
    typeError(() => lfd.logicLfd({ ...input(d), state: d.disturbed, after: d.interrupted }), /^logicLfd: input\.state and input\.after/);
    typeError(() => lfd.logicLfdPerturb(7), /^logicLfdPerturb: input must be an object, got number$/);
    typeError(() => lfd.logicLfdPerturb({ ...input(d), problem: true, count: 1, seed: 1 }), /^logicLfdPerturb: input\.problem must be a string, got boolean$/);
    // `undefined` and `null` for state/after read as absent.
    assert.equal(lfd.logicLfd({ ...input(d), state: undefined, after: null }).k, 0);
  });
});

describe('logicLfdPerturb', () => {
  test('the same seed draws the same states; another seed others', () => {
    for (const d of DOMAINS) {
      const a = lfd.logicLfdPerturb(input(d, { count: 30, seed: 7 }));
      const b = lfd.logicLfdPerturb(input(d, { count: 30, seed: 7 }));
      const c = lfd.logicLfdPerturb(input(d, { count: 30, seed: 8 }));
      assert.equal(a.ok, true, a.message);
      assert.equal(a.states.length, 30);
      assert.deepEqual(a, b);
      assert.notDeepEqual(a.states, c.states);
      const { demo, fluents } = lfd.logicLfd(input(d));
      a.states.forEach((s, i) => {
        if (i % 2 === 0) assert.equal(s.fromK, 0);
        assert.ok(s.fromK >= 0 && s.fromK <= demo.actions.length);
        assert.ok(s.steps >= 0 && s.steps <= 8);
        for (const f of s.facts) assert.ok(fluents.includes(f), f);
        // Each drawn state is a state logicLfd reads and plans from.
        checkPlan(d, lfd.logicLfd(input(d, { state: s.facts.join('\n'), search: 'lazy-gbfs' })), `seed 7 #${i}`);
      });
      const short = lfd.logicLfdPerturb(input(d, { count: 10, seed: 7, maxSteps: 2 }));
      for (const s of short.states) assert.ok(s.steps <= 2);
    }
  });

  test('bad inputs are values with located diagnostics', () => {
    const d = DOMAINS[0];
    const bad = lfd.logicLfdPerturb({ ...input(d), demo: '(fly chef)', count: 1, seed: 1 });
    assert.equal(bad.ok, false);
    assert.deepEqual(bad.states, []);
    assert.equal(bad.diagnostics[0].source, 'demo');
    assert.equal(bad.diagnostics[0].line, 1);
    const noCount = lfd.logicLfdPerturb({ ...input(d), seed: 1 });
    assert.equal(noCount.ok, false);
    assert.match(noCount.message, /count/);
    assert.equal(noCount.diagnostics[0].source, 'options');
    assert.match(lfd.logicLfdPerturb({ ...input(d), count: 1, seed: -1 }).message, /seed/);
    assert.match(lfd.logicLfdPerturb({ ...input(d), count: 1, seed: 1, steps: 3 }).message, /unknown input key `steps`/);
  });
});

test("the package README's Logic-LfD example runs and prints what it says", () => {
  const md = readFileSync(fileURLToPath(new URL('../../npm/README.md', import.meta.url)), 'utf8');
  const section = md.slice(md.indexOf('## Logic-LfD on your own domain'));
  const code = /```js\n([\s\S]*?)```/.exec(section)[1].replace(/^import .*$/m, '').replace('await init();', '');
  const logged = [];
  const console = { log: (...a) => logged.push(a), error: (...a) => logged.push(['error', ...a]) };
  new Function('logicLfd', 'logicLfdPerturb', 'console', code)(lfd.logicLfd, lfd.logicLfdPerturb, console);
  assert.deepEqual(logged.slice(0, 3), [[['(load p2 mill)']], [4, ['(drive mill farm)', '(deliver p2 farm)']], [true, 3]]);
  assert.equal(logged.length, 6);
  // The comments after each call say what it prints.
  assert.match(code, /\/\/ \[ '\(load p2 mill\)' \]/);
  assert.match(code, /\/\/ 4 \[ '\(drive mill farm\)', '\(deliver p2 farm\)' \]/);
  assert.match(code, /\/\/ true 3/);
});
