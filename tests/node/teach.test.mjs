// Teach mode through the npm package: the recorder (`Teacher`), refusals as data, the taught
// demo.json, and a closed-loop `Session.fromTaught` run and its exact replay.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

function run(session, maxSteps = 4000) {
  let f = session.frame();
  for (let i = 0; i < maxSteps && f.status.kind !== 'done' && f.status.kind !== 'failed'; i++) f = session.step(0.1);
  return f;
}

describe('Teacher', () => {
  test('quick-mode drags become actions and demo states; a teleport is refused as data', () => {
    const t = new lfd.Teacher('b1');
    assert.equal(t.current().segments.length, 0);
    const r1 = t.push({ edit: 'drag', body: 'c', onto: 'b' });
    assert.ok(r1.ok);
    assert.deepEqual(
      r1.newSegments.map((s) => s.action),
      ['(pick panda c)', '(stack panda c b)'],
    );
    assert.equal(r1.state.states.length, 3);
    assert.ok(r1.state.states[2].includes('(on c b)'));
    // A block moved by hand onto another: not explained, with its time and change; nothing kept.
    const d = r1.state.world.bodies.find((b) => b.name === 'd').pose.position;
    const bad = t.push({ edit: 'move', body: 'a', position: [d[0], d[1], d[2] + 0.062] });
    assert.equal(bad.ok, false);
    assert.equal(bad.error.kind, 'unexplained');
    assert.equal(typeof bad.error.t, 'number');
    assert.ok(bad.error.added.includes('(on a d)'), JSON.stringify(bad.error));
    assert.match(bad.error.message, /^at t = \d+\.\d\d s: the change /);
    assert.equal(bad.state.segments.length, 2);
    assert.ok(bad.state.facts.includes('(ontable a)'));
    // Malformed edits are refused with the key, never thrown.
    const malformed = t.push({ edit: 'drag' });
    assert.equal(malformed.ok, false);
    assert.equal(malformed.error.kind, 'input');
    assert.match(t.push({ edit: 'drag', body: 'zz', onto: 'b' }).error.message, /zz/);
    // A non-object edit or a non-array goal is a TypeError (nothing recorded); the names are camelCase.
    assert.throws(() => t.push('drag'), (e) => e instanceof TypeError && /^Teacher\.push: edit must be an object, got string$/.test(e.message));
    assert.throws(() => t.setGoal('(on a c)'), (e) => e instanceof TypeError && /^Teacher\.setGoal: goal must be an array of strings, got string$/.test(e.message));
    assert.throws(() => t.setGoal([1]), TypeError);
    const seg = t.current().segments[0];
    assert.ok(seg.tStart <= seg.tEvent && seg.tEvent <= seg.tEnd, JSON.stringify(seg));

    assert.ok(t.push({ edit: 'drag', body: 'a', onto: 'c' }).ok);
    assert.ok(t.setGoal(['(on a c)', '(on c b)']).ok);
    assert.equal(t.setGoal(['(on x y)']).ok, false);
    const fin = t.finish();
    assert.ok(fin.ok, JSON.stringify(fin));
    assert.deepEqual(fin.info.goal, ['(on a c)', '(on c b)']);
    assert.equal(fin.skills.length, 8);
    for (const f of fin.skills) assert.ok(f.rmsError < 0.003, JSON.stringify(f));
    const demo = JSON.parse(fin.demoJson);
    assert.deepEqual(
      demo.actions.map((a) => a.action),
      ['(pick panda c)', '(stack panda c b)', '(pick panda a)', '(stack panda a c)'],
    );
    assert.deepEqual(lfd.taughtInfo(fin.demoJson).actions, fin.info.actions);
    assert.throws(() => lfd.taughtInfo('{"actions": []}'), /not a taught demonstration/);
    // The raw recording is what `logic-lfd demo segment` reads.
    assert.equal(JSON.parse(t.recordingJson()).benchmark, 'b1');

    // Undo removes the last action.
    const u = t.undo();
    assert.ok(u.ok);
    assert.equal(u.removed.action, '(stack panda a c)');
    assert.equal(u.state.segments.length, 3);
    t.free();

    // Run the taught task from a random world; its log replays exactly.
    const s = lfd.Session.fromTaught(fin.demoJson, { seed: 3, random: true });
    const f = run(s);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.ok(f.facts.includes('(on a c)') && f.facts.includes('(on c b)'));
    const again = lfd.Session.replayTaught(s.episodeJson());
    assert.deepEqual(again.frame().facts, f.facts);
    assert.equal(again.frame().tick, f.tick);
    assert.throws(() => lfd.Session.fromTaught(fin.demoJson, { sed: 3 }), /options: unknown field `sed`/);
    s.free();
    again.free();
  });

  test('Teacher.fromFolder records in a task folder; its taught task runs and replays with that folder', () => {
    const dir = new URL('../../domains/sorting/', import.meta.url);
    const files = {};
    for (const name of readdirSync(dir)) files[name] = readFileSync(new URL(name, dir), 'utf8');
    const folder = { files, dir: 'sorting' };
    const t = lfd.Teacher.fromFolder(files, { dir: 'sorting' });
    assert.equal(t.current().benchmark, null);
    assert.equal(t.current().folder, './sorting');
    const r = t.push({ edit: 'drag', body: 'r2', position: [0.39, 0.32] });
    assert.ok(r.ok, JSON.stringify(r.error));
    assert.deepEqual(
      r.newSegments.map((s) => s.action),
      ['(unstack panda r2 b2 pile)', '(place panda r2 red-tray)'],
    );
    assert.ok(t.setGoal(['(at r2 red-tray)']).ok);
    const fin = t.finish();
    assert.ok(fin.ok, JSON.stringify(fin));
    assert.equal(fin.info.folder, './sorting');
    t.free();
    // The taught demo needs its folder: without it the error says so.
    assert.throws(() => lfd.taughtInfo(fin.demoJson), /world `sorting` is none of the benchmarks.*task folder/);
    assert.deepEqual(lfd.taughtInfo(fin.demoJson, folder).actions, fin.info.actions);
    assert.throws(() => lfd.taughtInfo(fin.demoJson, { files, dri: 'x' }), /taughtInfo: folder: unknown field `dri`/);
    const s = lfd.Session.fromTaught(fin.demoJson, { seed: 1, random: true }, folder);
    const f = run(s);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.ok(f.facts.includes('(at r2 red-tray)'));
    const again = lfd.Session.replayTaught(s.episodeJson(), folder);
    assert.deepEqual(again.frame().facts, run(again).facts);
    s.free();
    again.free();
  });
});
