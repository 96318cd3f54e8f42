// Browser tests of the page (Debian Chromium, headless, WebGL through SwiftShader), driven with
// real mouse and keyboard events against the production build in web/dist.
import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdir } from 'node:fs/promises';
import { join } from 'node:path';
import { launch, openPage, screenshots, serve } from './harness.mjs';

let server;
let browser;

before(async () => {
  server = await serve();
  browser = await launch();
  await mkdir(screenshots, { recursive: true });
});

after(async () => {
  await browser?.close();
  await server?.close();
});

const terminal = (kinds) => (f) => f && kinds.includes(f.status.kind);

/** Opens the page with URL parameters and waits until the worker has drawn the first frame. */
async function open(query = '') {
  const r = await openPage(browser, `${server.url}${query}`);
  await r.page.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
  return r;
}

async function frame(page) {
  return page.evaluate(() => window.lfd.frame());
}

/** Waits until the run is done or failed and returns the last frame. */
async function finish(page, timeout = 120000) {
  await page.waitForFunction(
    () => {
      const f = window.lfd.frame();
      return f && (f.status.kind === 'done' || f.status.kind === 'failed');
    },
    null,
    { timeout, polling: 200 },
  );
  return frame(page);
}

describe('page', () => {
  test('loads the wasm in a worker and draws B1 with no console errors', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    const f = await frame(page);
    assert.equal(f.world.name.startsWith('b1'), true, `scene ${f.world.name}`);
    assert.ok(f.world.bodies.some((b) => b.kind === 'block'));
    assert.ok(f.world.arms.length >= 1);
    // Every control has an accessible name.
    const unnamed = await page.evaluate(() =>
      [...document.querySelectorAll('button, select, input')]
        .filter((e) => !e.hidden && !(e.getAttribute('aria-label') || e.textContent?.trim() || e.closest('label')))
        .map((e) => e.outerHTML),
    );
    assert.deepEqual(unnamed, []);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('B1 runs to success', async () => {
    const { page, errors } = await open('?benchmark=b1&speed=8&seed=1');
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.match(await page.textContent('#status-text'), /done/i);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('dragging a block during execution makes the robot replan and still succeed', async () => {
    const { page, errors } = await open('?benchmark=b1&speed=2&seed=3');
    // Wait until the robot has put at least one block on another (the tower is growing).
    await page.waitForFunction(
      () => {
        const f = window.lfd.frame();
        return f && f.status.kind === 'executing' && (f.executing ?? 0) >= 2;
      },
      null,
      { timeout: 60000, polling: 100 },
    );
    // Drag the top-most clear block that the arm is not holding onto the free table.
    const target = await page.evaluate(() => {
      const f = window.lfd.frame();
      const held = new Set(f.world.arms.map((a) => a.holding).filter(Boolean));
      const blocks = f.world.bodies.filter((b) => b.kind === 'block' && !held.has(b.name) && !b.lost);
      const clear = blocks.filter((b) => f.facts.includes(`(clear ${b.name})`));
      clear.sort((a, b) => b.pose.position[2] - a.pose.position[2]);
      const pick = clear[0];
      const table = f.world.bodies.find((b) => b.kind === 'table');
      const [tx, ty, tz] = table.pose.position;
      const half = table.shape.type === 'cuboid' ? table.shape.half_extents : [0.3, 0.3, 0.02];
      // A free spot near the table's front-left corner, on its top face.
      const drop = [tx - half[0] * 0.6, ty - half[1] * 0.6, tz + half[2] + 0.03];
      return { name: pick.name, from: window.lfd.screenPosition(pick.name), to: window.lfd.project(drop) };
    });
    await page.mouse.move(target.from.x, target.from.y);
    await page.mouse.down();
    for (let i = 1; i <= 12; i++) {
      await page.mouse.move(
        target.from.x + ((target.to.x - target.from.x) * i) / 12,
        target.from.y + ((target.to.y - target.from.y) * i) / 12,
      );
    }
    await page.mouse.up();
    await page.waitForFunction(
      () => {
        const f = window.lfd.frame();
        return f && (f.status.kind === 'replanning' || (f.last_replan && f.replans > 0));
      },
      null,
      { timeout: 20000, polling: 20 },
    );
    const seen = await page.evaluate(() => {
      const f = window.lfd.frame();
      return { replans: f.replans, reason: f.last_replan?.reason ?? f.status.message };
    });
    assert.ok(seen.replans >= 1, `expected a replan after moving ${target.name}`);
    const f = await finish(page);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.deepEqual(errors, []);
    await page.close();
  });

  for (const level of ['l1', 'l2', 'l3', 'l4']) {
    test(`the ${level.toUpperCase()} button disturbs the run and the run still ends`, async () => {
      const { page, errors } = await open(`?benchmark=b1&speed=4&seed=2`);
      await page.waitForFunction(() => (window.lfd.frame()?.t ?? 0) > 1.0, null, { timeout: 30000 });
      const before = await frame(page);
      await page.click(`#inject-${level}`);
      await page.waitForSelector('#notice:not([hidden])', { timeout: 10000 });
      const text = await page.textContent('#notice');
      assert.match(text, new RegExp(level, 'i'));
      assert.doesNotMatch(text, /refused/i, text);
      const f = await finish(page);
      assert.ok(f.tick > before.tick);
      if (level !== 'l1') assert.ok(f.replans >= 1 || f.status.kind === 'done', f.status.message);
      assert.equal(f.status.kind, 'done', f.status.message);
      assert.deepEqual(errors, []);
      await page.close();
    });
  }

  test('an error in the PDDL editor is shown at its line:col', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await page.click('#tab-pddl');
    await page.waitForFunction(() => document.querySelector('#panel-pddl .cm-content')?.textContent.includes('define'));
    // Type a stray token on line 2 of the domain.
    const line2 = page.locator('#panel-pddl .cm-host:not([hidden]) .cm-line').nth(1);
    await line2.click();
    await page.keyboard.press('End');
    await page.keyboard.type(' (:bogus');
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-errors li', { timeout: 10000 });
    const msg = await page.textContent('#pddl-errors li');
    assert.match(msg, /domain\.pddl:\d+:\d+/);
    // The editor marks the error inline too.
    await page.waitForSelector('#panel-pddl .cm-lintRange-error, #panel-pddl .cm-lint-marker-error', { timeout: 5000 });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('the PDDL editor plans the benchmark and steps through the states', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await page.click('#tab-pddl');
    await page.waitForFunction(() => document.querySelector('#panel-pddl .cm-content')?.textContent.includes('define'));
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-plan-list button.step[data-index="1"]', { timeout: 20000 });
    const n = await page.locator('#pddl-plan-list button.step').count();
    assert.ok(n >= 2);
    await page.click('#pddl-plan-list button.step[data-index="1"]');
    assert.match(await page.textContent('#pddl-state .state-title'), /After step 1/);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('the permalink restores benchmark, method, mode and seed', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await page.selectOption('#method', 'rlds');
    await page.selectOption('#mode', 'prioritised');
    await page.fill('#seed', '7');
    await page.press('#seed', 'Enter');
    await page.waitForFunction(() => location.search.includes('seed=7') && location.search.includes('method=rlds'));
    const url = page.url();
    await page.close();
    const again = await open(new URL(url).search + '&autoplay=0');
    assert.equal(await again.page.inputValue('#method'), 'rlds');
    assert.equal(await again.page.inputValue('#mode'), 'prioritised');
    assert.equal(await again.page.inputValue('#seed'), '7');
    assert.equal(await again.page.inputValue('#benchmark'), 'b1');
    assert.deepEqual([...errors, ...again.errors], []);
    await again.page.close();
  });

  test('the help overlay opens with ? and closes with Escape', async () => {
    const { page } = await open('?benchmark=b1&autoplay=0');
    await page.locator('canvas').focus();
    await page.keyboard.press('?');
    await page.waitForSelector('#help-overlay:not([hidden])');
    await page.keyboard.press('Escape');
    await page.waitForSelector('#help-overlay', { state: 'hidden' });
    await page.close();
  });

  for (const b of ['b1', 'b2', 'b3']) {
    test(`screenshot of ${b.toUpperCase()}`, async () => {
      const { page, errors } = await open(`?benchmark=${b}&speed=2&seed=1`);
      await page.waitForFunction(() => (window.lfd.frame()?.t ?? 0) > 3, null, { timeout: 60000 });
      await page.waitForTimeout(300);
      await page.screenshot({ path: join(screenshots, `${b}.png`) });
      assert.deepEqual(errors, []);
      await page.close();
    });
  }
});
