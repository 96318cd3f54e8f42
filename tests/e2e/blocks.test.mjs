// Browser tests of the block-count control: the generated 20-block B1 task (two towers) picked
// with the mouse and keyboard, kept in the URL, restored on load, and reset when the benchmark
// cannot take it.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { currentFrame, openApp, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

/** Waits until the scene shows `n` blocks and the loop is executing a plan. */
async function executingWith(page, n) {
  await page.waitForFunction(
    (n) => {
      const f = window.lfd.frame();
      return f && f.world.bodies.filter((b) => b.kind === 'block').length === n && f.status.kind === 'executing';
    },
    n,
    { timeout: 60000, polling: 100 },
  );
}

/** How far the page is wider than the window (px; ≤ 0 when nothing sticks out). */
const overflow = (page) => page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);

describe('block count', () => {
  test('20 blocks picked in the select: the tower task runs, the URL keeps it, a reload restores it', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1');
    assert.equal(await page.inputValue('#blocks'), '', 'the template task by default');
    assert.equal(await page.isDisabled('#blocks'), false);
    // A real click on the select, then the keyboard: End goes to its last choice, 20 blocks, and
    // Enter takes it (from the open list; a closed select takes End at once).
    await page.click('#blocks');
    assert.equal(await page.evaluate(() => document.activeElement?.id), 'blocks');
    await page.keyboard.press('End');
    await page.keyboard.press('Enter');
    await page.waitForFunction(() => (/** @type {HTMLSelectElement} */ (document.querySelector('#blocks'))).value === '20');
    assert.equal(await page.$eval('#blocks', (s) => s.selectedOptions[0].textContent), '20 blocks');
    await executingWith(page, 20);
    assert.match(page.url(), /[?&]blocks=20(&|$)/);
    assert.ok((await overflow(page)) <= 0);
    // The top bar keeps one row at 1440 px: its last group (scene and link) beside the first.
    const tops = await page.$$eval('.topbar > .group', (gs) => gs.map((g) => Math.round(g.getBoundingClientRect().top)));
    assert.equal(new Set(tops).size, 1, `top bar rows at ${tops}`);
    await page.screenshot({ path: join(screenshots, 'blocks-20-1440.png') });
    const query = new URL(page.url()).search;

    // 1024×700: the control row wraps without pushing the page sideways.
    await page.setViewportSize({ width: 1024, height: 700 });
    await page.waitForTimeout(300);
    assert.ok((await overflow(page)) <= 0);
    await page.screenshot({ path: join(screenshots, 'blocks-20-1024.png') });
    assert.deepEqual(errors, []);
    await page.close();

    // The link restores it, on a phone too.
    const phone = await openApp(ctx.browser, ctx.server, query, { width: 390, height: 844 });
    assert.equal(await phone.page.inputValue('#blocks'), '20');
    await executingWith(phone.page, 20);
    assert.ok((await overflow(phone.page)) <= 0, 'the phone page is wider than the screen');
    await phone.page.screenshot({ path: join(screenshots, 'blocks-20-phone.png') });
    assert.deepEqual(phone.errors, []);
    await phone.page.close();
  });

  test('switching benchmark keeps an allowed count, resets another, and B2 disables the control', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&blocks=8&autoplay=0');
    assert.equal(await page.inputValue('#blocks'), '8');
    assert.equal((await currentFrame(page)).world.bodies.filter((b) => b.kind === 'block').length, 8);
    // B3 takes 2 to 10: 8 stays.
    await page.selectOption('#benchmark', 'b3');
    await page.waitForFunction(() => location.search.includes('benchmark=b3') && window.lfd.frame()?.world.bodies.filter((b) => b.kind === 'block').length === 8);
    assert.equal(await page.inputValue('#blocks'), '8');
    const b3 = await page.$$eval('#blocks option', (os) => os.map((o) => o.value));
    assert.deepEqual(b3, ['', ...Array.from({ length: 9 }, (_, i) => String(i + 2))]);
    // B2 has none: template, disabled, and the title says why.
    await page.selectOption('#benchmark', 'b2');
    await page.waitForFunction(() => location.search.includes('benchmark=b2') && !location.search.includes('blocks='));
    assert.equal(await page.inputValue('#blocks'), '');
    assert.equal(await page.isDisabled('#blocks'), true);
    assert.match(await page.getAttribute('#blocks', 'title'), /B2 has no N-block variant/);
    // Back to B1: still the template, enabled; 12 then B3 (2 to 10) falls back to the template.
    await page.selectOption('#benchmark', 'b1');
    assert.equal(await page.isDisabled('#blocks'), false);
    await page.selectOption('#blocks', '12');
    await page.waitForFunction(() => location.search.includes('blocks=12'));
    await page.selectOption('#benchmark', 'b3');
    await page.waitForFunction(() => location.search.includes('benchmark=b3') && !location.search.includes('blocks='));
    assert.equal(await page.inputValue('#blocks'), '');
    // A count out of range in the URL is ignored.
    await page.close();
    const bad = await openApp(ctx.browser, ctx.server, '?benchmark=b1&blocks=40&autoplay=0');
    assert.equal(await bad.page.inputValue('#blocks'), '');
    assert.equal((await currentFrame(bad.page)).world.bodies.filter((b) => b.kind === 'block').length, 4);
    assert.deepEqual([...errors, ...bad.errors], []);
    await bad.page.close();
  });
});
