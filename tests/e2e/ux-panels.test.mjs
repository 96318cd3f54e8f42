// Browser tests of the page's guidance and panels (Debian Chromium, real mouse, touch and keyboard
// events): the first-visit hint and the goal in words, the help's explanations, Space after a
// select, the L1–L4 buttons, the Run tab's chips and highlights, Teach mode's leftovers, the PDDL
// tab as a sandbox, and the layout on a phone and a small laptop.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { currentFrame, finish, openApp, screenshots, useBrowser } from './harness.mjs';
import { dragBody, dropPoint, waitStatus } from './ux-helpers.mjs';

const ctx = useBrowser({ withScreenshots: true });
const open = (query = '', viewport = undefined) => openApp(ctx.browser, ctx.server, query, viewport);

describe('guidance', () => {
  test('a first visit shows the goal in words and what to do; the help explains levels, methods, modes, L_k and S_C', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await page.waitForSelector('#first-hint:not([hidden])');
    await page.waitForFunction(() => document.querySelector('#hint-goal')?.textContent === 'a on b, b on c and c on d');
    assert.match(await page.textContent('#first-hint'), /Drag a block/);
    assert.equal(await page.textContent('#goal'), 'a on b, b on c and c on d');
    await page.screenshot({ path: join(screenshots, 'ux-first-visit-1440.png') });
    await page.click('#hint-close');
    await page.waitForSelector('#first-hint', { state: 'hidden' });
    await page.click('#help');
    await page.waitForSelector('#help-explain');
    const help = await page.textContent('#help-explain');
    for (const w of ['L1', 'L2', 'L3', 'L4', 'Linear', 'RLDS', 'TAMP', 'Logic-LfD', 'paper', 'prioritised', 'S_C', 'L_0', 'joined at L_k']) assert.ok(help.includes(w), `help lacks ${w}`);
    await page.screenshot({ path: join(screenshots, 'ux-help-1440.png') });
    await page.keyboard.press('Escape');
    // The method select explains the chosen method in its tooltip.
    assert.match(await page.getAttribute('#method', 'title'), /^Method: Plans with PDDL/);
    // Closed once, the hint stays closed.
    await page.reload();
    await page.waitForSelector('#app[data-ready="true"]');
    assert.equal(await page.isHidden('#first-hint'), true);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Space pauses and plays after a select was used, instead of opening it', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await page.click('#speed');
    await page.keyboard.press('ArrowDown');
    await page.keyboard.press('Enter');
    await page.waitForFunction(() => location.search.includes('speed=2'));
    assert.equal(await page.evaluate(() => document.activeElement?.id), 'speed');
    await page.keyboard.press(' ');
    await page.waitForSelector('#play[aria-pressed="true"]');
    assert.equal(await page.inputValue('#speed'), '2', 'Space changed the select');
    await page.keyboard.press(' ');
    await page.waitForSelector('#play[aria-pressed="false"]');
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('disturbance buttons', () => {
  test('L1–L4 are greyed with the reason when they cannot apply, and an L1 move is marked in the view', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1');
    // Some level cannot apply at some moment of the episode (e.g. L2 while the arm holds a block):
    // its button greys, and its title and a press say why.
    await page.waitForSelector('button.level[aria-disabled="true"]', { timeout: 60000 });
    await page.click('#play');
    await page.waitForSelector('#play[aria-pressed="false"]');
    await page.waitForTimeout(500);
    const grey = await page.$('button.level[aria-disabled="true"]');
    if (grey) {
      const level = await grey.getAttribute('data-level');
      assert.match(await grey.getAttribute('title'), /not now: /);
      // aria-disabled makes Playwright wait for "enabled"; the press itself is what is tested.
      await grey.click({ force: true });
      await page.waitForSelector('#notice.error:not([hidden])');
      assert.ok((await page.textContent('#notice')).startsWith(`${(await grey.textContent()).trim()} refused: `));
    }
    // L1 applies once the hand is empty; what it moved (a block, or the moving arm's hand) is
    // marked, since a few centimetres are easy to miss.
    await page.click('#play');
    await page.waitForFunction(() => !window.lfd.frame()?.world.arms.some((a) => a.holding), null, { timeout: 60000, polling: 20 });
    await page.click('#play');
    await page.waitForSelector('#inject-l1[aria-disabled="false"]', { timeout: 30000 });
    await page.click('#inject-l1');
    await page.waitForFunction(() => window.lfd.moveMarks().length === 1, null, { timeout: 30000, polling: 20 });
    const [mark] = await page.evaluate(() => window.lfd.moveMarks());
    const said = await page.textContent('#notice');
    assert.match(mark, /pushed the hand of (\w+)/.test(said) ? new RegExp(`^pushed:${said.match(/hand of (\w+)/)[1]}$`) : /^moved:[a-z]\w*$/, `${mark} for "${said}"`);
    await page.screenshot({ path: join(screenshots, 'ux-l1-mark-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('run panel', () => {
  test('the last fact change stays, the robot’s place in the demonstration moves, finished steps stay grey', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1&speed=8');
    await waitStatus(page, ['executing']);
    const at0 = await page.textContent('#matched');
    const done = await finish(page);
    assert.equal(done.status.kind, 'done');
    // Every step of the finished plan is grey, and the robot is at the demonstration's end.
    const plan = await page.$$eval('#plan li', (ls) => ls.map((l) => l.className));
    assert.ok(plan.length >= 6 && plan.every((c) => c === 'done'), plan.join(','));
    assert.ok(await page.$eval('#demo .demo-state.at', (e, n) => e.textContent.startsWith(`L${n}`), done.demo.length));
    assert.notEqual(await page.textContent('#matched'), at0);
    // A drag at 1×: its fact changes stay on screen after the replan it causes (until the arm
    // changes the facts again).
    await page.selectOption('#speed', '1');
    const start = done.world.bodies.find((b) => b.name === 'a').pose.position;
    await dragBody(page, 'a', await dropPoint(page, [start[0], start[1] - 0.2, 0]));
    await waitStatus(page, ['executing', 'replanning']);
    await page.waitForTimeout(300);
    const chips = await page.$$eval('#facts-diff .chip', (cs) => cs.map((c) => c.textContent));
    assert.ok(chips.some((c) => c.includes('(on a b)')), chips.join(' '));
    assert.ok((await page.$$('#replan-info .replan')).length >= 2, 'every replan is listed');
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('charts', () => {
  test('hovering a replan shows its time and reason; both charts span the same time', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1&speed=8');
    await finish(page);
    await page.click('#tab-charts');
    await page.waitForSelector('#chart-replan .u-over');
    await page.waitForTimeout(300);
    const over = await page.$eval('#chart-replan .u-over', (e) => e.getBoundingClientRect().toJSON());
    await page.mouse.move(over.left + 2, over.top + over.height / 2);
    await page.waitForFunction(() => /ms: start/.test(document.querySelector('#chart-replan .u-legend')?.textContent ?? ''));
    // The same x axis: the last tick label of both charts is the same.
    const last = (id) => page.$eval(`#${id} .u-axis`, (a) => [...a.querySelectorAll('.u-value, div')].map((d) => d.textContent).filter(Boolean).pop());
    assert.equal(await last('chart-replan'), await last('chart-ee'));
    await page.screenshot({ path: join(screenshots, 'ux-charts-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('teach and pddl', () => {
  test('Teach: no run clock, no Cancel, Play does not pretend, Stop ends once', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1&speed=4');
    await page.waitForFunction(() => (window.lfd.frame()?.t ?? 0) > 1);
    await page.click('#tab-teach');
    await page.click('#teach-record');
    await page.waitForFunction(() => document.querySelector('#status-text')?.textContent?.startsWith('Teaching'));
    assert.equal(await page.textContent('#hud'), '');
    assert.equal(await page.isDisabled('#cancel'), true);
    // Play waits while Teach records: it is disabled, not a button that does nothing.
    assert.equal(await page.isDisabled('#play'), true);
    assert.equal(await page.getAttribute('#play', 'aria-pressed'), 'false');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('PDDL: a sandbox label, edits kept per benchmark, an error is no plan step, stepping shows removed facts', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await page.click('#tab-pddl');
    await page.waitForSelector('#pddl-own');
    assert.match(await page.textContent('#pddl-own'), /plans on its own/);
    await page.waitForFunction(() => document.querySelector('#panel-pddl .cm-content')?.textContent.includes('define'));
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-plan-list button.step[data-index="2"]', { timeout: 20000 });
    await page.click('#pddl-plan-list button.step[data-index="2"]');
    assert.ok((await page.$$('#pddl-state li.removed')).length >= 1, 'removed facts are shown');
    // An edit, then B2 and back: the edit is still there.
    const line = page.locator('#panel-pddl .cm-host:not([hidden]) .cm-line').first();
    await line.click();
    await page.keyboard.press('End');
    await page.keyboard.type(' ; my edit');
    await page.selectOption('#benchmark', 'b2');
    await page.waitForFunction(() => document.querySelector('#panel-pddl .cm-content')?.textContent.includes('hook'), null, { timeout: 20000 });
    await page.selectOption('#benchmark', 'b1');
    await page.waitForFunction(() => document.querySelector('#panel-pddl .cm-content')?.textContent.includes('; my edit'), null, { timeout: 20000 });
    // A broken domain: the message is not numbered as a step.
    await page.locator('#panel-pddl .cm-host:not([hidden]) .cm-line', { hasText: ':requirements' }).first().click();
    await page.keyboard.press('End');
    await page.keyboard.type(' (:bogus');
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-no-plan', { timeout: 20000 });
    assert.doesNotMatch(await page.$eval('#pddl-no-plan', (e) => getComputedStyle(e, '::before').content), /counter/);
    assert.equal(await page.$$eval('#pddl-plan-list button.step', (b) => b.length), 0);
    await page.screenshot({ path: join(screenshots, 'ux-pddl-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('layout', () => {
  for (const [w, h] of [
    [390, 844],
    [1024, 700],
  ]) {
    test(`at ${w}×${h}: every control on screen, no sideways scroll, the panel readable, touch drag works`, async () => {
      const page = await ctx.browser.newPage({ viewport: { width: w, height: h }, hasTouch: true, isMobile: w < 500 });
      const errors = [];
      page.on('pageerror', (e) => errors.push(String(e)));
      await page.goto(`${ctx.server.url}?benchmark=b1&seed=1&autoplay=0`);
      await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
      assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), 'the page scrolls sideways');
      for (const id of ['benchmark', 'method', 'mode', 'seed', 'reset', 'play', 'step', 'speed', 'inject-l1', 'inject-l4', 'load-scene', 'help']) {
        const r = await page.$eval(`#${id}`, (e) => e.getBoundingClientRect().toJSON());
        assert.ok(r.left >= 0 && r.right <= w + 0.5 && r.width > 0, `#${id} off screen: ${JSON.stringify(r)}`);
      }
      const stage = await page.$eval('.stage', (e) => e.getBoundingClientRect().toJSON());
      const side = await page.$eval('.side', (e) => e.getBoundingClientRect().toJSON());
      if (w < 1000) assert.ok(side.top >= stage.bottom - 1, 'the panel is below the view');
      await page.screenshot({ path: join(screenshots, `ux-layout-${w}.png`), fullPage: w < 1000 });
      // A touch drag moves a block (CDP touch events: pointerType touch).
      const f0 = await currentFrame(page);
      const a = f0.world.bodies.find((b) => b.name === 'a').pose.position;
      const from = await page.evaluate(() => window.lfd.screenPosition('a'));
      const to = await dropPoint(page, [a[0], a[1] + 0.12, 0]);
      const cdp = await page.context().newCDPSession(page);
      const touch = (type, p) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: p ? [{ x: p.x, y: p.y }] : [] });
      await touch('touchStart', from);
      for (let i = 1; i <= 10; i++) await touch('touchMove', { x: from.x + ((to.x - from.x) * i) / 10, y: from.y + ((to.y - from.y) * i) / 10 });
      await touch('touchEnd');
      await page.waitForFunction((y) => Math.abs(window.lfd.frame().world.bodies.find((b) => b.name === 'a').pose.position[1] - y) > 0.05, a[1], { timeout: 10000 });
      assert.deepEqual(errors, []);
      await page.close();
    });
  }
});
