// The PDDL planner through the npm package: IPC blocks problems, line:col errors, options.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
const ipc = (p) => readFileSync(fileURLToPath(new URL(`../data/ipc/${p}`, import.meta.url)), 'utf8');

/** Replays a plan on the STRIPS blocks world by hand (independent of the planner's own states). */
function replayBlocks(problem, plan) {
  const init = /\(:init([\s\S]*?)\)\s*\(:goal/i.exec(problem)[1];
  const facts = new Set([...init.matchAll(/\(([^()]+)\)/g)].map((m) => `(${m[1].trim().toLowerCase().replace(/\s+/g, ' ')})`));
  const need = (f) => assert.ok(facts.has(f), `precondition ${f} missing`);
  for (const a of plan) {
    const [op, x, y] = a.slice(1, -1).split(' ');
    if (op === 'pick-up') {
      [`(clear ${x})`, `(ontable ${x})`, '(handempty)'].forEach(need);
      ['(handempty)', `(clear ${x})`, `(ontable ${x})`].forEach((f) => facts.delete(f));
      facts.add(`(holding ${x})`);
    } else if (op === 'put-down') {
      need(`(holding ${x})`);
      facts.delete(`(holding ${x})`);
      ['(handempty)', `(clear ${x})`, `(ontable ${x})`].forEach((f) => facts.add(f));
    } else if (op === 'stack') {
      [`(holding ${x})`, `(clear ${y})`].forEach(need);
      [`(holding ${x})`, `(clear ${y})`].forEach((f) => facts.delete(f));
      ['(handempty)', `(clear ${x})`, `(on ${x} ${y})`].forEach((f) => facts.add(f));
    } else if (op === 'unstack') {
      [`(on ${x} ${y})`, `(clear ${x})`, '(handempty)'].forEach(need);
      [`(on ${x} ${y})`, `(clear ${x})`, '(handempty)'].forEach((f) => facts.delete(f));
      [`(holding ${x})`, `(clear ${y})`].forEach((f) => facts.add(f));
    } else assert.fail(`unknown action ${a}`);
  }
  return facts;
}

function goalOf(problem) {
  const g = /\(:goal\s*\(and([\s\S]*?)\)\s*\)/i.exec(problem)[1];
  return [...g.matchAll(/\(([^()]+)\)/g)].map((m) => `(${m[1].trim().toLowerCase().replace(/\s+/g, ' ')})`);
}

test('plans IPC blocks problems optimally and the plan reaches the goal', () => {
  const domain = ipc('blocks/domain.pddl');
  for (const [file, optimal] of [
    ['probBLOCKS-4-0.pddl', 6],
    ['probBLOCKS-5-0.pddl', 12],
  ]) {
    const problem = ipc(`blocks/${file}`);
    const out = lfd.plan(domain, problem, { search: 'astar', heuristic: 'lmcut' });
    assert.equal(out.ok, true, JSON.stringify(out));
    assert.equal(out.plan.length, optimal, `${file}: ${out.plan.join(' ')}`);
    assert.equal(out.cost, optimal);
    assert.equal(out.optimal, true);
    const facts = replayBlocks(problem, out.plan);
    for (const g of goalOf(problem)) assert.ok(facts.has(g), `${file}: goal ${g} not reached`);
    // The reported states follow the plan: one per action plus the initial state.
    assert.equal(out.states.length, out.plan.length + 1);
    for (const g of goalOf(problem)) assert.ok(out.states.at(-1).includes(g));
  }
});

test('greedy search with h_FF solves a larger instance', () => {
  const out = lfd.plan(ipc('blocks/domain.pddl'), ipc('blocks/probBLOCKS-9-0.pddl'), { search: 'gbfs', heuristic: 'hff' });
  assert.equal(out.ok, true);
  assert.equal(out.optimal, false);
  const facts = replayBlocks(ipc('blocks/probBLOCKS-9-0.pddl'), out.plan);
  for (const g of goalOf(ipc('blocks/probBLOCKS-9-0.pddl'))) assert.ok(facts.has(g));
});

test('bad PDDL gives file:line:col diagnostics', () => {
  const domain = ipc('blocks/domain.pddl');
  const lines = domain.split('\n');
  // Insert an unknown section as line 7, inside (define …).
  lines.splice(6, 0, '  (:bogus x)');
  const out = lfd.plan(lines.join('\n'), ipc('blocks/probBLOCKS-4-0.pddl'), {});
  assert.equal(out.ok, false);
  assert.equal(out.kind, 'parse');
  const d = out.diagnostics[0];
  assert.equal(d.source, 'domain');
  assert.equal(d.file, 'domain.pddl');
  assert.equal(d.line, 7);
  assert.equal(d.col, 4); // at `:bogus`
  assert.match(out.message, /^domain\.pddl:7:4: .*bogus/);
  // An undeclared object in the problem points into the problem text.
  const bad = lfd.plan(domain, '(define (problem p) (:domain blocks)\n (:objects a)\n (:init (clear zz))\n (:goal (clear a)))', {
    problemFile: 'p.pddl',
  });
  assert.equal(bad.ok, false);
  assert.equal(bad.diagnostics[0].source, 'problem');
  assert.equal(bad.diagnostics[0].file, 'p.pddl');
  assert.equal(bad.diagnostics[0].line, 3);
  assert.equal(bad.diagnostics[0].col, 16);
  // check() reports the same without searching, and nothing for good input.
  assert.deepEqual(lfd.check(domain, ipc('blocks/probBLOCKS-4-0.pddl')), []);
  assert.equal(lfd.check(lines.join('\n'), ipc('blocks/probBLOCKS-4-0.pddl'))[0].line, 7);
});

test('unsolvable, budget and option errors are values, not exceptions', () => {
  const domain = ipc('blocks/domain.pddl');
  const impossible = '(define (problem p) (:domain blocks) (:objects a)\n (:init (clear a) (ontable a) (handempty))\n (:goal (on a a)))';
  const u = lfd.plan(domain, impossible, { search: 'bfs' });
  assert.equal(u.ok, false);
  assert.equal(u.kind, 'unsolvable');
  const b = lfd.plan(domain, ipc('blocks/probBLOCKS-9-0.pddl'), { search: 'bfs', maxExpanded: 10 });
  assert.equal(b.ok, false);
  assert.equal(b.kind, 'budget');
  const o = lfd.plan(domain, impossible, { search: 'dijkstra' });
  assert.equal(o.ok, false);
  assert.equal(o.kind, 'options');
  assert.match(o.message, /dijkstra/);
  assert.throws(() => lfd.plan(domain, impossible, { serch: 'bfs' }), /serch/);
});

test('the snake_case option names of 0.1 still work (deprecated)', () => {
  const domain = ipc('blocks/domain.pddl');
  const problem = ipc('blocks/probBLOCKS-9-0.pddl');
  const b = lfd.plan(domain, problem, { search: 'bfs', max_expanded: 10, time_limit_ms: 5000 });
  assert.equal(b.kind, 'budget');
  assert.match(b.message, /node budget/);
  const bad = lfd.plan(domain, '(define (problem p) (:domain blocks)\n (:objects a)\n (:init (clear zz))\n (:goal (clear a)))', {
    domain_file: 'd.pddl',
    problem_file: 'p.pddl',
  });
  assert.equal(bad.diagnostics[0].file, 'p.pddl');
  // One option under both names is refused, as any repeated key.
  assert.throws(() => lfd.plan(domain, problem, { maxExpanded: 1, max_expanded: 2 }), /duplicate field/);
});

test('outputs are camelCase: plan, validate', () => {
  const domain = ipc('blocks/domain.pddl');
  const problem = ipc('blocks/probBLOCKS-4-0.pddl');
  const out = lfd.plan(domain, problem, {});
  assert.equal(out.ok, true);
  assert.equal(typeof out.timeMs, 'number');
  assert.equal(typeof out.groundMs, 'number');
  assert.equal(out.time_ms, undefined);
  const v = lfd.validate(domain, problem, out.plan.join('\n'));
  assert.equal(v.valid, true);
  assert.equal(v.stepsApplied, out.plan.length);
  assert.deepEqual(v.falseLiterals, []);
  const w = lfd.validate(domain, problem, out.plan.slice(1).join('\n'));
  assert.equal(w.valid, false);
  assert.equal(w.failedStep, 1);
  assert.ok(w.falseLiterals.length > 0);
});

test('a wrong-typed argument throws a TypeError naming the parameter', () => {
  const domain = ipc('blocks/domain.pddl');
  const problem = ipc('blocks/probBLOCKS-4-0.pddl');
  const typeError = (fn, re) => assert.throws(fn, (e) => e instanceof TypeError && re.test(e.message), re.source);
  typeError(() => lfd.plan(42, null, {}), /^plan: domain must be a string, got number$/);
  typeError(() => lfd.plan(domain, null, {}), /^plan: problem must be a string, got null$/);
  typeError(() => lfd.plan(domain, problem, 5), /^plan: options must be an object, got number$/);
  typeError(() => lfd.plan(domain, problem, [1]), /^plan: options must be an object, got array$/);
  typeError(() => lfd.validate(domain, problem, 5), /^validate: plan must be a string, got number$/);
  typeError(() => lfd.validate({}, problem, ''), /^validate: domain must be a string, got object$/);
  typeError(() => lfd.check(domain, 7), /^check: problem must be a string, got number$/);
  typeError(() => lfd.check(domain, problem, 1), /^check: domainFile must be a string, got number$/);
  typeError(() => lfd.benchmark(1), /^benchmark: id must be a string, got number$/);
  typeError(() => lfd.lqt(3), /^lqt: case must be an object or a JSON string, got number$/);
  typeError(() => lfd.runEpisode({}), /^runEpisode: optionsJson must be a string, got object$/);
  typeError(() => lfd.taughtInfo(undefined), /^taughtInfo: demoJson must be a string, got undefined$/);
  typeError(() => lfd.taughtRandomScene(1, 2), /^taughtRandomScene: demoJson must be a string, got number$/);
  typeError(() => lfd.taughtRandomScene('{}', 'x'), /^taughtRandomScene: seed must be a number, got string$/);
  typeError(() => new lfd.Teacher(2), /^new Teacher: benchmark must be a string, got number$/);
  typeError(() => new lfd.Teacher('b1', 3), /^new Teacher: scene must be a string, got number$/);
  // The module is still alive and answers normally after all of these.
  assert.deepEqual(lfd.check(domain, problem), []);
  // Undefined optional arguments are fine.
  assert.deepEqual(lfd.check(domain, problem, undefined, undefined), []);
  assert.equal(lfd.plan(domain, problem).ok, true);
  assert.equal(lfd.plan(domain, problem, null).ok, true);
});
