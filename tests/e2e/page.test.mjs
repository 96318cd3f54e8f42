// Browser tests of the page (Debian Chromium, headless, WebGL through SwiftShader), driven with
// real mouse and keyboard events against the production build in web/dist.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { currentFrame, finish, ipcBlocks, openApp, screenshots, typeIntoEditor, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

const open = (query = '') => openApp(ctx.browser, ctx.server, query);

/** Opens the PDDL tab and types IPC blocks 4-0 into its domain and problem editors. */
async function blocksInEditor(page) {
  const [d, p] = await Promise.all([ipcBlocks('domain.pddl'), ipcBlocks('probBLOCKS-4-0.pddl')]);
  await typeIntoEditor(page, d, p);
}

describe('page', () => {
  test('loads the wasm in a worker with no console errors; every control is labelled', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    assert.match(await page.textContent('#version'), /^v\d+\.\d+\.\d+/);
    // Every control has an accessible name.
    const unnamed = await page.evaluate(() =>
      [...document.querySelectorAll('button, select, input')]
        .filter((e) => !(e instanceof HTMLElement && e.hidden) && !(e.getAttribute('aria-label') || e.textContent?.trim() || e.closest('label')))
        .map((e) => e.outerHTML),
    );
    assert.deepEqual(unnamed, []);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('an error in the PDDL editor is shown at its line:col', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await blocksInEditor(page);
    // Type an unknown section at the end of line 6 of the domain, (:requirements :strips).
    const line6 = page.locator('#panel-pddl .cm-host:not([hidden]) .cm-line').nth(5);
    await line6.click();
    await page.keyboard.press('End');
    await page.keyboard.type(' (:bogus x)');
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-errors li', { timeout: 10000 });
    const msg = await page.textContent('#pddl-errors li');
    assert.match(msg, /domain\.pddl:6:\d+/);
    assert.match(msg, /bogus/);
    // The editor marks the error inline too.
    await page.waitForSelector('#panel-pddl .cm-lintRange-error, #panel-pddl .cm-lint-marker-error', { timeout: 5000 });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('the PDDL editor plans and steps through the states after each action', async () => {
    const { page, errors } = await open('?benchmark=b1&autoplay=0');
    await blocksInEditor(page);
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-plan-list button.step[data-index="1"]', { timeout: 20000 });
    // IPC blocks 4-0 has an optimal plan of 6 actions: initial state + 6 steps.
    assert.equal(await page.locator('#pddl-plan-list button.step').count(), 7);
    await page.click('#pddl-plan-list button.step[data-index="1"]');
    assert.match(await page.textContent('#pddl-state .state-title'), /After step 1/);
    await page.click('button[aria-label="Next state"]');
    assert.match(await page.textContent('#pddl-state .state-title'), /After step 2/);
    assert.ok((await page.locator('#pddl-state li.added').count()) >= 1);
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
    await page.locator('.stage canvas').focus();
    await page.keyboard.press('?');
    await page.waitForSelector('#help-overlay:not([hidden])');
    await page.keyboard.press('Escape');
    await page.waitForSelector('#help-overlay', { state: 'hidden' });
    await page.close();
  });

});
