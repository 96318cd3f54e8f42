// Browser test of the Compare tab (Debian Chromium, real mouse events): the same seed and the same
// scripted disturbance for every method, and the results table's pattern for an L3 on B1.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { compareRows, currentFrame, openApp, runScriptedCompare, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

describe('compare methods', () => {
  test('a scripted L3 on B1: Logic-LfD (both modes) and TAMP succeed, Linear and RLDS fail with their reasons', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&autoplay=0');
    const before = await currentFrame(page);
    await runScriptedCompare(page, 'l3', 0.5);
    const rows = await compareRows(page);
    const row = (n) => rows.find((r) => r.name === n);
    for (const n of ['Logic-LfD (paper)', 'Logic-LfD (prioritised)', 'TAMP']) {
      assert.match(row(n).result, /success/, `${n}: ${row(n).reason}`);
      assert.ok(row(n).replans >= 2, `${n} replanned after the disturbance`);
    }
    assert.match(row('Linear').result, /failed/);
    assert.match(row('Linear').reason, /cannot lift/);
    assert.match(row('RLDS').result, /failed/);
    assert.match(row('RLDS').reason, /no remaining part of the demonstration/);
    // Every method met the same disturbance.
    assert.equal(new Set(rows.map((r) => r.disturbance)).size, 1, rows.map((r) => r.disturbance).join(' | '));
    assert.match(rows[0].disturbance, /^Scramble: /);
    // The Run's own episode was not touched.
    assert.equal((await currentFrame(page)).tick, before.tick);
    await page.screenshot({ path: join(screenshots, 'compare-episode-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });
});
