// Browser test of the PDDL tab as a workspace on B1: bracket errors near the edit, "did you mean"
// for unknown names, diagnostics that follow the typing, the (:init …) notice in Logic-LfD mode,
// the wide editor mode and permalinks that carry the edited texts. Real mouse and keyboard events.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { openApp, openPage, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });
const visible = '#panel-pddl .cm-host:not([hidden]) .cm-content';

/** Opens B1's PDDL tab (optionally in Logic-LfD mode) with the problem editor shown. */
async function openPddl(viewport = undefined, lfd = false) {
  const r = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0', viewport);
  await r.page.click('#tab-pddl');
  await r.page.waitForFunction((sel) => document.querySelector(sel)?.textContent.includes('define'), visible);
  if (lfd) {
    await r.page.click('#pddl-mode-lfd');
    await r.page.waitForSelector('#lfd-demo button.lfd-lk', { timeout: 30000 });
  }
  await r.page.click('#pddl-tab-problem');
  return r;
}

/** The visible editor's text. */
const editorText = (page) => page.evaluate((sel) => [...document.querySelectorAll(`${sel} .cm-line`)].map((l) => l.textContent).join('\n'), visible);

/** Replaces the visible editor's text by `text` (one input event, as a paste). */
async function replaceText(page, text) {
  await page.click(visible);
  await page.keyboard.press('ControlOrMeta+A');
  await page.keyboard.insertText(text);
}

/** The text of the diagnostics list once it holds an item matching `re`. */
async function diagnostic(page, re) {
  await page.waitForFunction((src) => new RegExp(src).test(document.getElementById('pddl-errors')?.textContent ?? ''), re.source, { timeout: 15000 });
  return page.textContent('#pddl-errors');
}

describe('PDDL tab as a workspace', () => {
  test('a deleted `)` on line 8 is reported near line 8; an unknown name gets a suggestion', async () => {
    const { page, errors } = await openPddl();
    const original = await editorText(page);
    const lines = original.split('\n');
    assert.match(lines[7], /\(ontable d\)\s*$/);
    lines[7] = lines[7].replace(/\)\s*$/, '');
    await replaceText(page, lines.join('\n'));
    const text = await diagnostic(page, /not closed|unclosed/);
    assert.doesNotMatch(text, /:2:1/, text);
    const line = Number(/problem[^:]*:(\d+):\d+/.exec(text)?.[1]);
    assert.ok(Math.abs(line - 8) <= 1, text);
    assert.match(text, /probably ends before line 9/);

    await replaceText(page, original.replace('(clear a)', '(clera a)'));
    assert.match(await diagnostic(page, /did you mean/), /undeclared predicate `clera`; did you mean `clear`\?/);
    // The inline mark carries the same message.
    await page.waitForSelector('#panel-pddl .cm-host:not([hidden]) .cm-lintRange-error');
    assert.deepEqual(errors, []);
  });

  test('a fixed text clears the old error at once, without Run', async () => {
    const { page } = await openPddl(undefined, true);
    const original = await editorText(page);
    await replaceText(page, original.replace('(clear a)', '(clera a)'));
    await diagnostic(page, /did you mean/);
    // Run shows the failure in the results too.
    await page.click('#pddl-plan');
    await page.waitForSelector('#lfd-results .lfd-fail', { timeout: 30000 });
    await replaceText(page, original);
    // Cleared well before the check after typing (600 ms) could have answered.
    await page.waitForFunction(() => !document.querySelector('#pddl-errors li') && !document.querySelector('#lfd-results .lfd-fail'), null, { timeout: 300 });
    await page.waitForTimeout(1500);
    assert.equal(await page.locator('#pddl-errors li').count(), 0);
    assert.equal(await page.locator('#panel-pddl .cm-lintRange-error').count(), 0);
  });

  test('an (:init …) edit in Logic-LfD mode says S_C is the place, and moves it there', async () => {
    const { page } = await openPddl(undefined, true);
    const original = await editorText(page);
    assert.equal(await page.isVisible('#pddl-init-notice'), false);
    await replaceText(page, original.replace('(ontable a)', '(on a b)').replace('(clear b)', ''));
    await page.waitForSelector('#pddl-init-notice:not([hidden])', { timeout: 5000 });
    assert.match(await page.textContent('#pddl-init-notice'), /belongs in the S_C editor/);
    await page.click('text=Use this state as S_C');
    assert.equal(await page.isVisible('#pddl-init-notice'), false);
    const problem = await editorText(page);
    assert.match(problem, /\(ontable a\)/);
    assert.match(problem, /\(clear b\)/);
    const sc = await page.evaluate(() => [...document.querySelectorAll('#lfd-state .cm-line')].map((l) => l.textContent).join('\n'));
    assert.match(sc, /\(on a b\)/);
    assert.doesNotMatch(sc, /\(clear b\)/);
    // S_C no longer holds L_0 (a is on b): LogicIn says so once the check answers.
    await page.waitForFunction(() => /SC/.test(document.getElementById('lfd-verdict')?.textContent ?? '') && !/L0 ⊆/.test(document.getElementById('lfd-verdict')?.textContent ?? ''), null, { timeout: 15000 });
  });

  test('wide mode shows at least 35 lines at 1440×900; screenshots at three sizes', async () => {
    const { page } = await openPddl({ width: 1440, height: 900 });
    await page.keyboard.press('Alt+w');
    await page.waitForSelector('#pddl-wide[aria-pressed="true"]');
    assert.equal(await page.isVisible('.stage'), false);
    await page.waitForTimeout(200);
    const shown = await page.evaluate(() => {
      const host = document.querySelector('#panel-pddl .cm-host:not([hidden])');
      const line = host.querySelector('.cm-line').getBoundingClientRect().height;
      return host.querySelector('.cm-scroller').clientHeight / line;
    });
    assert.ok(shown >= 35, `${shown.toFixed(1)} lines`);
    await page.screenshot({ path: join(screenshots, 'pddl-1440.png') });
    await page.click('#pddl-wide');
    assert.equal(await page.isVisible('.stage'), true);
    await page.close();
    const narrow = await openPddl({ width: 1024, height: 768 });
    await narrow.page.screenshot({ path: join(screenshots, 'pddl-1024.png') });
    await narrow.page.close();
    const phone = await ctx.browser.newPage({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
    await phone.goto(`${ctx.server.url}?benchmark=b1&autoplay=0`);
    await phone.waitForSelector('#app[data-ready="true"]', { timeout: 30000 });
    await phone.tap('#tab-pddl');
    await phone.waitForFunction((sel) => document.querySelector(sel)?.textContent.includes('define'), visible);
    await phone.locator('#pddl-copy-link').scrollIntoViewIfNeeded();
    await phone.screenshot({ path: join(screenshots, 'pddl-phone.png') });
  });

  test('a permalink carries an edited problem into a fresh page', async () => {
    const { page } = await openPddl();
    const edited = (await editorText(page)).replace('(:goal (and (on a b)', '(:goal (and (on d c) (on a b)');
    assert.match(edited, /on d c/);
    await replaceText(page, edited);
    await page.click('#pddl-copy-link');
    await page.waitForFunction(() => location.hash.startsWith('#pddl='));
    const url = page.url();
    await page.close();
    const fresh = await openPage(ctx.browser, url);
    await fresh.page.waitForFunction((sel) => document.querySelector(sel)?.textContent.includes('define'), visible, { timeout: 30000 });
    await fresh.page.click('#pddl-tab-problem');
    assert.equal(await editorText(fresh.page), edited);
    assert.deepEqual(fresh.errors, []);
  });
});
