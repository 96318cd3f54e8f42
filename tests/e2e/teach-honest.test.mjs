// Teach mode says what it records: while a block is dragged the block that would receive it is
// outlined and a contact footprint lies where it would land (on that block, else on the table);
// the drop's actions and fact change show at once over the view; Undo takes back a whole move
// (pick and place); after Stop the goal and the recorded moves can be edited, checked again, and
// the run gets the edited demonstration. Screenshots at 1440, 1024 and on a phone (touch).
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { finish, openApp, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

const segments = (page) => page.evaluate(() => window.lfdTeach.state()?.segments.map((s) => s.action) ?? []);
const idle = (page, n) =>
  page.waitForFunction((n) => !window.lfdTeach.busy() && window.lfdTeach.state()?.segments.length === n, n, { timeout: 20000, polling: 50 });
const teachBody = (page, name) =>
  page.evaluate((name) => {
    const b = window.lfdTeach.state().world.bodies.find((x) => x.name === name);
    return { p: b.pose.position, hz: b.shape.type === 'cuboid' ? b.shape.half_extents[2] : 0 };
  }, name);

/** Screen points: `body`'s centre, the centre of `onto`'s top face, and a table point behind
 * `onto` (away from the camera) that the screen shows just above `onto`'s top. */
async function points(page, body, onto) {
  return page.evaluate(
    ([body, onto]) => {
      const w = window.lfdTeach.state().world;
      const b = w.bodies.find((x) => x.name === onto);
      const [x, y, z] = b.pose.position;
      const hz = b.shape.type === 'cuboid' ? b.shape.half_extents[2] : 0;
      // Away from the camera: of the table points 15 cm around the block, the highest on screen.
      let behind = null;
      for (let k = 0; k < 72; k++) {
        const a = (k * Math.PI) / 36;
        const q = window.lfd.project([x + 0.15 * Math.cos(a), y + 0.15 * Math.sin(a), z - hz]);
        if (!behind || q.y < behind.y) behind = q;
      }
      return { from: window.lfd.screenPosition(body), top: window.lfd.project([x, y, z + hz]), behind, tableZ: z - hz, topZ: z + hz };
    },
    [body, onto],
  );
}

/** Mouse-drags from `from` to `to` and keeps the button down (the caller releases). */
async function hold(page, from, to) {
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  for (let i = 1; i <= 12; i++) await page.mouse.move(from.x + ((to.x - from.x) * i) / 12, from.y + ((to.y - from.y) * i) / 12);
}

async function startRecording(page) {
  await page.click('#tab-teach');
  await page.click('#teach-record');
  await page.waitForFunction(() => window.lfdTeach.state() !== null);
}

describe('teach says what it records', () => {
  test('a drag over a block outlines it and shadows its top; the drop stacks and its actions and fact change show at once', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0');
    await startRecording(page);
    const pt = await points(page, 'c', 'd');
    await hold(page, pt.from, pt.top);
    const hint = await page.evaluate(() => window.lfdTeach.dropHint());
    assert.equal(hint?.onto, 'd', JSON.stringify(hint));
    assert.ok(Math.abs(hint.shadow[2] - pt.topZ) < 0.005, `the footprint lies on d's top: ${JSON.stringify(hint)}`);
    await page.screenshot({ path: join(screenshots, 'teach-1440.png') });
    await page.screenshot({ path: join(screenshots, 'teach-drop-close.png'), clip: { x: pt.top.x - 100, y: pt.top.y - 110, width: 200, height: 200 } });
    await page.mouse.up();
    assert.equal(await page.evaluate(() => window.lfdTeach.dropHint()), null, 'the marks go with the drag');
    // The recorded actions and the fact change show over the view as soon as the drop is recorded.
    await page.waitForSelector('#teach-toast:not([hidden])', { timeout: 20000 });
    assert.deepEqual(await segments(page), ['(pick panda c)', '(stack panda c d)']);
    const toast = await page.textContent('#teach-toast');
    assert.match(toast, /a1 \(pick panda c\).*a2 \(stack panda c d\)/);
    assert.match(toast, /\+ \(on c d\)/);
    assert.match(toast, /− \(ontable c\)/);
    assert.doesNotMatch(toast, /holding/, 'the net change of the move, not of its pick alone');
    const box = await page.$eval('#teach-toast', (e) => e.getBoundingClientRect().toJSON());
    const stage = await page.$eval('.stage', (e) => e.getBoundingClientRect().toJSON());
    assert.ok(box.top >= stage.top && box.bottom <= stage.bottom && box.right <= stage.right, 'the toast is over the view');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('one Undo takes back the whole move: its place and its pick', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0');
    await startRecording(page);
    const c0 = await teachBody(page, 'c');
    const pt = await points(page, 'c', 'd');
    await hold(page, pt.from, pt.top);
    await page.mouse.up();
    await idle(page, 2);
    assert.deepEqual(await segments(page), ['(pick panda c)', '(stack panda c d)']);

    // One Undo: the whole move (its place and its pick) is gone, c is back where it was.
    await page.click('#teach-undo');
    await page.waitForFunction(() => /Undid/.test(document.querySelector('#notice')?.textContent ?? '') && !window.lfdTeach.busy(), null, { timeout: 10000 });
    assert.deepEqual(await segments(page), [], 'one Undo leaves no half move');
    const c1 = await teachBody(page, 'c');
    assert.ok(Math.hypot(c1.p[0] - c0.p[0], c1.p[1] - c0.p[1], c1.p[2] - c0.p[2]) < 0.003, `c is back: ${JSON.stringify([c0, c1])}`);
    assert.ok(await page.evaluate(() => window.lfdTeach.state().facts.includes('(ontable c)')));
    assert.match(await page.textContent('#notice'), /Undid \(stack panda c d\) and \(pick panda c\)/);
    // The toast says what was undone, with the change it takes back.
    const toast = await page.textContent('#teach-toast');
    assert.match(toast, /Undone a1 \(pick panda c\) · a2 \(stack panda c d\)/);
    assert.match(toast, /\+ \(ontable c\)/);
    assert.match(toast, /− \(on c d\)/);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a drop just behind a block (it looks like on top from this camera) is shown on the table and recorded as a place', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0', { width: 1024, height: 768 });
    await startRecording(page);
    const pt = await points(page, 'c', 'd');
    assert.ok(pt.behind.y < pt.top.y && pt.top.y - pt.behind.y < 60, `the table point shows just above d's top: ${JSON.stringify(pt)}`);
    await hold(page, pt.from, pt.behind);
    const hint = await page.evaluate(() => window.lfdTeach.dropHint());
    assert.equal(hint?.onto, null, JSON.stringify(hint));
    assert.ok(Math.abs(hint.shadow[2] - pt.tableZ) < 0.005, `the footprint lies on the table: ${JSON.stringify(hint)}`);
    await page.mouse.up();
    await idle(page, 2);
    const segs = await segments(page);
    assert.equal(segs[0], '(pick panda c)');
    assert.match(segs[1], /^\(place panda c\b/);
    // c is on the table again: no fact changed, and the toast says so (not a tower).
    assert.match(await page.textContent('#teach-toast'), /a2 \(place panda c.*facts unchanged/);
    // The 1024 screenshot shows a drag over a block with its outline and footprint.
    await hold(page, (await points(page, 'a', 'b')).from, (await points(page, 'a', 'b')).top);
    assert.equal((await page.evaluate(() => window.lfdTeach.dropHint()))?.onto, 'b');
    await page.screenshot({ path: join(screenshots, 'teach-1024.png') });
    await page.mouse.up();
    await idle(page, 4);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('on a phone a touch drag shows the outline and footprint', async () => {
    const page = await ctx.browser.newPage({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`${ctx.server.url}?benchmark=b1&autoplay=0`);
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
    await startRecording(page);
    await page.evaluate(() => window.scrollTo(0, 0));
    const pt = await points(page, 'c', 'd');
    const cdp = await page.context().newCDPSession(page);
    const touch = (type, p) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: p ? [{ x: p.x, y: p.y }] : [] });
    await touch('touchStart', pt.from);
    for (let i = 1; i <= 10; i++) await touch('touchMove', { x: pt.from.x + ((pt.top.x - pt.from.x) * i) / 10, y: pt.from.y + ((pt.top.y - pt.from.y) * i) / 10 });
    const hint = await page.evaluate(() => window.lfdTeach.dropHint());
    assert.equal(hint?.onto, 'd', JSON.stringify(hint));
    await page.screenshot({ path: join(screenshots, 'teach-phone.png') });
    await touch('touchEnd');
    await idle(page, 2);
    assert.deepEqual(await segments(page), ['(pick panda c)', '(stack panda c d)']);
    await page.waitForSelector('#teach-toast:not([hidden])');
    const box = await page.$eval('#teach-toast', (e) => e.getBoundingClientRect().toJSON());
    assert.ok(box.left >= 0 && box.right <= 390, `the toast fits the phone: ${JSON.stringify(box)}`);
    await page.screenshot({ path: join(screenshots, 'teach-phone-recorded.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('after Stop the goal is edited and a move deleted, each checked again; the run gets the edited demo', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0&speed=4');
    await startRecording(page);
    for (const [body, onto, n] of [
      ['c', 'b', 2],
      ['a', 'd', 4],
    ]) {
      const pt = await points(page, body, onto);
      await hold(page, pt.from, pt.top);
      await page.mouse.up();
      await idle(page, n);
    }
    await page.click('#teach-stop');
    await page.waitForSelector('#teach-run-box:not([hidden])');
    // Deleting the first move while the goal still holds (on c b): refused with the reason.
    await page.click('#teach-delete-move-1');
    await page.waitForSelector('#teach-error:not([hidden])');
    assert.match(await page.textContent('#teach-error'), /Deleting move 1, \(pick panda c\) \(stack panda c b\), leaves an invalid demonstration: .*\(on c b\)/);
    assert.match(await page.textContent('#teach-error'), /The demonstration is unchanged/);
    assert.equal(await page.evaluate(() => window.lfdTeach.info().actions.length), 4);
    // Goal: only (on a d).
    const boxes = page.locator('#teach-goal input[type=checkbox]');
    for (let i = 0; i < (await boxes.count()); i++) {
      if ((await boxes.nth(i).getAttribute('aria-label')) !== 'goal fact (on a d)') await boxes.nth(i).uncheck();
    }
    await page.waitForFunction(() => window.lfdTeach.info().goal.length === 1, null, { timeout: 5000 });
    // Now the first move may go: the rest is checked again and listed.
    await page.click('#teach-delete-move-1');
    await page.waitForFunction(() => window.lfdTeach.info().actions.length === 2, null, { timeout: 5000 });
    assert.equal(await page.isHidden('#teach-error'), true);
    const info = await page.evaluate(() => window.lfdTeach.info());
    assert.deepEqual(info.actions, ['(pick panda a)', '(stack panda a d)']);
    assert.deepEqual(info.goal, ['(on a d)']);
    assert.ok(!info.states.at(-1).includes('(on c b)'));
    assert.match(await page.textContent('#teach-summary'), /Deleted move 1, \(pick panda c\) \(stack panda c b\): 2 actions left/);
    assert.match(await page.textContent('#status'), /2 actions recognised · stopped/);
    const listed = await page.textContent('#teach-list');
    assert.match(listed, /a1 \(pick panda a\)/);
    assert.doesNotMatch(listed, /panda c/);
    const demo = JSON.parse(await page.evaluate(() => window.lfdTeach.demoJson()));
    assert.deepEqual(demo.actions.map((a) => a.action), info.actions);
    assert.deepEqual(demo.goal, ['(on a d)']);
    await page.screenshot({ path: join(screenshots, 'teach-edited.png') });
    // The run gets the edited demonstration: its demo is the two actions, its goal (on a d) alone.
    await page.selectOption('#teach-start', 'taught');
    await page.click('#teach-run');
    await page.waitForFunction(() => document.querySelector('#tab-run').classList.contains('active'));
    assert.deepEqual(await page.evaluate(() => window.lfd.frame().demo), ['(pick panda a)', '(stack panda a d)']);
    const f = await finish(page, 60000);
    assert.equal(f.status.kind, 'done', JSON.stringify(f.status));
    assert.ok(f.facts.includes('(on a d)') && !f.facts.includes('(on c b)'), JSON.stringify(f.facts));
    assert.deepEqual(errors, []);
    await page.close();
  });
});
