// Teach mode in the browser (Debian Chromium, headless): a person teaches a new 3-block tower
// (a on c on b — not B1's order) with real mouse drags, sees the actions and demo states appear,
// stops, and runs the taught task with Logic-LfD from a random initial world under an L3
// disturbance to "done". Also: a change the domain cannot explain is shown with its time and fact
// change, and nothing is recorded; the gripper handle moves the arm.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { join } from 'node:path';
import { finish, openApp, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

/** Screen points of a block's centre and of the centre of its top face, in the teacher's world. */
async function blockPoints(page, name) {
  return page.evaluate((name) => {
    const b = window.lfdTeach.state().world.bodies.find((x) => x.name === name);
    const [x, y, z] = b.pose.position;
    const hz = b.shape.type === 'cuboid' ? b.shape.half_extents[2] : 0;
    return { centre: window.lfd.screenPosition(name), top: window.lfd.project([x, y, z + hz]) };
  }, name);
}

/** Drags `body` with the mouse and drops it on the top face of `onto`. */
async function dragOnto(page, body, onto) {
  const from = (await blockPoints(page, body)).centre;
  const to = (await blockPoints(page, onto)).top;
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 12; i++) {
    await page.mouse.move(from.x + ((to.x - from.x) * i) / 12, from.y + ((to.y - from.y) * i) / 12);
  }
  await page.mouse.up();
}

/** Drags a part of the gripper handle so that the handle goes from world point `from` to `to`. */
async function dragHandle(page, part, from, to) {
  const lift = part === 'lift' ? 0.115 : 0;
  const [a, b] = await page.evaluate(
    ([f, t]) => [window.lfd.project(f), window.lfd.project(t)],
    [
      [from[0], from[1], from[2] + lift],
      [to[0], to[1], to[2] + lift],
    ],
  );
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(a.x + ((b.x - a.x) * i) / 10, a.y + ((b.y - a.y) * i) / 10);
  await page.mouse.up();
  await page.waitForFunction(() => !window.lfdTeach.busy(), null, { timeout: 10000, polling: 20 });
  return to;
}

const tcp = (page) => page.evaluate(() => window.lfdTeach.state().handles[0].position);
const body = (page, name) =>
  page.evaluate((name) => {
    const b = window.lfdTeach.state().world.bodies.find((x) => x.name === name);
    return { p: b.pose.position, hz: b.shape.type === 'cuboid' ? b.shape.half_extents[2] : 0 };
  }, name);

const segments = (page) => page.evaluate(() => window.lfdTeach.state()?.segments.map((s) => s.action) ?? []);
const idle = (page, n) =>
  page.waitForFunction((n) => !window.lfdTeach.busy() && window.lfdTeach.state()?.segments.length === n, n, { timeout: 20000, polling: 50 });

describe('teach', () => {
  test('teach a on c on b with mouse drags, then run it from a random world under L3 to done', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0&speed=2');
    await page.click('#tab-teach');
    await page.click('#teach-record');
    await page.waitForFunction(() => window.lfdTeach.state() !== null);
    assert.match(await page.textContent('#teach-list'), /L0/);

    await dragOnto(page, 'c', 'b');
    await idle(page, 2);
    assert.deepEqual(await segments(page), ['(pick panda c)', '(stack panda c b)']);
    // The listing shows the actions and the demo states as they appear.
    const listed = await page.textContent('#teach-list');
    assert.match(listed, /a1 \(pick panda c\)/);
    assert.match(listed, /L2/);

    await dragOnto(page, 'a', 'c');
    await idle(page, 4);
    assert.deepEqual(await segments(page), ['(pick panda c)', '(stack panda c b)', '(pick panda a)', '(stack panda a c)']);
    await page.screenshot({ path: join(screenshots, 'teach-recorded.png') });

    await page.click('#teach-stop');
    await page.waitForSelector('#teach-run-box:not([hidden])');
    assert.match(await page.textContent('#teach-summary'), /Taught 4 actions.*8 LQT-CP skills/);
    // Keep only the tower in the goal (uncheck every other fact of L4).
    const boxes = page.locator('#teach-goal input[type=checkbox]');
    const n = await boxes.count();
    for (let i = 0; i < n; i++) {
      const label = await boxes.nth(i).getAttribute('aria-label');
      if (!/\(on a c\)|\(on c b\)/.test(label)) await boxes.nth(i).uncheck();
    }
    await page.waitForFunction(() => window.lfdTeach.info().goal.length === 2, null, { timeout: 5000 });
    assert.deepEqual((await page.evaluate(() => window.lfdTeach.info().goal)).sort(), ['(on a c)', '(on c b)']);
    await page.screenshot({ path: join(screenshots, 'teach-stopped.png') });
    // Save the demo (a download) and load it back.
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#teach-save')]);
    const saved = JSON.parse(await readFile(await download.path(), 'utf8'));
    assert.deepEqual(saved.goal.sort(), ['(on a c)', '(on c b)']);
    assert.deepEqual(saved.actions.map((a) => a.action), ['(pick panda c)', '(stack panda c b)', '(pick panda a)', '(stack panda a c)']);
    await page.setInputFiles('#panel-teach input[type=file]', { name: 'taught.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(saved)) });
    await page.waitForFunction(() => /Loaded taught\.json: 4 actions/.test(document.querySelector('#teach-summary').textContent));

    // Run from a random initial world (seed 1); inject L3 once the robot has done an action.
    await page.click('#teach-run');
    await page.waitForFunction(() => document.querySelector('#tab-run').classList.contains('active'));
    const start = await page.evaluate(() => window.lfd.frame().facts);
    assert.ok(!(start.includes('(on a c)') && start.includes('(on c b)')), 'the random world already holds the goal');
    await page.waitForFunction(
      () => {
        const f = window.lfd.frame();
        return f && f.status.kind === 'executing' && (f.executing ?? 0) >= 1 && f.plan.length - (f.executing ?? 0) >= 3;
      },
      null,
      { timeout: 30000, polling: 20 },
    );
    const replansBefore = await page.evaluate(() => window.lfd.frame().replans);
    await page.keyboard.press('3');
    await page.waitForSelector('#notice:not([hidden])');
    assert.match(await page.textContent('#notice'), /^Scramble: /);
    const f = await finish(page, 60000);
    const info = JSON.stringify({ facts: f.facts, status: f.status, plan: f.plan, last: f.lastReplan, replans: f.replans });
    assert.equal(f.status.kind, 'done', info);
    assert.ok(f.facts.includes('(on a c)') && f.facts.includes('(on c b)'), info);
    // Logic-LfD replanned after the L3 change (not a lucky finish before it).
    assert.ok(f.replans > replansBefore, info);
    await page.screenshot({ path: join(screenshots, 'teach-run.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a teleport by hand is refused with its time and fact change; the gripper handle picks and places; undo', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0');
    await page.click('#tab-teach');
    await page.click('#teach-record');
    await page.waitForFunction(() => window.lfdTeach.state() !== null);
    // By hand, c onto d: the facts change with no robot action.
    await page.click('#teach-mode-hand');
    await dragOnto(page, 'c', 'd');
    await page.waitForSelector('#teach-error:not([hidden])', { timeout: 10000 });
    const msg = await page.textContent('#teach-error');
    assert.match(msg, /Not explained by the domain at t = \d+\.\d\d s/);
    assert.match(msg, /\+ \(on c d\)/);
    assert.match(msg, /− \(ontable c\)/);
    assert.deepEqual(await segments(page), []);
    const onTable = await page.evaluate(() => window.lfdTeach.state().facts.includes('(ontable c)'));
    assert.ok(onTable, 'the refused move was applied');
    await page.screenshot({ path: join(screenshots, 'teach-error.png') });

    // Gripper mode: drag the handle's ball sideways; the arm's TCP follows.
    await page.click('#teach-mode-gripper');
    const before = await page.evaluate(() => window.lfdTeach.state().handles[0].position);
    const p = await page.evaluate(() => window.lfdTeach.handle('move'));
    await page.mouse.move(p.x, p.y);
    await page.mouse.down();
    for (let i = 1; i <= 10; i++) await page.mouse.move(p.x - 8 * i, p.y + 4 * i);
    await page.mouse.up();
    await page.waitForFunction(() => !window.lfdTeach.busy(), null, { timeout: 10000 });
    const after = await page.evaluate(() => window.lfdTeach.state().handles[0].position);
    const moved = Math.hypot(after[0] - before[0], after[1] - before[1]);
    assert.ok(moved > 0.03, `the arm moved ${moved} m`);
    assert.ok(Math.abs(after[2] - before[2]) < 0.01, 'the ball keeps the height');

    // A pick and place with the handle alone: over c, down (blue arrow), G closes, up, over d,
    // down onto d, G opens, up. The recorder sees (pick panda c) then (stack panda c d).
    const c = await body(page, 'c');
    const d = await body(page, 'd');
    let at = await tcp(page);
    at = await dragHandle(page, 'move', at, [c.p[0], c.p[1], at[2]]);
    at = await dragHandle(page, 'lift', at, [c.p[0], c.p[1], c.p[2]]);
    await page.keyboard.press('g');
    await idle(page, 1);
    assert.deepEqual(await segments(page), ['(pick panda c)']);
    const high = d.p[2] + d.hz + 2 * c.hz + 0.12;
    at = await dragHandle(page, 'lift', at, [c.p[0], c.p[1], high]);
    at = await dragHandle(page, 'move', at, [d.p[0], d.p[1], high]);
    at = await dragHandle(page, 'lift', at, [d.p[0], d.p[1], d.p[2] + d.hz + c.hz + 0.004]);
    await page.screenshot({ path: join(screenshots, 'teach-gripper.png') });
    await page.keyboard.press('g');
    await idle(page, 2);
    at = await dragHandle(page, 'lift', at, [d.p[0], d.p[1], high]);
    assert.deepEqual(await segments(page), ['(pick panda c)', '(stack panda c d)']);
    assert.ok(await page.evaluate(() => window.lfdTeach.state().facts.includes('(on c d)')));

    // One Undo takes back the whole move (the place and its pick): back to the start, c on the table.
    await page.click('#teach-undo');
    await idle(page, 0);
    assert.ok(await page.evaluate(() => window.lfdTeach.state().facts.includes('(ontable c)')));
    assert.deepEqual(errors, []);
    await page.close();
  });
});
