// Cancel and responsiveness, asserted on what happens (timings are measured by tests/e2e/bench.mjs):
// Cancel drops the robot's running plan, the loop replans and the ticks go on to the goal; a
// pathological PDDL problem typed into the editor searches in a worker of its own while the page
// handles a click and the robot keeps ticking, and Cancel terminates that worker.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { bigBlocks, currentFrame, ipcBlocks, openApp, typeIntoEditor, useBrowser } from './harness.mjs';

const ctx = useBrowser();

describe('cancel', () => {
  test('Cancel drops the running plan; the loop replans and the ticks go on', async () => {
    // Half speed: the episode outlasts five cancels on a loaded machine.
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=2&speed=0.5');
    for (let round = 0; round < 5; round++) {
      // Wait until an action is running (the arm is moving along its skill).
      await page.waitForFunction(() => window.lfd.frame()?.executing != null && window.lfd.frame().status.kind === 'executing', null, {
        timeout: 60000,
        polling: 10,
      });
      await page.waitForSelector('#cancel:not([disabled])', { timeout: 60000 });
      const before = await page.evaluate(() => ({
        replans: window.lfd.frame().replans,
        cancel: window.lfd.lastCancel(),
      }));
      await page.click('#cancel');
      await page.waitForFunction((prev) => window.lfd.lastCancel() !== null && window.lfd.lastCancel().clickedAt !== prev?.clickedAt, before.cancel, {
        polling: 10,
      });
      const c = await page.evaluate(() => window.lfd.lastCancel());
      // The worker dropped the plan; the loop then replans "because no plan (cancelled)".
      await page.waitForFunction((n) => window.lfd.frame().replans > n, before.replans, { timeout: 10000, polling: 10 });
      const f = await currentFrame(page);
      // The worker applied the cancel (it stamps when), and the plan it dropped was replaced.
      assert.equal(typeof c.appliedAt, 'number', JSON.stringify(c));
      assert.match(f.lastReplan.reason, /cancel/, JSON.stringify(f.lastReplan));
      // The simulation keeps ticking after the cancel.
      const tick = f.tick;
      await page.waitForFunction((t) => window.lfd.frame().tick > t, tick, { timeout: 10000, polling: 10 });
    }
    // The robot goes on with its new plan and finishes the task.
    await page.selectOption('#speed', '8');
    const end = await page.waitForFunction(() => /done|failed/.test(window.lfd.frame().status.kind) && window.lfd.frame(), null, {
      timeout: 120000,
      polling: 100,
    });
    const last = await end.jsonValue();
    assert.equal(last.status.kind, 'done', last.status.message);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a pathological PDDL problem does not freeze the page; Cancel stops its search', async () => {
    // Quarter speed: the robot is still working while the editor types and searches.
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=0.25');
    const domain = await ipcBlocks('domain.pddl');
    await typeIntoEditor(page, domain, bigBlocks(60));
    await page.selectOption('#pddl-search', 'bfs');
    await page.selectOption('#pddl-heuristic', 'blind');
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-cancel:not([hidden])');
    // Keep typing into the problem while it searches (the lint check must not block either).
    await page.locator('#panel-pddl .cm-host:not([hidden]) .cm-line').last().click();
    await page.keyboard.type(' ; still typing');
    // While the search runs (its time limit is 20 s): the robot ticks on and a real click on a page
    // button is handled.
    const tick0 = (await currentFrame(page)).tick;
    await page.waitForFunction((t) => window.lfd.frame().tick > t, tick0, { timeout: 10000, polling: 10 });
    await page.click('#help');
    await page.waitForSelector('#help-overlay:not([hidden])', { timeout: 10000 });
    await page.click('#help-close');
    assert.ok(await page.isVisible('#pddl-cancel'), 'the search ended by itself: the problem is not hard enough for this test');
    // Cancel: the search worker is terminated and the editor says so.
    await page.click('#pddl-cancel');
    await page.waitForSelector('#pddl-stopped', { timeout: 10000 });
    assert.match(await page.textContent('#pddl-stopped'), /cancelled/i);
    assert.ok(await page.isHidden('#pddl-cancel'));
    // A fresh search worker plans the next problem.
    await typeIntoEditor(page, domain, await ipcBlocks('probBLOCKS-4-0.pddl'));
    await page.selectOption('#pddl-search', 'astar');
    await page.selectOption('#pddl-heuristic', 'lmcut');
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-plan-list button.step[data-index="1"]', { timeout: 20000 });
    assert.equal(await page.locator('#pddl-plan-list button.step').count(), 7);
    const f = await currentFrame(page);
    assert.notEqual(f.status.kind, 'failed', f.status.message);
    assert.deepEqual(errors, []);
    await page.close();
  });
});
