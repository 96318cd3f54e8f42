// The worker's move onto the full-speed module (web/src/speed-up.ts): after the first frame it
// fetches the full module, warms it up, replays the live episode on it and switches when the
// replay is identical; the run then goes on without a jump and replans on the new module.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { finish, openApp, useBrowser } from './harness.mjs';

const ctx = useBrowser();

test('the session moves onto the full-speed module and plays on without a jump', { timeout: 180000 }, async () => {
  const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=3');
  // Frames before and after the move: time never goes back and the facts never jump.
  await page.evaluate(() => {
    const seen = [];
    /** @type {any} */ (window).seen = seen;
    const poll = () => {
      const f = window.lfd.frame();
      if (f && seen[seen.length - 1]?.tick !== f.tick) seen.push({ t: f.t, tick: f.tick, added: f.factsAdded.length });
      requestAnimationFrame(poll);
    };
    poll();
  });
  let s = await page.evaluate(() => window.lfd.speedUp());
  for (const end = Date.now() + 60000; ['idle', 'loading', 'warming'].includes(s.stage) && Date.now() < end; ) {
    await new Promise((r) => setTimeout(r, 100));
    s = await page.evaluate(() => window.lfd.speedUp());
  }
  assert.equal(s.stage, 'ready', `speed-up ended ${s.stage}: ${s.reason}`);
  assert.equal(s.moved, 1);
  assert.ok(s.warmReplans > 0, 'the warm-up replanned nothing');

  // A disturbance after the move replans on the full module and the run still ends.
  const before = (await page.evaluate(() => window.lfd.frame())).replans;
  await page.waitForSelector('#inject-l3:not([aria-disabled="true"])', { timeout: 60000 });
  await page.click('#inject-l3');
  await page.waitForFunction((n) => (window.lfd.frame()?.replans ?? 0) > n, before, { timeout: 60000 });
  const last = await finish(page);
  assert.equal(last.status.kind, 'done', last.status.message);

  const seen = await page.evaluate(() => /** @type {any} */ (window).seen);
  for (let i = 1; i < seen.length; i++) {
    assert.ok(seen[i].t >= seen[i - 1].t && seen[i].tick > seen[i - 1].tick, `frame ${i} went back: ${JSON.stringify(seen.slice(i - 1, i + 1))}`);
    // B1 holds about 15 facts; one step changes a handful.
    assert.ok(seen[i].added <= 6, `frame ${i} added ${seen[i].added} facts at once`);
  }
  assert.deepEqual(errors, []);
  await page.close();
});
