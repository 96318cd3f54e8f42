// Browser test of the Compare tab replaying the Run's recorded disturbances (Debian Chromium, real
// mouse events): with nothing recorded the choice is disabled with its reason; after a drag in the
// Run every method meets that drag at its time, and the Run's episode is untouched.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { compareRows, currentFrame, openApp, screenshots, useBrowser } from './harness.mjs';
import { dragBody, dropPoint } from './ux-helpers.mjs';

const ctx = useBrowser({ withScreenshots: true });

const recordedOption = (page) => page.$eval('#compare-source option[value="recorded"]', (o) => o.disabled);

describe('compare on the recorded disturbances', () => {
  test('a drag in the Run is replayed at its time for every method; Logic-LfD succeeds', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&autoplay=0');

    // Nothing recorded yet: the choice is disabled and says why.
    await page.click('#tab-compare');
    await page.waitForSelector('#compare-source-why:not([hidden])');
    await page.waitForFunction(() => /recorded disturbances: none yet/.test(document.querySelector('#compare-source-why')?.textContent ?? ''));
    assert.equal(await recordedOption(page), true);
    await page.screenshot({ path: join(screenshots, 'compare-nothing-recorded-1440.png') });

    // A real drag in the Run, 0.5 s into the episode: block a onto c, the block the arm reaches for.
    await page.click('#tab-run');
    for (let i = 0; i < 5; i++) await page.click('#step');
    await page.waitForFunction(() => window.lfd.frame().t >= 0.49);
    const c = (await currentFrame(page)).world.bodies.find((b) => b.name === 'c').pose.position;
    await dragBody(page, 'a', await page.evaluate((p) => window.lfd.project(p), [c[0], c[1], c[2] + 0.03]));
    await page.waitForFunction(() => window.lfd.marks().some((m) => m.kind === 'drag'), null, { timeout: 10000 });
    const drag = await page.evaluate(() => window.lfd.marks().find((m) => m.kind === 'drag'));
    const before = await currentFrame(page);

    await page.click('#tab-compare');
    await page.waitForSelector('#compare-source-why', { state: 'hidden' });
    assert.equal(await recordedOption(page), false);
    await page.selectOption('#compare-source', 'recorded');
    assert.equal(await page.isVisible('#compare-level'), false, 'the scripted level is hidden');
    await page.click('#compare-run');
    await page.waitForSelector('.compare[data-done="true"]', { timeout: 240000 });

    const label = `drag a at ${drag.t.toFixed(2)} s`;
    assert.match(await page.textContent('#compare-note'), new RegExp(`B1 · seed 1 · the Run’s recorded disturbances: ${label}$`));
    const rows = await compareRows(page);
    assert.equal(rows.length, 5);
    for (const r of rows) assert.ok(r.disturbance.startsWith(`${label}: `), `${r.name}: ${r.disturbance}`);
    for (const n of ['Logic-LfD (paper)', 'Logic-LfD (prioritised)']) {
      const r = rows.find((x) => x.name === n);
      assert.match(r.result, /success/, `${n}: ${r.reason}`);
      assert.match(r.disturbance, /: Moved a onto c/, `${n} met the drag: ${r.disturbance}`);
      assert.ok(r.replans >= 2, `${n} replanned after the drag`);
    }
    // A stacked c cannot be picked as demonstrated: the fixed plan and the demo's states fail.
    assert.match(rows.find((x) => x.name === 'Linear').result, /failed/);
    assert.match(rows.find((x) => x.name === 'RLDS').reason, /no remaining part of the demonstration/);
    // The Run's own episode was not touched.
    assert.equal((await currentFrame(page)).tick, before.tick);

    await page.screenshot({ path: join(screenshots, 'compare-recorded-1440.png') });
    await page.setViewportSize({ width: 1024, height: 700 });
    await page.screenshot({ path: join(screenshots, 'compare-recorded-1024.png') });
    await page.setViewportSize({ width: 390, height: 844 });
    await page.screenshot({ path: join(screenshots, 'compare-recorded-390.png'), fullPage: true });
    assert.deepEqual(errors, []);
    await page.close();
  });
});
