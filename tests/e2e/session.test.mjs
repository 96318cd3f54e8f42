// Browser tests of the page (Debian Chromium, headless, WebGL through SwiftShader), driven with
// real mouse and keyboard events against the production build in web/dist.
import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdir } from 'node:fs/promises';
import { join } from 'node:path';
import { currentFrame, finish, launch, openApp, screenshots, serve } from './harness.mjs';

let server;
let browser;

before(async () => {
  server = await serve();
  browser = await launch();
  await mkdir(screenshots, { recursive: true });
});

after(async () => {
  await browser?.close();
  await server?.close();
});

const open = (query = '') => openApp(browser, server, query);
const frame = currentFrame;

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
const noSession = typeof lfd.Session === 'function' ? false : 'this build has no closed-loop Session yet';

describe('closed-loop session in the page', { skip: noSession }, () => {
  test('draws B1: blocks, tables and the arm from its link capsules', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    const f = await frame(page);
    assert.ok(f, 'no frame');
    assert.ok(f.world.name.startsWith('b1'), `scene ${f.world.name}`);
    assert.equal(f.world.bodies.filter((b) => b.kind === 'block').length, 4);
    assert.ok(f.world.arms.length >= 1 && f.world.arms[0].links.length > 0);
    assert.equal(f.status.kind === 'failed', false, f.status.message);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('B1 runs to success', async () => {
    const { page, errors } = await open('?benchmark=b1&speed=8&seed=1');
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.match(await page.textContent('#status-text'), /done/i);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('dragging a block during execution makes the robot replan and still succeed', async () => {
    const { page, errors } = await open('?benchmark=b1&speed=2&seed=3');
    // Wait until the robot has put at least one block on another (the tower is growing).
    await page.waitForFunction(
      () => {
        const f = window.lfd.frame();
        return f && f.status.kind === 'executing' && (f.executing ?? 0) >= 2;
      },
      null,
      { timeout: 60000, polling: 100 },
    );
    // Drag the top-most clear block that the arm is not holding onto the free table.
    const target = await page.evaluate(() => {
      const f = window.lfd.frame();
      const held = new Set(f.world.arms.map((a) => a.holding).filter(Boolean));
      const blocks = f.world.bodies.filter((b) => b.kind === 'block' && !held.has(b.name) && !b.lost);
      const clear = blocks.filter((b) => f.facts.includes(`(clear ${b.name})`));
      clear.sort((a, b) => b.pose.position[2] - a.pose.position[2]);
      const pick = clear[0];
      const table = f.world.bodies.find((b) => b.kind === 'table');
      const [tx, ty, tz] = table.pose.position;
      const half = table.shape.type === 'cuboid' ? table.shape.half_extents : [0.3, 0.3, 0.02];
      // A free spot near the table's front-left corner, on its top face.
      /** @type {[number, number, number]} */
      const drop = [tx - half[0] * 0.6, ty - half[1] * 0.6, tz + half[2] + 0.03];
      return { name: pick.name, from: window.lfd.screenPosition(pick.name), to: window.lfd.project(drop) };
    });
    await page.mouse.move(target.from.x, target.from.y);
    await page.mouse.down();
    for (let i = 1; i <= 12; i++) {
      await page.mouse.move(
        target.from.x + ((target.to.x - target.from.x) * i) / 12,
        target.from.y + ((target.to.y - target.from.y) * i) / 12,
      );
    }
    await page.mouse.up();
    await page.waitForFunction(
      () => {
        const f = window.lfd.frame();
        return f && (f.status.kind === 'replanning' || (f.last_replan && f.replans > 0));
      },
      null,
      { timeout: 20000, polling: 20 },
    );
    const seen = await page.evaluate(() => {
      const f = window.lfd.frame();
      return { replans: f.replans, reason: f.last_replan?.reason ?? f.status.message };
    });
    assert.ok(seen.replans >= 1, `expected a replan after moving ${target.name}`);
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.deepEqual(errors, []);
    await page.close();
  });

  for (const level of ['l1', 'l2', 'l3', 'l4']) {
    test(`the ${level.toUpperCase()} button disturbs the run and the run still ends`, async () => {
      const { page, errors } = await open(`?benchmark=b1&speed=4&seed=2`);
      await page.waitForFunction(() => (window.lfd.frame()?.t ?? 0) > 1.0, null, { timeout: 30000 });
      const before = await frame(page);
      await page.click(`#inject-${level}`);
      await page.waitForSelector('#notice:not([hidden])', { timeout: 10000 });
      const text = await page.textContent('#notice');
      assert.match(text, new RegExp(level, 'i'));
      assert.doesNotMatch(text, /refused/i, text);
      const f = await finish(page);
      assert.ok(f.tick > before.tick);
      if (level !== 'l1') assert.ok(f.replans >= 1 || f.status.kind === 'done', f.status.message);
      assert.equal(f.status.kind, 'done', f.status.message);
      assert.deepEqual(errors, []);
      await page.close();
    });
  }

  for (const b of ['b1', 'b2', 'b3']) {
    test(`screenshot of ${b.toUpperCase()}`, async () => {
      const { page, errors } = await open(`?benchmark=${b}&speed=2&seed=1`);
      await page.waitForFunction(() => (window.lfd.frame()?.t ?? 0) > 3, null, { timeout: 60000 });
      await page.waitForTimeout(300);
      await page.screenshot({ path: join(screenshots, `${b}.png`) });
      assert.deepEqual(errors, []);
      await page.close();
    });
  }
});
