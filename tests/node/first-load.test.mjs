// The page's first-load module (pkg/page/logic_lfd_bg.wasm, what the page's worker starts on):
// it runs B1's template task on the built-in Panda (its DH chain and capsules), and the npm
// package replays that episode byte for byte (what the page's speed-up relies on) and runs the
// same episode on the Panda from its URDF with the same plans, actions and ticks. It refuses, with
// a message, what it leaves to the full module (B2, B3, N-block tasks, loaded scenes), which the
// worker then opens there.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const page = await import(new URL('../../pkg/page/logic_lfd.js', import.meta.url).href);
page.initSync({ module: readFileSync(new URL('../../pkg/page/logic_lfd_bg.wasm', import.meta.url)) });
const full = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

/** A log with the wall-clock times zeroed. */
function untimed(json) {
  const log = JSON.parse(json);
  for (const r of log.replans) r.time_ms = r.bind_ms = 0;
  return log;
}

/** An episode with injected disturbances: its status, replans, raw log and untimed log. */
function episode(mod, options) {
  const s = new mod.Session(options);
  try {
    const inject = [[1, 'l3'], [4, 'l4'], [7, 'l2']];
    let f = s.frame();
    while (!['done', 'failed'].includes(f.status.kind)) {
      if (inject.length && f.t > inject[0][0]) {
        const level = inject.shift()[1];
        if (s.canInject(level) === undefined) s.inject(level);
      }
      f = s.step(1 / 30);
    }
    const raw = s.episodeJson();
    return { status: f.status.kind, replans: f.replans, raw, log: untimed(raw) };
  } finally {
    s.free();
  }
}

describe("the page's first-load module", () => {
  for (const mode of ['paper', 'prioritised']) {
    test(`runs B1 (${mode}) as the npm package does, and the package replays it byte for byte`, () => {
      const options = { benchmark: 'b1', method: 'logic-lfd', mode, seed: 3 };
      const a = episode(page, options);
      assert.equal(a.status, 'done');
      assert.ok(a.replans >= 3, `${a.replans} replans`);
      assert.equal(a.log.scene.arms[0].robot, undefined, 'the first-load module runs the built-in Panda');
      const replayed = full.Session.replay(a.raw);
      assert.equal(JSON.stringify(untimed(replayed.episodeJson())), JSON.stringify(a.log));
      replayed.free();
      // The package's own episode: the Panda from its URDF, the same plans, actions and ticks.
      const b = episode(full, options);
      assert.equal(b.log.scene.arms[0].robot, 'panda');
      for (const key of ['events', 'replans', 'actions', 'ticks', 'result', 'final_facts']) {
        assert.deepEqual(b.log[key], a.log[key], key);
      }
    });
  }

  test('refuses B2, B3 and N-block tasks with a message; the full module opens them', () => {
    for (const options of [
      { benchmark: 'b2', method: 'logic-lfd', mode: 'paper', seed: 1 },
      { benchmark: 'b3', method: 'tamp', mode: 'paper', seed: 1 },
      { benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: 5 },
    ]) {
      assert.throws(() => new page.Session(options), /on the page's full module, not its first-load module/);
      const s = new full.Session(options);
      assert.equal(s.frame().status.kind === 'failed', false);
      s.free();
    }
    assert.throws(() => page.benchmark('b3'), /b3 runs on the page's full module/);
    assert.equal(page.benchmark('b1').name, 'b1-tower');
    assert.equal(full.benchmark('b3').name, 'b3-dual-arm');
  });

  test('leaves loaded scenes to the full module', () => {
    assert.equal(page.Session.fromScene, undefined);
    assert.equal(typeof full.Session.fromScene, 'function');
  });

  test('leaves task folders to the full module', () => {
    assert.equal(page.Session.fromFolder, undefined);
    assert.equal(page.Session.prototype.taskFiles, undefined);
    assert.equal(typeof full.Session.fromFolder, 'function');
    assert.equal(typeof full.Session.prototype.taskFiles, 'function');
  });
});
