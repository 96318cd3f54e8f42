// Browser tests of the robot select: the UR5 in the arms' place from the select and from a link,
// drawn with its own meshes (kinematic finger boxes beside them); a robot folder opened from this
// computer runs drawn as capsules; a robot that cannot reach the task is refused with the reason
// and changes nothing.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { cpSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { compareRows, currentFrame, finish, openApp, root, runScriptedCompare, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

const meshInfo = (page) => page.evaluate(() => window.lfd.armMeshes());

/** A robot folder on disk: the UR5's URDF and meshes with `robot.json` renamed to `name`;
 * `reach` scales the robot file's TCP offset (a long tool cannot reach the table's blocks). */
function ur5Folder(name, tcpZ = 0.15) {
  const dir = mkdtempSync(join(tmpdir(), 'robot-folder-'));
  const folder = join(dir, name);
  cpSync(join(root, 'robots', 'example-robot-data', 'robots', 'ur_description'), join(folder, 'example-robot-data', 'robots', 'ur_description'), { recursive: true });
  const robot = JSON.parse(readFileSync(join(root, 'robots', 'ur5.json'), 'utf8'));
  robot.name = name;
  robot.tcp.xyz[2] = tcpZ;
  writeFileSync(join(folder, 'robot.json'), JSON.stringify(robot));
  return folder;
}

describe('the robot select', () => {
  test('the UR5 from the select: six joints drawn with its meshes, the link keeps it, B2 finishes', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b2&seed=1&autoplay=0');
    assert.equal(await page.inputValue('#robot'), 'panda');
    await page.selectOption('#robot', 'ur5');
    await page.waitForFunction(() => window.lfd.frame()?.world.arms[0].robot === 'ur5', null, { timeout: 60000 });
    await page.waitForFunction(() => new URLSearchParams(location.search).get('robot') === 'ur5');
    assert.match(await page.textContent('#notice'), /The arms are now the UR5\./);
    await page.waitForFunction(() => document.querySelector('.stage canvas')?.getAttribute('data-meshes-of')?.includes('ur5'), null, { timeout: 30000 });
    await page.click('#play');
    await page.waitForFunction(() => (window.lfd.frame()?.t ?? 0) > 4, null, { timeout: 60000 });
    const info = await meshInfo(page);
    const arm = info.arms[0];
    assert.ok(arm?.shown, 'the UR5 drawn with its meshes');
    assert.equal(arm.drawn.joints.length, 6);
    assert.ok(arm.links.wrist_3_link && arm.links.shoulder_link, Object.keys(arm.links).join(' '));
    await page.screenshot({ path: join(screenshots, 'robot-ur5-b2.png') });
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.deepEqual(errors, []);
    await page.close();

    // A link with ?robot=ur5 opens on the UR5.
    const again = await openApp(ctx.browser, ctx.server, '?benchmark=b1&robot=ur5&autoplay=0');
    await again.page.waitForFunction(() => window.lfd.frame()?.world.arms[0].robot === 'ur5', null, { timeout: 60000 });
    assert.equal(await again.page.inputValue('#robot'), 'ur5');
    await again.page.selectOption('#robot', 'panda');
    // The Panda: from its URDF on the full module, the built-in one (no robot named) on the first-load module.
    await again.page.waitForFunction(() => (window.lfd.frame()?.world.arms[0].robot ?? 'panda') === 'panda', null, { timeout: 60000 });
    assert.equal(new URLSearchParams(new URL(again.page.url()).search).get('robot'), null);
    assert.deepEqual(again.errors, []);
    await again.page.close();
  });

  test('a robot folder from this computer runs, drawn as capsules; one that cannot reach is refused', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&autoplay=0');
    let chooser = page.waitForEvent('filechooser');
    await page.selectOption('#robot', 'open-robot');
    let picker = await chooser;
    assert.equal(await picker.element().getAttribute('id'), 'robot-dir');
    await picker.setFiles(ur5Folder('my-arm'));
    await page.waitForFunction(() => window.lfd.frame()?.world.arms[0].robot === 'my-arm', null, { timeout: 60000 });
    assert.equal(await page.inputValue('#robot'), 'robot-folder');
    assert.match(await page.textContent('#robot option[value="robot-folder"]'), /my-arm \(folder\)/);
    await page.waitForFunction(() => /drawn as capsules/.test(document.getElementById('notice')?.textContent ?? ''), null, { timeout: 10000 });
    assert.equal((await meshInfo(page)).arms[0], null, 'no meshes for a robot of its own');
    await page.click('#play');
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);
    await page.screenshot({ path: join(screenshots, 'robot-folder-b1.png') });

    // A tool 1.2 m long puts every block out of reach: refused by block and distance, nothing changed.
    const before = await currentFrame(page);
    chooser = page.waitForEvent('filechooser');
    await page.selectOption('#robot', 'open-robot');
    picker = await chooser;
    await picker.setFiles(ur5Folder('long-tool', 1.2));
    await page.waitForFunction(() => /was not put in the arms' place/.test(document.getElementById('notice')?.textContent ?? ''), null, { timeout: 60000 });
    assert.match(await page.textContent('#notice'), /The robot long-tool was not put in the arms' place: block [a-d] lies .* out of the robots' reach/);
    assert.equal(await page.inputValue('#robot'), 'robot-folder');
    const after = await currentFrame(page);
    assert.equal(after.world.arms[0].robot, 'my-arm');
    assert.equal(after.tick, before.tick);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Compare runs every method on the robot the Run has', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=2&robot=ur5&autoplay=0');
    await page.waitForFunction(() => window.lfd.frame()?.world.arms[0].robot === 'ur5', null, { timeout: 60000 });
    await runScriptedCompare(page, 'l3', 0.5);
    assert.match(await page.textContent('#compare-note'), /^B1 · UR5 · seed 2 · Scramble at 0\.5 s/);
    const rows = await compareRows(page);
    for (const n of ['Logic-LfD (paper)', 'Logic-LfD (prioritised)', 'TAMP']) {
      const row = rows.find((r) => r.name === n);
      assert.match(row.result, /success/, `${n}: ${row.reason}`);
    }
    assert.deepEqual(errors, []);
    await page.close();
  });
});
