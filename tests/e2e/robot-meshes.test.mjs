// Browser tests of the arms drawn with the Panda's own meshes (web/src/robot-meshes.ts): fetched
// only after the first frame (the first load stays within its budget), posed from each frame's
// joint angles and gripper opening (the drawn links sit on the simulator's capsule ends, the drawn
// TCP on the frame's TCP, the fingers around it), the Capsules / Meshes switch, and blocks still
// dragged through the meshes.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { gzipSync } from 'node:zlib';
import { currentFrame, finish, openApp, screenshots, useBrowser } from './harness.mjs';
import { dragBody, dropPoint, waitStatus } from './ux-helpers.mjs';

const ctx = useBrowser({ withScreenshots: true });

/** The page's first-load budget: what it fetches until the first frame is drawn, gzip -9. */
const FIRST_LOAD_BUDGET = 600 * 1024;

const sub = (a, b) => a.map((x, i) => x - b[i]);
const norm = (a) => Math.hypot(...a);
const dist = (a, b) => norm(sub(a, b));
const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
/** The z axis of a unit quaternion [x, y, z, w]. */
const zAxis = ([x, y, z, w]) => [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)];

/** Which link frames the simulator's capsules join (crate/src/sim/geometry.rs, `links_of`). */
const CAPSULE_LINKS = [
  ['panda_link0', 'panda_link1'],
  ['panda_link2', 'panda_link3'],
  ['panda_link3', 'panda_link4'],
  ['panda_link4', 'panda_link5'],
  ['panda_link5', 'panda_link7'],
  ['panda_link7', 'panda_link8'],
];

/**
 * Checks one arm's meshes against the snapshot they were drawn from: every link frame on its
 * capsule's end (1 mm; the built-in Panda's capsules), the TCP frame on the snapshot's TCP
 * (5 mm, same approach axis), the fingers either side of the TCP's axis. Returns the fingers' spacing less the opening.
 */
function checkArm(arm) {
  const d = arm.drawn;
  assert.equal(d.joints.length, 7);
  // The built-in Panda's capsules join link frames; a URDF arm's are fitted to its link shapes.
  if (d.robot == null) CAPSULE_LINKS.forEach(([a, b], i) => {
    assert.ok(dist(arm.links[a], d.links[i].a) < 1e-3, `${d.name}: ${a} drawn at ${arm.links[a]}, capsule ${i} starts at ${d.links[i].a}`);
    assert.ok(dist(arm.links[b], d.links[i].b) < 1e-3, `${d.name}: ${b} drawn at ${arm.links[b]}, capsule ${i} ends at ${d.links[i].b}`);
  });
  assert.ok(dist(arm.links.panda_link0, d.base.position) < 1e-6, `${d.name}: base drawn at ${arm.links.panda_link0}, not ${d.base.position}`);
  const tcpError = dist(arm.tcp.position, d.tcp.position);
  assert.ok(tcpError < 0.005, `${d.name}: the drawn TCP is ${(tcpError * 1000).toFixed(1)} mm from the simulated one`);
  assert.ok(dot(arm.tcp.z, zAxis(d.tcp.quaternion)) > 0.999, `${d.name}: approach axis ${arm.tcp.z} vs ${zAxis(d.tcp.quaternion)}`);
  // The fingers' meshes: their middle on the TCP's approach axis, their spacing following the opening.
  assert.equal(arm.fingers.length, 2);
  const mid = arm.fingers[0].map((x, i) => (x + arm.fingers[1][i]) / 2);
  const off = sub(mid, arm.tcp.position);
  const lateral = norm(sub(off, arm.tcp.z.map((z) => z * dot(off, arm.tcp.z))));
  assert.ok(lateral < 0.005, `${d.name}: the fingers' middle is ${(lateral * 1000).toFixed(1)} mm off the TCP's axis`);
  return dist(arm.fingers[0], arm.fingers[1]) - d.gripper_opening;
}

const meshInfo = (page) => page.evaluate(() => window.lfd.armMeshes());

describe("the arms drawn with the robot's meshes", () => {
  test('fetched after the first frame, posed from every frame: links on the capsules, TCP within 5 mm', async () => {
    const requests = [];
    const page = await ctx.browser.newPage({ viewport: { width: 1440, height: 900 } });
    const errors = [];
    page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('request', (r) => requests.push({ url: r.url(), at: Date.now() }));
    await page.goto(`${ctx.server.url}?benchmark=b1&seed=1`);
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
    const readyAt = await page.evaluate(() => performance.timeOrigin + window.lfd.loadedAt);
    await page.waitForSelector('.stage canvas[data-meshes="loaded"]', { timeout: 30000 });
    const meshFetches = requests.filter((r) => /\/robots\/panda\/|robot-meshes-/.test(r.url));
    assert.ok(meshFetches.some((r) => r.url.endsWith('/robots/panda/hand.glb')), 'the hand mesh was fetched');
    for (const r of meshFetches) assert.ok(r.at >= readyAt - 1, `${r.url} fetched ${(readyAt - r.at).toFixed(0)} ms before the first frame`);

    // Sample the drawn arm while it works: every sample drawn as its frame says.
    const samples = [];
    while (samples.length < 40) {
      const info = await meshInfo(page);
      assert.equal(info.style, 'meshes');
      assert.ok(info.loaded);
      const arm = info.arms[0];
      assert.ok(arm && arm.shown, 'arm 0 is drawn with its meshes');
      samples.push({ joints: arm.drawn.joints, opening: arm.drawn.gripper_opening, spread: checkArm(arm), tcp: arm.tcp.position });
      if ((await currentFrame(page)).status.kind === 'done') break;
      await page.waitForTimeout(200);
    }
    assert.ok(samples.length >= 10, `${samples.length} samples before the run ended`);
    // Every joint moved during the run, and the drawn hand with them.
    for (let j = 0; j < 7; j++) {
      const qs = samples.map((s) => s.joints[j]);
      assert.ok(Math.max(...qs) - Math.min(...qs) > 0.01, `joint ${j + 1} never moved: ${qs.map((q) => q.toFixed(3))}`);
    }
    const travel = Math.max(...samples.map((s) => dist(s.tcp, samples[0].tcp)));
    assert.ok(travel > 0.1, `the drawn TCP moved ${travel.toFixed(3)} m`);
    // The gripper closed and opened, and the finger meshes kept the same spacing beyond the opening.
    const openings = samples.map((s) => s.opening);
    assert.ok(Math.max(...openings) - Math.min(...openings) > 0.01, `opening ${Math.min(...openings)}..${Math.max(...openings)}`);
    const spreads = samples.map((s) => s.spread);
    assert.ok(Math.max(...spreads) - Math.min(...spreads) < 1e-3, `finger spacing less opening varies: ${spreads.map((s) => s.toFixed(4))}`);
    await page.screenshot({ path: join(screenshots, 'robot-meshes-b1.png') });

    // Paused, the meshes show the page's current frame itself.
    await finish(page);
    const [info, frame] = await Promise.all([meshInfo(page), currentFrame(page)]);
    assert.deepEqual(info.arms[0].drawn.joints, frame.world.arms[0].joints);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('two arms (B3): each on its own base, and the Capsules / Meshes switch', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b3&seed=1');
    await page.waitForSelector('.stage canvas[data-meshes="loaded"]', { timeout: 30000 });
    await page.waitForFunction(() => (window.lfd.frame()?.t ?? 0) > 2, null, { timeout: 30000 });
    const info = await meshInfo(page);
    assert.equal(info.arms.length, 2);
    for (const arm of info.arms) {
      assert.ok(arm?.shown, 'both arms drawn with meshes');
      checkArm(arm);
    }
    assert.ok(dist(info.arms[0].links.panda_link0, info.arms[1].links.panda_link0) > 0.3, 'two bases apart');
    await page.screenshot({ path: join(screenshots, 'robot-meshes-b3.png') });

    await page.click('#arm-capsules');
    assert.equal(await page.getAttribute('#arm-capsules', 'aria-pressed'), 'true');
    const capsules = await meshInfo(page);
    assert.equal(capsules.style, 'capsules');
    assert.ok(capsules.arms.every((a) => a && !a.shown), 'the meshes hidden');
    assert.equal(await page.$eval('.stage canvas', (c) => c.dataset.armStyle), 'capsules');
    await page.screenshot({ path: join(screenshots, 'robot-meshes-b3-capsules.png') });
    await page.click('#arm-meshes');
    assert.ok((await meshInfo(page)).arms.every((a) => a?.shown), 'the meshes shown again');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('?arm=capsules starts with the capsules; the meshes load all the same', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&arm=capsules');
    await page.waitForSelector('.stage canvas[data-meshes="loaded"]', { timeout: 30000 });
    const info = await meshInfo(page);
    assert.equal(info.style, 'capsules');
    assert.equal(info.arms[0]?.shown, false);
    assert.equal(await page.getAttribute('#arm-capsules', 'aria-pressed'), 'true');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a mesh that cannot be fetched leaves the capsules and says which file', async () => {
    const page = await ctx.browser.newPage({ viewport: { width: 1440, height: 900 } });
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.route('**/robots/panda/hand.glb', (r) => r.fulfill({ status: 404, body: 'not found' }));
    await page.goto(`${ctx.server.url}?benchmark=b1`);
    await page.waitForSelector('.stage canvas[data-meshes="failed"]', { timeout: 30000 });
    const notice = await page.textContent('#notice');
    assert.match(notice, /robot's meshes could not be loaded \(\/robots\/panda\/hand\.glb: HTTP 404\)/);
    const info = await meshInfo(page);
    assert.equal(info.loaded, false);
    assert.deepEqual(info.arms, [null], 'no meshes drawn');
    assert.equal(await page.$('.arm-style'), null, 'no switch without meshes');
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a block is still dragged with the meshes drawn: the robot replans and finishes', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=8');
    // Where a starts (read at once: at 8× it is soon on the tower).
    const start = (await currentFrame(page)).world.bodies.find((b) => b.name === 'a').pose.position;
    await page.waitForSelector('.stage canvas[data-meshes="loaded"]', { timeout: 30000 });
    const done = await finish(page);
    assert.equal(done.status.kind, 'done', done.status.message);
    assert.ok((await meshInfo(page)).arms[0]?.shown);
    await dragBody(page, 'a', await dropPoint(page, start));
    await waitStatus(page, ['done'], { not: true, timeout: 10000 });
    const again = await finish(page);
    assert.equal(again.status.kind, 'done', again.status.message);
    assert.ok(again.replans > done.replans, `replans ${done.replans} → ${again.replans}`);
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('first load', () => {
  test(`what the page fetches until the first frame stays within ${FIRST_LOAD_BUDGET / 1024} KiB gzipped, without the meshes`, async () => {
    const page = await ctx.browser.newPage({ viewport: { width: 1440, height: 900 } });
    const responses = [];
    page.on('response', (r) => r.status() === 200 && r.url().startsWith(ctx.server.url) && responses.push(r));
    await page.goto(`${ctx.server.url}?benchmark=b1`);
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
    // What was asked for before the first frame was drawn (the page's and its worker's fetches).
    const readyAt = await page.evaluate(() => performance.timeOrigin + window.lfd.loadedAt);
    const before = responses.filter((r) => r.request().timing().startTime <= readyAt);
    const bodies = before.map(async (r) => ({ url: r.url(), gz: gzipSync(await r.body(), { level: 9 }).length }));
    const files = await Promise.all(bodies);
    const total = files.reduce((s, f) => s + f.gz, 0);
    const list = files.map((f) => `${f.url.slice(ctx.server.url.length) || '/'} ${(f.gz / 1024).toFixed(1)} KiB`).join(', ');
    console.log(`first load: ${(total / 1024).toFixed(1)} KiB gzipped (${list})`);
    assert.ok(!files.some((f) => /robots\/|robot-meshes-/.test(f.url)), `meshes in the first load: ${list}`);
    assert.ok(total <= FIRST_LOAD_BUDGET, `first load ${(total / 1024).toFixed(1)} KiB > ${FIRST_LOAD_BUDGET / 1024} KiB: ${list}`);
    await page.close();
  });
});
