// Browser tests of failed loads (Debian Chromium): a file with a value of the wrong type deep
// inside is refused with its JSON path, what was expected, and its line and column — in Teach
// mode's Load and in the scene loader — and nothing changes: the loaded demo, the scene and the
// session stay as they were.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { currentFrame, openApp, screenshots, useBrowser } from './harness.mjs';
import { withValueAt } from '../json-at.mjs';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

const ctx = useBrowser({ withScreenshots: true });

const file = (name, text) => ({ name, mimeType: 'application/json', buffer: Buffer.from(text) });

describe('failed loads', () => {
  test('Teach: a demo with a wrong type deep inside is refused with its path; the loaded demo stays', async () => {
    const t = new lfd.Teacher('b1');
    assert.ok(t.push({ edit: 'drag', body: 'c', onto: 'd' }).ok);
    const fin = t.finish();
    assert.ok(fin.ok, JSON.stringify(fin));
    t.free();
    const good = JSON.parse(fin.demoJson);
    const bad = withValueAt(good, ['scene', 'bodies', 3, 'pose', 'position', 0], 'x');

    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&autoplay=0');
    await page.click('#tab-teach');
    await page.waitForSelector('#teach-load');
    await page.setInputFiles('#panel-teach input[type=file]', file('good.json', fin.demoJson));
    await page.waitForFunction(() => /Loaded good\.json: 2 actions/.test(document.querySelector('#teach-summary').textContent));
    const info = await page.evaluate(() => window.lfdTeach.info());

    await page.setInputFiles('#panel-teach input[type=file]', file('demo.json', bad.text));
    await page.waitForSelector('#teach-error:not([hidden])', { timeout: 10000 });
    const msg = (await page.textContent('#teach-error')).trim();
    const want = `demo.json: scene.bodies[3].pose.position[0]: invalid type: string "x", expected f64 at line ${bad.line} column ${bad.column}`;
    assert.ok(msg.includes(want), `${msg}\nwanted: ${want}`);
    assert.match(msg, /Nothing was loaded: the demonstration listed below is unchanged\./);
    // Nothing changed: the loaded demo is still the one listed and run.
    assert.match(await page.textContent('#teach-summary'), /Loaded good\.json: 2 actions/);
    assert.deepEqual(await page.evaluate(() => window.lfdTeach.info()), info);
    await page.screenshot({ path: join(screenshots, 'load-error-teach-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('scene loader: a scene with a wrong type deep inside is refused with its path; the session stays', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&autoplay=0');
    for (let i = 0; i < 3; i++) await page.click('#step');
    await page.waitForFunction(() => window.lfd.frame().tick >= 30);
    const before = await currentFrame(page);
    const bad = withValueAt(before.world, ['bodies', 2, 'pose', 'position', 1], 'x');

    const chooser = page.waitForEvent('filechooser');
    await page.click('#load-scene');
    await (await chooser).setFiles(file('bad-scene.json', bad.text));
    await page.waitForSelector('#notice.error:not([hidden])');
    const msg = (await page.textContent('#notice')).trim();
    const want = `bad-scene.json was not loaded: scene: bodies[2].pose.position[1]: invalid type: string "x", expected f64 at line ${bad.line} column ${bad.column}`;
    assert.ok(msg.startsWith(want), `${msg}\nwanted: ${want}`);
    // Nothing changed: the same session at the same tick with the same world.
    const after = await currentFrame(page);
    assert.equal(after.tick, before.tick);
    assert.deepEqual(after.world, before.world);
    await page.screenshot({ path: join(screenshots, 'load-error-scene-1440.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });
});
