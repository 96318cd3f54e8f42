// Browser test of the Run tab's "why L_k?" panel: after an L3 disturbance on B1 the replan line
// says which L_k it joined, and the panel (a lazy chunk) lists the candidates with the costs the
// replan's search found and the mode's reason.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { openApp, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

/** Steps the paused run to tick 160 and injects L3 there (stepping 0.1 s more while the
 * injector finds no move now); returns the tick of the injection. The time is the same on every
 * run: a wall-clock one would give each run another state, and another replan to check. */
async function injectL3(page) {
  while ((await page.evaluate(() => window.lfd.frame().tick)) < 160) await page.click('#step');
  for (let attempt = 0; attempt < 10; attempt++) {
    const before = await page.evaluate(() => window.lfd.frame().tick);
    await page.click('#inject-l3', { force: true });
    await page.waitForSelector('#notice:not([hidden])', { timeout: 10000 });
    const text = await page.textContent('#notice');
    if (!/refused|cannot/i.test(text)) return before;
    await page.evaluate(() => document.getElementById('notice').setAttribute('hidden', ''));
    await page.click('#step');
  }
  throw new Error('L3 was refused ten times');
}

describe('why L_k', () => {
  for (const [mode, width, height] of [['paper', 1440, 900], ['prioritised', 390, 844]]) {
    test(`${mode}: a replan after L3 shows the L_k it joined and why, with the candidates' costs (${width}x${height})`, async () => {
      const { page, errors } = await openApp(ctx.browser, ctx.server, `?benchmark=b1&seed=3&mode=${mode}&autoplay=0`, { width, height });
      const at = await injectL3(page);
      // The replan that searched (a new prefix): its record carries the candidates.
      const r = await page.waitForFunction(
        (t) => {
          const r = window.lfd.frame().lastReplan;
          return r && r.tick >= t && r.alternatives.some((a) => a.status === 'joined' && a.prefix > 0) && r;
        },
        at,
        { timeout: 30000, polling: 20 },
      ).then((h) => h.jsonValue());
      if (await page.getAttribute('#play', 'aria-pressed') === 'true') await page.click('#play');
      const joined = r.k == null ? 'G' : `L${r.k}`;
      const line = page.locator('#replan-info .replan', { hasText: `at tick ${r.tick}:` }).first();
      assert.match(await line.textContent(), new RegExp(`joined ${joined} \\(`));
      await line.locator('.why-btn').click();
      const panel = page.locator('#replan-info .why-join');
      await panel.waitFor();
      const rows = await panel.locator('tbody tr').evaluateAll((trs) => trs.map((tr) => [...tr.cells].map((c) => c.textContent)));
      assert.equal(rows.length, r.alternatives.length);
      const numbered = rows.filter((c) => /^\d+$/.test(c[3]));
      // Paper mode stops at the first L_k reached: the others are marked, not given numbers;
      // prioritised mode weighs every one: a path found, or proved no cheaper.
      if (mode === 'paper') assert.ok(rows.some((c) => c[4] === 'not reached (search stopped)'), JSON.stringify(rows));
      else assert.ok(rows.every((c) => /^\d+$/.test(c[3]) || c[4] === 'no cheaper plan (proved)'), JSON.stringify(rows));
      assert.ok(numbered.length >= 1, `no candidate with numbers: ${JSON.stringify(rows)}`);
      for (const c of numbered) assert.equal(+c[1] + +c[2], +c[3], `prefix + demo left = total: ${c}`);
      const mine = rows.find((c) => c[4] === 'joined');
      assert.equal(mine[0], joined);
      const sentence = await panel.locator('.why-sentence').textContent();
      assert.match(sentence, mode === 'paper' ? /^Paper: .*first state satisfying any/ : /^Prioritised: .*least total/);
      if (mode === 'prioritised') assert.equal(+mine[3], Math.min(...numbered.map((c) => +c[3])));
      await page.screenshot({ path: join(screenshots, `why-join-${mode}-${width}.png`) });
      // The Run tab lists every replan, newest first — also one whose frames were drawn over by
      // a later replan's within one animation frame (the timeline's markers see every frame).
      const listed = await page.$$eval('#replan-info .replan', (ls) => ls.map((l) => Number(/at tick (\d+):/.exec(l.textContent)[1])));
      const marked = await page.evaluate(() => {
        const dt = window.lfd.frame().world.dt;
        return [...new Set(window.lfd.marks().filter((m) => m.kind === 'replan').map((m) => Math.round(m.t / dt)))].reverse();
      });
      assert.deepEqual(listed, marked.slice(0, listed.length));
      assert.equal(listed.length, Math.min(6, marked.length));
      assert.deepEqual(errors, []);
      await page.close();
    });
  }
});
