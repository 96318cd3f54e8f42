// The closed loop through the npm package: a B1 episode, disturbances, drags, replay.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { withValueAt } from '../json-at.mjs';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

/**
 * Steps until done/failed (or a bound), calling `each(frame, i)` after every step.
 * @param {any} session
 * @param {(frame: any, i: number) => void} [each]
 */
function run(session, each = () => {}, maxSteps = 4000) {
  let f = session.frame();
  for (let i = 0; i < maxSteps && f.status.kind !== 'done' && f.status.kind !== 'failed'; i++) {
    f = session.step(0.1);
    each(f, i);
  }
  return f;
}

const TOWER = ['(on a b)', '(on b c)', '(on c d)'];

describe('Session', () => {
  test('a B1 episode reaches success: the tower A on B on C on D stands', () => {
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 });
    const first = s.frame();
    assert.equal(first.world.bodies.filter((b) => b.kind === 'block').length, 4);
    assert.ok(first.demo.length > 0 && first.demoStates.length === first.demo.length + 1);
    const f = run(s);
    assert.equal(f.status.kind, 'done', f.status.message);
    for (const g of TOWER) assert.ok(f.facts.includes(g), `${g} missing from ${f.facts.join(' ')}`);
    // The tower is physically there: each block is one block height above the one below.
    const z = Object.fromEntries(f.world.bodies.filter((b) => b.kind === 'block').map((b) => [b.name, b.pose.position[2]]));
    for (const [x, y] of [['a', 'b'], ['b', 'c'], ['c', 'd']]) assert.ok(Math.abs(z[x] - z[y] - 0.06) < 0.01);
    s.free();
  });

  test('an L3 disturbance makes Logic-LfD replan and the episode still succeeds', () => {
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 2 });
    let injected = null;
    const f = run(s, (fr, i) => {
      if (i === 30) injected = { inj: s.inject('l3'), replans: fr.replans };
    });
    assert.ok(injected, 'the episode ended before the injection');
    assert.equal(injected.inj.level, 'l3');
    assert.ok(injected.inj.description.length > 0);
    assert.ok(f.replans > injected.replans, 'no replan after L3');
    // The replan was timed by the caller's clock: it took some time, and less than the episode.
    assert.ok(f.lastReplan.timeMs > 0 && Number.isFinite(f.lastReplan.timeMs), String(f.lastReplan.timeMs));
    assert.equal(f.status.kind, 'done', f.status.message);
    s.free();
  });

  test('a refused drag rejects with the reason and leaves the world unchanged', () => {
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 });
    const before = s.frame().world;
    // Off every table: nothing would support it.
    assert.throws(() => s.perturb('a', [5, 5, 0.03]), (e) => e instanceof Error && e.message.length > 0);
    assert.throws(() => s.perturb('no-such-block', [0.5, 0, 0.03]), /no-such-block/);
    assert.deepEqual(s.frame().world.bodies, before.bodies);
    s.free();
  });

  test('bad options reject with a message instead of panicking', () => {
    assert.throws(() => new lfd.Session({ benchmark: 'b9', method: 'logic-lfd', mode: 'paper', seed: 1 }), /b9|benchmark/);
    assert.throws(() => new lfd.Session({ benchmark: 'b1', method: 'magic', mode: 'paper', seed: 1 }), /magic|method/);
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 });
    assert.throws(() => s.inject('l9'), /l9/);
    assert.throws(() => s.step(-1), /dt/);
    assert.throws(() => s.reset(-3), /seed/);
    s.free();
  });

  test('a wrong-typed argument throws a TypeError naming the parameter', () => {
    const typeError = (fn, re) => assert.throws(fn, (e) => e instanceof TypeError && re.test(e.message), re.source);
    typeError(() => lfd.Session.fromScene('{}', {}), /^Session\.fromScene: options must be an object, got string$/);
    const o = { benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 };
    typeError(() => lfd.Session.fromScene(o, {}), /^Session\.fromScene: scene must be a string, got object$/);
    typeError(() => lfd.Session.fromScene(o, '{}', 4), /^Session\.fromScene: demo must be a string, got number$/);
    typeError(() => new lfd.Session('b1'), /^new Session: options must be an object, got string$/);
    typeError(() => new lfd.Session(), /^new Session: options must be an object, got undefined$/);
    typeError(() => lfd.Session.replay(1), /^Session\.replay: episode must be a string, got number$/);
    typeError(() => lfd.Session.fromTaught(null), /^Session\.fromTaught: demoJson must be a string, got null$/);
    typeError(() => lfd.Session.replayTaught([]), /^Session\.replayTaught: episode must be a string, got array$/);
    const s = new lfd.Session(o);
    typeError(() => s.perturb(1, [0.5, 0, 0.03]), /^Session\.perturb: body must be a string, got number$/);
    typeError(() => s.perturb('a', 'up'), /^Session\.perturb: position must be \[x, y, z\]/);
    typeError(() => s.perturb('a', [1, 2]), /^Session\.perturb: position must be \[x, y, z\]/);
    typeError(() => s.inject(3), /^Session\.inject: level must be a string, got number$/);
    typeError(() => s.step('0.1'), /^Session\.step: dt must be a number, got string$/);
    typeError(() => s.reset(null), /^Session\.reset: seed must be a number, got null$/);
    // The session still works.
    assert.equal(s.step(0.1).tick, 10);
    s.free();
  });

  test('a demo with a wrong type deep inside is refused with its path and position', () => {
    const o = { benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 };
    const s = new lfd.Session(o);
    const scene = s.sceneJson();
    s.free();
    const demo = JSON.parse(readFileSync(new URL('../../domains/b1-tower/demo.json', import.meta.url), 'utf8'));
    const bad = withValueAt(demo, ['actions', 2, 'samples', 5, 1], 'x');
    assert.throws(
      () => lfd.Session.fromScene(o, scene, bad.text),
      (e) => {
        assert.ok(e instanceof Error);
        assert.equal(
          e.message,
          `demo: actions[2].samples[5][1]: invalid type: string "x", expected f64 at line ${bad.line} column ${bad.column}`,
        );
        return true;
      },
    );
    // The same demo, well-formed, is accepted.
    const good = lfd.Session.fromScene(o, scene, JSON.stringify(demo, null, 2));
    assert.equal(good.frame().demo.length, demo.actions.length);
    good.free();
  });

  test('frames are camelCase; the episode log keeps the CLI names', () => {
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 });
    let f = s.frame();
    for (let i = 0; i < 20 && !f.lastReplan; i++) f = s.step(0.1);
    for (const k of ['demoStates', 'factsAdded', 'factsRemoved', 'lastReplan', 'matchedK']) assert.ok(k in f, k);
    for (const k of ['demo_states', 'facts_added', 'facts_removed', 'last_replan', 'matched_k']) assert.ok(!(k in f), k);
    assert.equal(typeof f.lastReplan.timeMs, 'number');
    assert.equal(typeof f.lastReplan.newActions, 'number');
    const log = JSON.parse(s.episodeJson());
    assert.equal(typeof log.replans[0].time_ms, 'number');
    assert.equal(typeof log.replans[0].new_actions, 'number');
    s.free();
  });

  test('the episode JSON replays to the same end state', () => {
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 5 });
    for (let i = 0; i < 40; i++) s.step(0.1);
    s.cancel();
    for (let i = 0; i < 20; i++) s.step(0.1);
    const json = s.episodeJson();
    const r = lfd.Session.replay(json);
    const a = s.frame();
    const b = r.frame();
    assert.equal(b.tick, a.tick);
    assert.deepEqual(b.facts, a.facts);
    assert.deepEqual(b.world.bodies, a.world.bodies);
    s.free();
    r.free();
  });
});
