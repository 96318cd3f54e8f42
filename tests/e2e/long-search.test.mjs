// Browser test of a long search on the page: TAMP on a 12-block tower searches for seconds inside
// one worker step. The status line shows what runs and how many states it has expanded, with
// Cancel; a budget that runs out is called a budget; the step timings start afresh with the next
// episode; and the worker's memory returns to its fresh size after a reset.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { openApp, useBrowser } from './harness.mjs';

const ctx = useBrowser();
const TALL = '?benchmark=b1&blocks=12&method=tamp&seed=1&autoplay=0';

/** The worker's wasm memory (bytes). */
const wasmBytes = (page) => page.evaluate(() => window.lfd.memory().then((m) => m.wasmBytes));

describe('a long search', () => {
  test('shows its progress, ends at its budget, and leaves no memory behind after a reset', { timeout: 240000 }, async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, TALL);
    const fresh = await wasmBytes(page);
    await page.click('#play');
    // While the worker is inside the search, its progress reaches the status line.
    await page.waitForFunction(() => /TAMP searching: [\d,]+ states expanded · [\d.]+ s/.test(document.getElementById('status-text')?.textContent ?? ''), null, {
      timeout: 30000,
    });
    assert.equal(await page.isVisible('#cancel'), true);
    assert.equal(await page.isEnabled('#cancel'), true);
    const first = await page.textContent('#status-text');
    await page.waitForFunction((was) => document.getElementById('status-text')?.textContent !== was, first, { timeout: 10000 });
    await page.waitForFunction(() => ['done', 'failed'].includes(window.lfd.frame()?.status.kind), null, { timeout: 200000 });
    const end = await page.evaluate(() => window.lfd.frame().status);
    const said = await page.textContent('#status-text');
    console.log(`the episode ended ${end.kind}: ${said}`);
    if (end.kind === 'failed' && end.message.includes('budget exhausted')) assert.match(said, /stopped at a budget, not proved unsolvable/);
    const grown = await wasmBytes(page);
    await page.click('#reset');
    await page.waitForFunction(() => window.lfd.frame()?.t === 0 && /mean 0\.00/.test(document.getElementById('hud')?.textContent ?? ''), null, { timeout: 30000 });
    const after = await wasmBytes(page);
    console.log(`worker wasm memory: fresh ${(fresh / 1e6).toFixed(2)} MB, after the search ${(grown / 1e6).toFixed(2)} MB, after Reset ${(after / 1e6).toFixed(2)} MB`);
    assert.ok(after <= 1.5 * fresh, `after Reset ${after} B > 1.5 × fresh ${fresh} B`);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Cancel stops a running search and the episode opens again', { timeout: 120000 }, async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, TALL);
    await page.click('#play');
    await page.waitForFunction(() => /searching/.test(document.getElementById('status-text')?.textContent ?? ''), null, { timeout: 30000 });
    const t0 = Date.now();
    await page.click('#cancel');
    await page.waitForSelector('#notice:not([hidden])', { timeout: 15000 });
    assert.match(await page.textContent('#notice'), /Search stopped/);
    const took = Date.now() - t0;
    const f = await page.evaluate(() => window.lfd.frame());
    assert.equal(f.t, 0);
    assert.equal(await page.textContent('#play').then((t) => t.trim()), '▶ Play');
    console.log(`Cancel during the search: a fresh worker and the episode reopened in ${took} ms`);
    assert.deepEqual(errors, []);
    await page.close();
  });
});
