// Robots through the npm package: a shipped robot by name and a robot folder given by its files
// (texts and bytes) take the arms' place; a log replays on a shipped robot without its files; bad
// robots are refused with the file or the option at fault.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, readdirSync, statSync } from 'node:fs';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

const ROBOTS = new URL('../../robots/', import.meta.url);

/** Every file under `dir` (a URL ending in `/`), by its path below `root`, as bytes. */
function filesUnder(dir, root = dir, out = {}) {
  for (const name of readdirSync(dir)) {
    const at = new URL(name, dir);
    if (statSync(at).isDirectory()) filesUnder(new URL(`${name}/`, dir), root, out);
    else out[at.href.slice(root.href.length)] = new Uint8Array(readFileSync(at));
  }
  return out;
}

/** The UR5's robot folder: its robot file as `robot.json` (text) and the files it names (bytes). */
function ur5Folder() {
  const files = {};
  for (const [path, bytes] of Object.entries(filesUnder(new URL('example-robot-data/robots/ur_description/', ROBOTS)))) {
    files[`example-robot-data/robots/ur_description/${path}`] = bytes;
  }
  files['robot.json'] = readFileSync(new URL('ur5.json', ROBOTS), 'utf8');
  return files;
}

function run(session, maxSteps = 4000) {
  let f = session.frame();
  for (let i = 0; i < maxSteps && f.status.kind !== 'done' && f.status.kind !== 'failed'; i++) f = session.step(0.1);
  return f;
}

describe('robots', () => {
  test('the shipped UR5 builds B1 by name: six joints, and the log replays without its files', () => {
    const s = new lfd.Session({ benchmark: 'b1', seed: 1, robot: 'ur5' });
    const first = s.frame();
    assert.equal(first.world.arms[0].robot, 'ur5');
    const f = run(s);
    assert.equal(f.status.kind, 'done', f.status.message);
    // Equal but for the wall-clock planning times, which a replay writes as 0.
    const untimed = (json) => json.replace(/"(time_ms|bind_ms)":[0-9.e-]+/g, '"$1":0');
    const log = s.episodeJson();
    assert.equal(untimed(lfd.Session.replay(log).episodeJson()), untimed(log));
    s.free();
  });

  test('a robot folder given by its files runs as the same robot does by name', () => {
    const byName = new lfd.Session({ benchmark: 'b2', seed: 3, robot: 'ur5' });
    const byFiles = new lfd.Session({ benchmark: 'b2', seed: 3, robot: ur5Folder() });
    for (let i = 0; i < 60; i++) {
      const [a, b] = [byName.step(0.1), byFiles.step(0.1)];
      assert.deepEqual(b.world.arms, a.world.arms, `tick ${a.tick}`);
    }
    byName.free();
    byFiles.free();
  });

  test('B3 takes one robot per arm', () => {
    const s = new lfd.Session({ benchmark: 'b3', seed: 1, robot: ['panda', 'ur5'] });
    assert.deepEqual(s.frame().world.arms.map((a) => a.robot), ['panda', 'ur5']);
    s.free();
  });

  test('bad robots are refused with the option or the file at fault, and the options object is kept', () => {
    const options = { benchmark: 'b1', robot: 'ur10' };
    assert.throws(() => new lfd.Session(options), /options\.robot: no shipped robot `ur10` \(shipped: panda, ur5\)/);
    assert.equal(options.robot, 'ur10');
    assert.throws(() => new lfd.Session({ benchmark: 'b1', robot: 7 }), (e) => e instanceof TypeError && /options\.robot must be a robot's name/.test(e.message));
    assert.throws(() => new lfd.Session({ benchmark: 'b1', robot: [] }), TypeError);
    const folder = ur5Folder();
    delete folder['example-robot-data/robots/ur_description/meshes/ur5/collision/wrist2.stl'];
    assert.throws(() => new lfd.Session({ benchmark: 'b1', robot: folder }), /ur5_robot\.urdf:\d+:1: collision mesh .*wrist2\.stl/);
    assert.throws(() => new lfd.Session({ benchmark: 'b1', robot: { 'robot.json': 5 } }), /options\.robot\["robot\.json"\] must be a string, a Uint8Array or an ArrayBuffer, got number/);
    assert.throws(() => new lfd.Session({ benchmark: 'b3', robot: ['panda', 'ur5', 'ur5'] }), /3 robots for 2 arms/);
  });
});
