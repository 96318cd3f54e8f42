// Browser tests of how the page answers a visitor (Debian Chromium, real mouse, touch and keyboard
// events): it stays reactive after done and failed, the world holds still under a drag, drops no
// arm can work are refused with the reason, and errors are shown whole.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { currentFrame, finish, openApp, screenshots, useBrowser } from './harness.mjs';
import { dragBody, dropPoint, waitStatus } from './ux-helpers.mjs';

const ctx = useBrowser({ withScreenshots: true });
const open = (query = '', viewport = undefined) => openApp(ctx.browser, ctx.server, query, viewport);

describe('always reactive', () => {
  test('a block dragged off the finished tower makes the robot replan and finish again', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1&speed=8');
    const start = (await currentFrame(page)).world.bodies.find((b) => b.name === 'a').pose.position;
    const done = await finish(page);
    assert.equal(done.status.kind, 'done', done.status.message);
    // Back to where a started: on the table, within reach.
    await dragBody(page, 'a', await dropPoint(page, start));
    await waitStatus(page, ['done'], { not: true, timeout: 10000 });
    const again = await finish(page);
    assert.equal(again.status.kind, 'done', again.status.message);
    assert.ok(again.replans > done.replans, `replans ${done.replans} → ${again.replans}`);
    assert.ok(again.t > done.t, 'the arm worked again');
    assert.ok(again.facts.includes('(on a b)'), again.facts.join(' '));
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Play after a failure the user fixed resumes the run', async () => {
    // Linear follows the demonstration blindly: a put onto d early on makes its (pick a) fail
    // under the c it stacked there.
    const { page, errors } = await open('?benchmark=b1&seed=1&method=linear&speed=8&autoplay=0');
    for (let i = 0; i < 5; i++) await page.click('#step');
    await page.waitForFunction(() => window.lfd.frame()?.tick === 50);
    await page.click('#inject-l3');
    const failed = await finish(page);
    assert.equal(failed.status.kind, 'failed', failed.status.message);
    // The reason is one sentence, shown whole.
    assert.doesNotMatch(failed.status.message, /failed: failed/);
    await page.waitForFunction(() => document.querySelector('#status-text')?.textContent?.startsWith('failed because'));
    assert.ok(await page.$eval('#status-text', (e) => e.scrollWidth <= e.clientWidth + 1 && e.scrollHeight <= e.clientHeight + 1), 'the reason is cut off');
    // The failed step is marked in the plan.
    assert.match(await page.$eval('#plan li.failed', (e) => e.textContent), /\(pick panda a\)/);
    await page.screenshot({ path: join(screenshots, 'ux-failed-1440.png') });
    // Press Play: nothing to resume yet, the page says what to do.
    await page.click('#play');
    await page.waitForSelector('#notice:not([hidden])');
    assert.match(await page.textContent('#notice'), /move a block/i);
    // Fix the scene: move the block lying on the one the arm must lift (and what it carries) to the table.
    const blocker = failed.facts
      .map((x) => /^\(on (\S+) (\S+)\)$/.exec(x))
      .find((m) => m && /cannot lift (\w+)/.exec(failed.status.message)?.[1] === m[2]);
    assert.ok(blocker, `no block in the way in ${failed.facts.join(' ')}: ${failed.status.message}`);
    const free = await page.evaluate(() => {
      const f = window.lfd.frame();
      const base = f.world.arms[0].base.position;
      const blocks = f.world.bodies.filter((b) => b.kind === 'block');
      for (let a = -1.2; a <= 1.2; a += 0.15) {
        const x = base[0] + 0.5 * Math.cos(a);
        const y = base[1] + 0.5 * Math.sin(a);
        if (blocks.every((o) => Math.hypot(o.pose.position[0] - x, o.pose.position[1] - y) > 0.12)) return [x, y];
      }
      return null;
    });
    assert.ok(free);
    await dragBody(page, blocker[1], await dropPoint(page, [free[0], free[1], 0]));
    await waitStatus(page, ['failed'], { not: true, timeout: 10000 });
    const tick = (await currentFrame(page)).tick;
    await page.waitForTimeout(500);
    assert.equal((await currentFrame(page)).tick, tick, 'a failed run waits for Play after the fix');
    await page.click('#play');
    await page.waitForFunction((t) => window.lfd.frame().tick > t + 20, tick, { timeout: 20000 });
    assert.notEqual((await currentFrame(page)).status.kind, 'failed');
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('honest interaction', () => {
  test('the world holds still while the user drags a block, and goes on after the drop', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=2');
    await waitStatus(page, ['executing']);
    const f0 = await currentFrame(page);
    const free = f0.world.bodies.find((b) => b.kind === 'block' && !f0.world.arms.some((a) => a.holding === b.name) && b.name !== 'd');
    const from = await page.evaluate((n) => window.lfd.screenPosition(n), free.name);
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.waitForTimeout(150);
    const t0 = (await currentFrame(page)).t;
    // A slow drag: two seconds of small moves.
    for (let i = 0; i < 20; i++) {
      await page.mouse.move(from.x + i, from.y + i / 2);
      await page.waitForTimeout(100);
    }
    const during = await currentFrame(page);
    assert.equal(during.t, t0, 'the simulation advanced during the drag');
    assert.ok(!during.world.arms.some((a) => a.holding === free.name), 'the gripper took the held block');
    // Back where it was: the drop is accepted and the run plays on.
    await page.mouse.move(from.x, from.y, { steps: 5 });
    await page.mouse.up();
    await page.waitForFunction((t) => window.lfd.frame().t > t + 0.2, t0, { timeout: 20000 });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a drop no arm can reach is refused with the reason, the reach shaded meanwhile; nothing moves', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1&autoplay=0');
    const f0 = await currentFrame(page);
    // The corner of the table farthest from the arm's base.
    const corner = await page.evaluate(() => {
      const f = window.lfd.frame();
      const base = f.world.arms[0].base.position;
      const t = f.world.bodies.find((b) => b.kind === 'table');
      if (t.shape.type !== 'cuboid') return null;
      const [hx, hy] = t.shape.half_extents;
      const corners = [-1, 1].flatMap((sx) => [-1, 1].map((sy) => [t.pose.position[0] + sx * (hx - 0.03), t.pose.position[1] + sy * (hy - 0.03)]));
      return corners.sort((p, q) => Math.hypot(q[0] - base[0], q[1] - base[1]) - Math.hypot(p[0] - base[0], p[1] - base[1]))[0];
    });
    assert.ok(corner);
    const to = await dropPoint(page, [corner[0], corner[1], 0]);
    await page.waitForSelector('.stage canvas[data-extras="loaded"]');
    const from = await page.evaluate(() => window.lfd.screenPosition('a'));
    await page.mouse.move(from.x, from.y);
    await page.mouse.down();
    await page.mouse.move(to.x, to.y, { steps: 10 });
    assert.equal(await page.getAttribute('.stage canvas', 'data-reach-shown'), 'true', 'the reach is shaded while dragging');
    assert.equal(await page.getAttribute('.stage canvas', 'data-drop-reachable'), 'false', 'the ghost says the spot is out of reach');
    await page.screenshot({ path: join(screenshots, 'ux-reach-1440.png') });
    await page.mouse.up();
    await page.waitForSelector('#notice.error:not([hidden])');
    const notice = await page.textContent('#notice');
    assert.match(notice, /^Drop refused: cannot move a: no arm could grasp it there/);
    assert.ok(await page.$eval('#notice', (e) => e.scrollWidth <= e.clientWidth + 1), 'the message is cut off');
    assert.equal(await page.getAttribute('.stage canvas', 'data-reach-shown'), 'false');
    const f1 = await currentFrame(page);
    assert.deepEqual(f1.world.bodies.find((b) => b.name === 'a').pose, f0.world.bodies.find((b) => b.name === 'a').pose);
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('loading', () => {
  test('a broken scene file is refused with the field named, and the run goes on unchanged', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1');
    await waitStatus(page, ['executing']);
    const scene = JSON.parse(await page.evaluate(() => JSON.stringify(window.lfd.frame().world)));
    const block = scene.bodies.findIndex((b) => b.kind === 'block');
    scene.bodies[block].shape.half_extents[0] = -0.02;
    const chooser = page.waitForEvent('filechooser');
    await page.click('#load-scene');
    await (await chooser).setFiles({ name: 'broken-scene.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(scene)) });
    await page.waitForSelector('#notice.error:not([hidden])');
    const msg = await page.textContent('#notice');
    assert.match(msg, /^broken-scene\.json was not loaded: /);
    assert.match(msg, new RegExp(`bodies\\[${block}\\]|${scene.bodies[block].name}`), msg);
    assert.match(msg, /half.extents|size/i, msg);
    // The same session plays on.
    const t = (await currentFrame(page)).t;
    await page.waitForFunction((t) => window.lfd.frame().t > t + 0.3, t, { timeout: 20000 });
    assert.equal(await page.getAttribute('#play', 'aria-pressed'), 'true');
    assert.notEqual((await currentFrame(page)).status.kind, 'failed');
    assert.deepEqual(errors, []);
    await page.close();
  });
});
