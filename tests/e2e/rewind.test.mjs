// Browser tests of the rewound panels (Debian Chromium, real mouse, keyboard and touch events):
// scrubbing the timeline of a B1 run with an L3 disturbance back to before its replan shows the
// status line, the clock, the plan, the replans and the facts exactly as the page showed them live
// then; a replan marker's click shows the plan before and after that replan; Play returns to live.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { openApp, screenshots, useBrowser } from './harness.mjs';
import { scrubTo, waitL3Replan } from './ux-helpers.mjs';

const ctx = useBrowser({ withScreenshots: true });

/** What the panels show now: status, clock, plan (text and state of each step), replans, facts. */
const SHOWN = () => ({
  status: document.querySelector('#status-text').textContent,
  hud: document.querySelector('#hud').textContent,
  plan: [...document.querySelectorAll('#plan li')].map((li) => `${li.className}|${li.textContent}`),
  replans: document.querySelector('#replan-info').textContent,
  facts: [...document.querySelectorAll('#facts li')].map((li) => `${li.className}|${li.textContent}`),
  change: document.querySelector('#facts-diff').textContent,
});

/** Records, at every animation frame, what the panels show, keyed by the clock's time (they are
 * drawn together), and the plan first shown after each replan, keyed by its tick. */
async function watchLive(page) {
  await page.evaluate((shown) => {
    const read = new Function(`return (${shown})()`);
    /** @type {any} */ (window).liveShown = {};
    /** @type {any} */ (window).planAfter = {};
    const grab = () => {
      if (!document.querySelector('.panel.rw-rewound')) {
        const s = read();
        const t = /^t = ([\d.]+) s/.exec(s.hud);
        if (t) /** @type {any} */ (window).liveShown[t[1]] = s;
        const r = /Last replan at tick (\d+):/.exec(s.replans);
        if (r && !(r[1] in /** @type {any} */ (window).planAfter)) /** @type {any} */ (window).planAfter[r[1]] = s.plan.map((p) => p.split('|')[1]);
      }
      requestAnimationFrame(grab);
    };
    grab();
  }, SHOWN.toString());
}

const shown = (page) => page.evaluate(SHOWN);

/** Opens B1 paused, steps it to 0.5 s, injects L3 there and lets the run finish; returns the plan
 * shown just before the disturbance. */
async function runWithL3(page) {
  await page.waitForSelector('#timeline-range');
  await page.waitForSelector('#rewind-note', { state: 'attached' });
  await watchLive(page);
  for (let i = 1; i <= 5; i++) {
    await page.click('#step');
    await page.waitForFunction((t) => t in /** @type {any} */ (window).liveShown, (i / 10).toFixed(2));
  }
  const before = (await shown(page)).plan.map((p) => p.split('|')[1]);
  await page.click('#inject-l3', { force: true });
  await waitL3Replan(page);
  await page.waitForFunction(() => ['done', 'failed'].includes(window.lfd.frame().status.kind), null, { timeout: 90000, polling: 100 });
  // The last frame drawn.
  await page.waitForFunction(() => document.querySelector('#hud').textContent.startsWith(`t = ${window.lfd.frame().t.toFixed(2)} s`));
  return before;
}

/** The first replan marker at or after the L3 disturbance: its time, and the point to click. */
async function l3Replan(page) {
  return page.evaluate(() => {
    const m = window.lfd.marks();
    const l3 = m.find((x) => x.kind === 'l3');
    const r = m.find((x) => x.kind === 'replan' && x.t >= l3.t - 1e-9);
    const el = [...document.querySelectorAll('#timeline .tl-mark.replan')].find((e) => /** @type {HTMLElement} */ (e).dataset.t === r.t.toFixed(2));
    const b = el.getBoundingClientRect();
    return { t: r.t, text: r.text, x: b.left + b.width / 2, y: b.top + b.height / 2 };
  });
}

/** Checks the replan's two plans: the one shown before it, the one shown after it (what each
 * dropped struck out, what each added tagged new). */
async function checkReplanDiff(page, r, planBefore) {
  const box = page.locator('#rewind-replan');
  await box.waitFor();
  const d = await box.evaluate((e) => ({
    reason: e.querySelector('.rw-reason').textContent,
    lists: [...e.querySelectorAll('ol')].map((ol) => [...ol.children].map((li) => ({ cls: li.className, text: li.querySelector('del')?.textContent ?? li.lastChild.textContent }))),
  }));
  assert.ok(d.reason.startsWith(`Replan at t = ${r.t.toFixed(2)} s: ${r.text}`), `${d.reason} | ${r.text}`);
  const [before, after] = d.lists;
  const tick = await page.evaluate((t) => Math.round(t / window.lfd.frame().world.dt), r.t);
  const planAfter = await page.evaluate((k) => /** @type {any} */ (window).planAfter[k], tick);
  assert.deepEqual(before.map((a) => a.text), planBefore);
  assert.deepEqual(after.map((a) => a.text), planAfter);
  assert.notDeepEqual(planBefore, planAfter, 'the replan changed nothing');
  for (const a of before) assert.equal(a.cls === 'rw-removed', !planAfter.includes(a.text), JSON.stringify(a));
  for (const a of after) assert.equal(a.cls === 'rw-new', !planBefore.includes(a.text), JSON.stringify(a));
  assert.ok(before.some((a) => a.cls === 'rw-removed') || after.some((a) => a.cls === 'rw-new'), JSON.stringify(d));
}

/** The note over the rewound panels: its moment's time (null when hidden). */
const noteTime = (page) => page.$eval('#rewind-note', (e) => (e.hidden ? null : e.dataset.t));

describe('rewind', () => {
  test('scrubbing back shows the panels as they were; a replan marker shows its plans; Play returns to live', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=2&autoplay=0');
    const planBefore = await runWithL3(page);
    // The L3 replan's "why L_k?" table, opened live.
    const r = await l3Replan(page);
    const tick = await page.evaluate((t) => Math.round(t / window.lfd.frame().world.dt), r.t);
    await page.locator('#replan-info .replan', { hasText: `at tick ${tick}:` }).locator('.why-btn').click();
    const why = await page.locator('#replan-info .why-join').textContent();
    const end = await shown(page);
    // Compact: every Moment recorded, snapshots only where the Run tab changed, plans shared.
    const use = await page.evaluate(() => ({ ...window.lfd.rewind(), replanMarks: window.lfd.marks().filter((m) => m.kind === 'replan').length }));
    assert.equal(use.recorded, use.moments, JSON.stringify(use));
    assert.ok(use.moments > 100 && use.snapshots < use.moments / 4, JSON.stringify(use));
    assert.ok(use.plans <= use.replans + 1 && use.replans === use.replanMarks, JSON.stringify(use));

    // Just after the replan: its "why L_k?" table, open as it is live, with the same candidates.
    await scrubTo(page, r.t + 1.5);
    assert.ok(Number(await noteTime(page)) > r.t, await page.textContent('#rewind-note'));
    assert.equal(await page.locator('#replan-info .why-join').textContent(), why);

    // Back to before the disturbance: every panel as it was shown live then.
    await scrubTo(page, 0.35);
    const at = await noteTime(page);
    assert.ok(at !== null && Number(at) < 0.5, `note at ${at}`);
    assert.match(await page.textContent('#rewind-note'), /^Viewing t = 0\.\d\d s — Play returns to live$/);
    const then = await page.evaluate((t) => /** @type {any} */ (window).liveShown[t], at);
    assert.ok(then, `nothing shown live at t = ${at}`);
    assert.deepEqual(await shown(page), then);
    assert.notDeepEqual(then.plan, end.plan, 'the plan is the same now as then');
    assert.ok(await page.$eval('#panel-run', (e) => e.classList.contains('rw-rewound')));

    // The keyboard steps the scrubber: a later moment, as shown live then.
    await page.focus('#timeline-range');
    let later = at;
    for (let i = 0; i < 40 && later === at; i++) {
      await page.keyboard.press('ArrowRight');
      later = await noteTime(page);
    }
    assert.ok(Number(later) > Number(at) && Number(later) < 0.5, `${at} → ${later}`);
    assert.deepEqual(await shown(page), await page.evaluate((t) => /** @type {any} */ (window).liveShown[t], later));

    // From the keyboard: the note offers the next replan, whose plans the Run tab then shows.
    await page.focus('#rewind-next button');
    assert.equal(await page.textContent('#rewind-next button'), `Next replan at t = ${r.t.toFixed(2)} s: its plans before and after`);
    await page.keyboard.press('Enter');
    await checkReplanDiff(page, r, planBefore);
    await scrubTo(page, 0.3);
    assert.ok(await page.$eval('#rewind-replan', (e) => e.hidden), 'the plans stay when another moment is viewed');

    // The replan marker: its time, and the plans before and after it.
    await page.mouse.click(r.x, r.y);
    const v = await page.evaluate(() => window.lfd.viewing());
    assert.ok(Math.abs(v.t - r.t) < 1e-9, JSON.stringify({ v, r }));
    await checkReplanDiff(page, r, planBefore);
    await page.screenshot({ path: join(screenshots, 'rewind-1440.png') });

    // Play returns to live: the last frame's panels, no note, no replan box.
    await page.click('#play');
    await page.waitForFunction(() => window.lfd.viewing().t === null);
    assert.equal(await noteTime(page), null);
    assert.ok(await page.$eval('#rewind-replan', (e) => e.hidden));
    assert.ok(!(await page.$eval('#panel-run', (e) => e.classList.contains('rw-rewound'))));
    const live = await shown(page);
    assert.deepEqual({ ...live, status: '' }, { ...end, status: '' });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('the rewound panels and a replan at 1024x700', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=2&autoplay=0', { width: 1024, height: 700 });
    const planBefore = await runWithL3(page);
    const r = await l3Replan(page);
    await page.mouse.click(r.x, r.y);
    await checkReplanDiff(page, r, planBefore);
    const at = await noteTime(page);
    assert.ok(at !== null && Number(at) <= r.t + 1e-9, `note at ${at}, replan at ${r.t}`);
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), 'the page scrolls sideways');
    await page.screenshot({ path: join(screenshots, 'rewind-1024.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a tap on a replan marker rewinds the panels on a phone (390x844, touch)', async () => {
    const page = await ctx.browser.newPage({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`${ctx.server.url}?benchmark=b1&seed=1&speed=2&autoplay=0`);
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
    const planBefore = await runWithL3(page);
    const r = await l3Replan(page);
    await page.touchscreen.tap(r.x, r.y);
    await checkReplanDiff(page, r, planBefore);
    const at = await noteTime(page);
    assert.ok(at !== null && Number(at) <= r.t + 1e-9, `note at ${at}, replan at ${r.t}`);
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), 'the page scrolls sideways');
    // The Run tab is under the view on a phone: the note at the top of the screen, the plans under it.
    await page.$eval('#rewind-note', (e) => e.scrollIntoView({ block: 'start' }));
    await page.screenshot({ path: join(screenshots, 'rewind-phone.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });
});
