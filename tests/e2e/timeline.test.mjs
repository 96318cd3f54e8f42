// Browser tests of the timeline under the 3-D view (Debian Chromium, real mouse events): an L3
// disturbance and the replan it causes are marked at their times, the charts mark the same
// disturbance, scrubbing back shows the world as it was, and Play returns to live.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { openApp, screenshots, useBrowser } from './harness.mjs';
import { dragBody, dropPoint, scrubTo, waitL3Replan } from './ux-helpers.mjs';

const ctx = useBrowser({ withScreenshots: true });
const open = (query, viewport = undefined) => openApp(ctx.browser, ctx.server, query, viewport);

const positions = (page) =>
  page.evaluate(() => Object.fromEntries(window.lfd.frame().world.bodies.filter((b) => b.kind === 'block').map((b) => [b.name, b.pose.position])));
const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

describe('timeline', () => {
  test('marks an L3 disturbance and its replan, scrubs back to before it, Play returns to live', async () => {
    const { page, errors } = await open('?benchmark=b1&seed=1&speed=2&autoplay=0');
    await page.waitForSelector('#timeline-range');
    for (let i = 0; i < 5; i++) await page.click('#step');
    await page.waitForFunction(() => window.lfd.frame()?.tick === 50);
    const before = await positions(page);
    await page.click('#inject-l3', { force: true });
    const l3t = await waitL3Replan(page);
    assert.ok(Math.abs(l3t - 0.5) < 1e-6, `L3 marked at ${l3t} s, injected at 0.5 s`);
    const after = await positions(page);
    const moved = Object.keys(before).filter((n) => dist(before[n], after[n]) > 0.02);
    assert.ok(moved.length >= 1, `no block moved: ${JSON.stringify({ before, after })}`);

    // The bar shows one disturbance marker (L3) and replan markers from its time on.
    const marks = await page.$$eval('#timeline .tl-mark', (ms) => ms.map((m) => ({ kind: m.dataset.kind, t: Number(m.dataset.t), title: m.title })));
    const dist3 = marks.filter((m) => m.kind !== 'replan');
    assert.equal(dist3.length, 1, JSON.stringify(marks));
    assert.equal(dist3[0].kind, 'l3');
    assert.ok(Math.abs(dist3[0].t - 0.5) < 0.006, JSON.stringify(dist3));
    const replans = marks.filter((m) => m.kind === 'replan');
    assert.ok(replans.some((m) => m.t >= 0.5 - 1e-6), JSON.stringify(marks));
    assert.ok(replans.every((m) => /^Replan at t = [\d.]+ s: \S/.test(m.title)), replans.map((m) => m.title).join(' | '));
    // Hovering a replan marker gives its reason (the tooltip's title).
    const replanBox = await page.$eval('#timeline .tl-mark.replan:last-child', (e) => {
      const b = e.getBoundingClientRect();
      return { x: b.left + b.width / 2, y: b.top + b.height / 2 };
    });
    await page.mouse.move(replanBox.x, replanBox.y);
    const hovered = await page.evaluate(([x, y]) => document.elementFromPoint(x, y)?.getAttribute('title') ?? '', [replanBox.x, replanBox.y]);
    assert.match(hovered, /^Replan at t = /);

    // Scrub back to before the disturbance: the run pauses and the view shows the block where it was.
    await page.waitForFunction(() => window.lfd.frame().t > 1.5, null, { timeout: 30000 });
    await scrubTo(page, 0.3);
    const viewing = await page.evaluate(() => window.lfd.viewing());
    assert.ok(viewing.t < 0.5 && viewing.t > 0.1, JSON.stringify(viewing));
    await page.waitForFunction(() => document.querySelector('#play')?.getAttribute('aria-pressed') === 'false');
    assert.match(await page.textContent('#timeline-label'), /^viewing t = 0\.\d s — Play returns to live$/);
    for (const n of moved) {
      const shown = await page.evaluate((b) => window.lfd.bodyPosition(b), n);
      assert.ok(dist(shown, before[n]) < 0.005, `${n} shown at ${shown}, was at ${before[n]}`);
      assert.ok(dist(shown, after[n]) > 0.02, `${n} shown where the disturbance put it`);
    }
    await page.screenshot({ path: join(screenshots, 'timeline-1440.png') });

    // A drag while viewing the past is refused with a message.
    const live = await page.evaluate(() => window.lfd.frame().t);
    await dragBody(page, moved[0], await dropPoint(page, [0.45, -0.3, 0]));
    await page.waitForSelector('#notice:not([hidden])');
    assert.match(await page.textContent('#notice'), /Viewing an earlier moment: press Play/);
    assert.equal(await page.evaluate(() => window.lfd.marks().filter((m) => m.kind === 'drag').length), 0);

    // Play returns to live: the latest time, the block where the run has it.
    await page.click('#play');
    await page.waitForFunction(() => window.lfd.viewing().t === null);
    await page.waitForFunction((t) => window.lfd.frame().t > t, live);
    assert.match(await page.textContent('#timeline-label'), /^live · t = /);
    await page.click('#play');
    await page.waitForFunction(() => document.querySelector('#play')?.getAttribute('aria-pressed') === 'false');
    await page.waitForTimeout(100);
    const end = await page.evaluate(() => ({ v: window.lfd.viewing(), value: Number(/** @type {HTMLInputElement} */ (document.querySelector('#timeline-range')).value) }));
    assert.ok(Math.abs(end.value - end.v.end) < 0.011, JSON.stringify(end));
    const now = await positions(page);
    for (const n of moved) {
      const shown = await page.evaluate((b) => window.lfd.bodyPosition(b), n);
      assert.ok(dist(shown, now[n]) < 0.005, `${n} shown at ${shown}, live at ${now[n]}`);
    }

    // The charts mark the same disturbance, in the timeline's colour, on both charts.
    await page.click('#tab-charts');
    await page.waitForFunction(() => window.lfd.chartMarks().every((c) => c.some((m) => m.kind === 'l3')), null, { timeout: 15000 });
    const charted = await page.evaluate(() => window.lfd.chartMarks().map((c) => c.filter((m) => m.kind !== 'replan')));
    for (const c of charted) assert.deepEqual(c.map((m) => [m.kind, m.t]), [['l3', l3t]]);
    await page.screenshot({ path: join(screenshots, 'timeline-charts-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  for (const [w, h] of [
    [1024, 700],
    [390, 844],
  ]) {
    test(`the timeline fits at ${w}x${h}`, async () => {
      const { page, errors } = await open('?benchmark=b1&seed=1&speed=2&autoplay=0', { width: w, height: h });
      await page.waitForSelector('#timeline-range');
      // The same moment as above: L3 applies there (the arm holds nothing yet).
      for (let i = 0; i < 5; i++) await page.click('#step');
      await page.waitForFunction(() => window.lfd.frame()?.tick === 50);
      await page.click('#inject-l3', { force: true });
      await waitL3Replan(page);
      const box = await page.$eval('#timeline', (e) => e.getBoundingClientRect().toJSON());
      const stage = await page.$eval('.stage', (e) => e.getBoundingClientRect().toJSON());
      assert.ok(box.left >= stage.left && box.right <= stage.right && box.bottom <= stage.bottom, JSON.stringify({ box, stage }));
      assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), 'the page scrolls sideways');
      await page.screenshot({ path: join(screenshots, `timeline-${w}.png`) });
      assert.deepEqual(errors, []);
      await page.close();
    });
  }
});
