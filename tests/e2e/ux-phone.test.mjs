// Browser tests of the page's small words and touch targets: the clock line counts its replans in
// the right number, Cancel waits for a session, and on a phone (390 × 844, touch) the hint names a
// tap rather than a key, Help's Close is in view without scrolling, the timeline's scrubber is a
// finger's height and the plan shows without scrolling.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { openApp, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

/** A page on a phone: 390 × 844, touch, `?query`. */
async function phone(query) {
  const page = await ctx.browser.newPage({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(`${ctx.server.url}${query}`);
  await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
  return { page, errors };
}

describe('words and touch targets', () => {
  test('the clock line says "1 replan", then "2 replans"', async () => {
    // Paused after the first plan: the scrambled state is the same in every run.
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=8&autoplay=0');
    await page.click('#step');
    await page.waitForFunction(() => window.lfd.frame()?.replans === 1, null, { timeout: 30000 });
    assert.match(await page.textContent('#hud'), /· 1 replan$/);
    await page.click('#inject-l3');
    await page.waitForFunction(() => (window.lfd.frame()?.replans ?? 0) >= 2, null, { timeout: 30000 });
    assert.match(await page.textContent('#hud'), /· \d+ replans$/);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Cancel stays hidden until a session runs', async () => {
    const page = await ctx.browser.newPage({ viewport: { width: 1440, height: 900 } });
    // Hold the first-load wasm module back: the page shows "Loading the planner…" meanwhile.
    let release;
    const held = new Promise((r) => (release = r));
    await page.route('**/*.wasm', async (route) => {
      await held;
      await route.continue();
    });
    await page.goto(`${ctx.server.url}?benchmark=b1&autoplay=0`);
    await page.waitForSelector('#status-text');
    assert.match(await page.textContent('#status-text'), /Loading/);
    assert.equal(await page.isVisible('#cancel'), false, 'Cancel shown while the planner loads');
    release();
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
    await page.click('#play');
    await page.waitForFunction(() => window.lfd.frame()?.status.kind === 'executing', null, { timeout: 30000 });
    assert.equal(await page.isVisible('#cancel'), true);
    await page.close();
  });

  test('on a phone the hint says tap, Help closes from the top, and the scrubber is finger-sized', async () => {
    const { page, errors } = await phone('?benchmark=b1&seed=1&autoplay=0');
    await page.waitForSelector('.hint', { timeout: 30000 });
    const hint = await page.textContent('.hint');
    assert.match(hint, /Tap \? for help/);
    assert.doesNotMatch(hint, /Press \?/);
    await page.tap('#help');
    await page.waitForSelector('#help-overlay:not([hidden])');
    await page.waitForSelector('.help-content h3', { timeout: 30000 });
    const close = await page.$eval('#help-close', (b) => {
      const r = b.getBoundingClientRect();
      return { top: r.top, bottom: r.bottom, height: innerHeight };
    });
    assert.ok(close.top >= 0 && close.bottom <= close.height, `Close at ${close.top}..${close.bottom} of ${close.height}`);
    await page.screenshot({ path: join(screenshots, 'help-phone.png') });
    await page.tap('#help-close');
    await page.waitForSelector('#help-overlay[hidden]', { state: 'attached' });
    // The timeline appears with the first recorded frame.
    await page.tap('#step');
    const h = await page.waitForSelector('.timeline input[type="range"]', { timeout: 30000 });
    const box = await h.boundingBox();
    assert.ok(box && box.height >= 24, `the scrubber is ${box?.height} px tall`);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('on a phone the plan shows without scrolling', async () => {
    const { page, errors } = await phone('?benchmark=b1&seed=1');
    await page.waitForFunction(() => (window.lfd.frame()?.plan.length ?? 0) > 0, null, { timeout: 30000 });
    const first = await page.$eval('#plan li', (li) => {
      const r = li.getBoundingClientRect();
      return { top: r.top, bottom: r.bottom, height: innerHeight, scrolled: scrollY };
    });
    assert.equal(first.scrolled, 0);
    assert.ok(first.bottom <= first.height, `the plan's first step at ${first.top}..${first.bottom} px of ${first.height}`);
    assert.deepEqual(errors, []);
    await page.close();
  });
});
