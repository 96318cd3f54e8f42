// A task folder given by its files through the npm package: a session and an episode on a task
// that is not a benchmark (B1 in the paper's naming), its replay from a log that carries the
// files, and errors that name the file at fault.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readdirSync, readFileSync } from 'node:fs';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

const DIR = new URL('../../domains/b1-paper-naming/', import.meta.url);

/** The folder's files by name, as a page or a script reads them. */
function folderFiles() {
  /** @type {Record<string, string>} */
  const files = {};
  for (const name of readdirSync(DIR)) files[name] = readFileSync(new URL(name, DIR), 'utf8');
  return files;
}

/** Steps to done or failed, injecting `level` once the robot has executed `after` actions. */
function run(session, level = null, after = 2) {
  let f = session.frame();
  let injected = null;
  for (let i = 0; i < 4000 && f.status.kind !== 'done' && f.status.kind !== 'failed'; i++) {
    if (level && !injected && f.executing !== null && f.executing >= after && session.canInject(level) === undefined) {
      injected = session.inject(level);
    }
    f = session.step(0.1);
  }
  return { frame: f, injected };
}

const TOWER = ['(on-block a b)', '(on-block b c)', '(on-block c d)'];

describe('task folders', () => {
  test('a folder of its own names runs, is disturbed at L3 and still builds its tower', () => {
    const s = lfd.Session.fromFolder(folderFiles(), { dir: 'b1-paper-naming', method: 'logic-lfd', mode: 'paper', seed: 3 });
    const first = s.frame();
    assert.ok(first.demo.every((a) => /^\((pick-up|put-down|put-on|take-off) /.test(a)), first.demo.join(' '));
    const { frame, injected } = run(s, 'l3');
    assert.ok(injected, 'L3 was injected');
    assert.equal(frame.status.kind, 'done', frame.status.message);
    assert.ok(frame.replans >= 2, `replans: ${frame.replans}`);
    for (const g of TOWER) assert.ok(frame.facts.includes(g), `${g} missing from ${frame.facts.join(' ')}`);

    // The log names the folder and each file's hash; without the files it cannot replay alone.
    const bare = s.episodeJson();
    const log = JSON.parse(bare);
    assert.equal(log.folder.dir, './b1-paper-naming');
    assert.deepEqual(Object.keys(log.folder.hashes).sort(), ['demo.json', 'domain.pddl', 'expert.json', 'motions.json', 'problem.pddl', 'scene.json']);
    assert.equal(log.folder.files, undefined);
    assert.throws(() => lfd.Session.replay(bare), /task folder \.\/b1-paper-naming, which the log does not carry/);

    // With the files carried, the replay ends where the episode ended, and its own log carries them too.
    const carried = s.episodeJson({ withFiles: true });
    assert.deepEqual(JSON.parse(carried).folder.files, folderFiles());
    const r = lfd.Session.replay(carried);
    assert.deepEqual(r.frame().facts, frame.facts);
    assert.equal(r.frame().replans, frame.replans);
    const again = JSON.parse(r.episodeJson({ withFiles: true }));
    assert.deepEqual(again.events, log.events);
    assert.deepEqual(again.folder.files, folderFiles());
    assert.deepEqual(r.folderFiles(), folderFiles());
    s.free();
    r.free();
  });

  test('runEpisode runs a folder at L3 and its log, carrying the files, replays to the same end', () => {
    const opts = { folder: folderFiles(), dir: 'b1-paper-naming', level: 'l3', method: 'logic-lfd', mode: 'paper', seed: 5, withFiles: true };
    const report = JSON.parse(lfd.runEpisode(JSON.stringify(opts)));
    assert.equal(report.success, true, JSON.stringify(report.reason));
    assert.ok(report.log.events.some((e) => e.event === 'inject' && e.level === 'l3'), JSON.stringify(report.log.events));
    assert.deepEqual(report.log.folder.files, folderFiles());
    const r = lfd.Session.replay(JSON.stringify(report.log));
    assert.equal(r.frame().status.kind, 'done');
    assert.deepEqual(r.frame().facts, report.log.final_facts);
    r.free();
    // Without `withFiles` the log keeps hashes only, as `logic-lfd run --json` prints it.
    const plain = JSON.parse(lfd.runEpisode(JSON.stringify({ ...opts, withFiles: false })));
    assert.equal(plain.log.folder.files, undefined);
  });

  test('the task files are the folder’s, and a generated N-block task shows its own problem', () => {
    const files = folderFiles();
    const s = lfd.Session.fromFolder(files, { dir: 'mine' });
    const t = s.taskFiles();
    assert.equal(t.domain, files['domain.pddl']);
    assert.equal(t.problem, files['problem.pddl']);
    assert.equal(t.dir, './mine');
    assert.match(t.demoPlan, /^\(pick-up /);
    s.free();
    const b = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: 7 });
    const bt = b.taskFiles();
    assert.notEqual(bt.problem, lfd.benchmark('b1').problem);
    for (const x of ['a', 'b', 'c', 'd', 'e', 'f', 'g']) assert.match(bt.problem, new RegExp(`\\b${x}\\b`));
    b.free();
  });

  test('a missing file is named, with what a folder holds', () => {
    const files = folderFiles();
    delete files['motions.json'];
    assert.throws(
      () => lfd.Session.fromFolder(files, { dir: 'mine' }),
      (/** @type {Error} */ e) => e.message.startsWith('./mine/motions.json: missing: a task folder holds domain.pddl, problem.pddl, motions.json, scene.json'),
    );
    assert.throws(() => lfd.runEpisode(JSON.stringify({ folder: files, dir: 'mine' })), /^Error: \.\/mine\/motions\.json: missing/);
    const noDemo = folderFiles();
    delete noDemo['demo.json'];
    delete noDemo['expert.json'];
    assert.throws(() => lfd.Session.fromFolder(noDemo, { dir: 'mine' }), /^Error: \.\/mine\/demo\.json: missing: give demo\.json, or expert\.json/);
  });

  test('a broken scene, domain or demonstration names its file', () => {
    const broken = (name, text) => ({ ...folderFiles(), [name]: text });
    const message = (files) => {
      try {
        lfd.Session.fromFolder(files, { dir: 'mine' }).free();
      } catch (e) {
        return e.message;
      }
      assert.fail('accepted a broken folder');
    };
    const scene = message(broken('scene.json', '{ "bodies": [ }'));
    assert.match(scene, /^\.\/mine\/scene\.json: /, scene);
    const domain = message(broken('domain.pddl', folderFiles()['domain.pddl'].replace(':action put-on', ':action')));
    assert.match(domain, /^\.\/mine\/domain\.pddl:\d+:\d+: /, domain);
    const demo = message(broken('demo.json', '{"actions": [1]}'));
    assert.match(demo, /^\.\/mine\/demo\.json: /, demo);
    // Recorded from expert.json: a broken scene is named there too.
    const recorded = broken('scene.json', '[]');
    delete recorded['demo.json'];
    assert.match(message(recorded), /^\.\/mine\/scene\.json: /);
  });

  test('bad arguments are type errors naming the parameter', () => {
    assert.throws(() => lfd.Session.fromFolder('domains/b1-paper-naming'), { name: 'TypeError', message: /files must be an object, got string/ });
    assert.throws(() => lfd.Session.fromFolder({ 'scene.json': 3 }), { name: 'TypeError', message: /files\["scene\.json"\] must be the file's text/ });
    assert.throws(() => lfd.Session.fromFolder(folderFiles(), { benchmark: 'b1' }), /options: unknown field `benchmark`/);
    const s = new lfd.Session({ benchmark: 'b1', seed: 1 });
    assert.throws(() => s.episodeJson({ withFiles: 'yes' }), { name: 'TypeError' });
    // A benchmark's log has no folder to carry.
    assert.equal(JSON.parse(s.episodeJson({ withFiles: true })).folder, undefined);
    s.free();
  });
});
