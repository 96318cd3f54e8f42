// Browser test of the PDDL tab's Logic-LfD view on B1: the demonstration states, editing the
// current state S_C (toggle a fact, apply an action), a run of both modes with the merged plan,
// and a located error in the demonstration editor. Real mouse and keyboard events only.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { join } from 'node:path';
import { openApp, screenshots, useBrowser } from './harness.mjs';

const ctx = useBrowser({ withScreenshots: true });

const ipc = (f) => readFile(new URL(`../data/ipc/blocks/${f}`, import.meta.url), 'utf8');

/** IPC blocks with `n` blocks in one tower, goal the reversed tower, and a demonstration that
 * unstacks everything and builds the goal: planning from scratch with blind BFS cannot finish. */
function bigBlocks(n) {
  const b = Array.from({ length: n }, (_, i) => `b${i}`);
  const init = ['(handempty)', `(ontable ${b[0]})`, `(clear ${b[n - 1]})`, ...b.slice(1).map((x, i) => `(on ${x} ${b[i]})`)];
  const goal = b.slice(0, -1).map((x, i) => `(on ${x} ${b[i + 1]})`);
  const problem = `(define (problem big-${n}) (:domain BLOCKS)\n (:objects ${b.join(' ')})\n (:init ${init.join(' ')})\n (:goal (and ${goal.join(' ')})))\n`;
  const demo = [];
  for (let i = n - 1; i > 0; i--) demo.push(`(unstack ${b[i]} ${b[i - 1]})`, `(put-down ${b[i]})`);
  for (let i = n - 2; i >= 0; i--) demo.push(`(pick-up ${b[i]})`, `(stack ${b[i]} ${b[i + 1]})`);
  return { problem, demo: demo.join('\n') + '\n' };
}

/** Opens B1's PDDL tab in Logic-LfD mode and waits for the demonstration states. */
async function openLfd(viewport = undefined) {
  const r = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0', viewport);
  const { page } = r;
  await page.click('#tab-pddl');
  await page.waitForFunction(() => document.querySelector('#panel-pddl .cm-content')?.textContent.includes('define'));
  await page.click('#pddl-mode-lfd');
  await page.waitForSelector('#lfd-demo button.lfd-lk', { timeout: 30000 });
  return r;
}

const verdict = (page) => page.textContent('#lfd-verdict');

/** Waits until the verdict on S_C matches `re`. */
async function verdictMatches(page, re) {
  await page.waitForFunction((src) => new RegExp(src).test(document.getElementById('lfd-verdict')?.textContent ?? ''), re.source, { timeout: 15000 });
}

/** The checkbox of fact `f` in the fact list. */
const factBox = (page, f) => page.locator(`#lfd-facts input[data-fact="${f}"]`);

describe('PDDL tab: Logic-LfD', () => {
  test('demonstration states, S_C edits, both modes side by side, a demo error at its line', async () => {
    const { page, errors } = await openLfd();
    // The demo tab holds B1's demonstration, one action a line.
    await page.click('#pddl-tab-demo');
    const demoText = await page.textContent('#panel-pddl .cm-host:not([hidden]) .cm-content');
    assert.match(demoText, /\(pick panda c\)/);
    // B1's demonstration has 6 actions: L_0 … L_6.
    assert.equal(await page.locator('#lfd-demo button.lfd-lk').count(), 7);
    assert.equal(await page.locator('#lfd-demo li.demo-action').count(), 6);
    // S_C starts at the problem's initial state: L_0 holds and LogicIn follows the demo from a_1.
    await verdictMatches(page, /L0 ⊆ SC.*LogicIn = 0/);
    assert.equal(await page.getAttribute('#lfd-demo button.lfd-lk[data-k="0"]', 'class').then((c) => c.includes('matched')), true);
    // Clicking L_2 shows its facts.
    await page.click('#lfd-demo button.lfd-lk[data-k="2"]');
    await page.waitForSelector('#lfd-lk-facts:not([hidden]) .facts li');
    assert.match(await page.textContent('#lfd-lk-facts'), /\(on c d\)/);
    await page.screenshot({ path: join(screenshots, 'pddl-lfd-state.png') });

    // Toggle a fact off: (clear d) leaves S_C, so L_0 no longer holds; toggling it back restores it.
    await factBox(page, '(clear d)').click();
    await verdictMatches(page, /No demonstration state holds/);
    assert.equal(await factBox(page, '(clear d)').isChecked(), false);
    assert.doesNotMatch(await page.textContent('#lfd-state .cm-content'), /\(clear d\)/);
    await factBox(page, '(clear d)').click();
    await verdictMatches(page, /L0 ⊆ SC/);

    // Apply an action the demonstration does not start with: no L_k ⊆ S_C any more.
    await page.selectOption('#lfd-apply', '(pick panda a)');
    await page.click('#lfd-apply-btn');
    await verdictMatches(page, /No demonstration state holds/);
    assert.equal(await factBox(page, '(holding panda a)').isChecked(), true);

    // Run: both modes, each a prefix marked "new" joined to the demonstration suffix at L_k.
    await page.click('#pddl-plan');
    await page.waitForSelector('#lfd-col-prioritised .lfd-sum', { timeout: 60000 });
    for (const mode of ['paper', 'prioritised']) {
      const col = page.locator(`#lfd-col-${mode}`);
      const k = await col.locator('.lfd-sum').getAttribute('data-k');
      assert.match(k, /^\d$/, `${mode}: a demonstration state joined`);
      assert.match(await col.locator('.lfd-sum').textContent(), new RegExp(`k = ${k}`));
      assert.ok((await col.locator('li.new').count()) >= 1, `${mode}: a new prefix`);
      const demoLines = await col.locator('li.demo').count();
      assert.equal(demoLines, 6 - Number(k), `${mode}: the demonstration after L_${k}`);
      if (demoLines > 0) assert.match(await col.locator('li.demo').first().textContent(), new RegExp(`demo a${Number(k) + 1}`));
    }
    assert.match(await page.textContent('#lfd-compare'), /shorter|Same length/);
    assert.match(await page.textContent('#lfd-scratch'), /From scratch.*cost \d+/);
    await page.locator('#lfd-results').scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(screenshots, 'pddl-lfd.png') });

    // A typo in the demonstration's third action: an error at demo.plan:3, inline in the demo editor.
    await page.click('#pddl-tab-demo');
    const line3 = page.locator('#panel-pddl .cm-host:not([hidden]) .cm-line').nth(2);
    await line3.click();
    await page.keyboard.press('End');
    await page.keyboard.press('ArrowLeft');
    await page.keyboard.type('zz');
    await page.waitForSelector('#pddl-errors li[data-source="demo"]', { timeout: 15000 });
    assert.match(await page.textContent('#pddl-errors li[data-source="demo"]'), /demo\.plan:3:\d+/);
    await page.waitForSelector('#panel-pddl .cm-host:not([hidden]) .cm-lint-marker-error', { timeout: 5000 });
    // The edited demonstration is still there after another run.
    await page.click('#pddl-plan');
    await page.waitForSelector('#lfd-results .lfd-fail', { timeout: 15000 });
    assert.match(await page.textContent('#panel-pddl .cm-host:not([hidden]) .cm-content'), /\(pick panda bzz\)/);
    await page.screenshot({ path: join(screenshots, 'pddl-lfd-error.png') });
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('a random walk sets S_C; paper mode may join an earlier L_k than prioritised; a state error shows at its line', async () => {
    const { page, errors } = await openLfd();
    // Seed 9, at most 6 steps: a state from which the first demonstration state reached is not the best.
    await page.fill('#lfd-seed', '9');
    await page.fill('#lfd-steps', '6');
    await page.click('#lfd-walk');
    await page.waitForFunction(() => /Random walk from L0, seed 9/.test(document.getElementById('lfd-state-note')?.textContent ?? ''));
    await verdictMatches(page, /No demonstration state holds/);
    await page.click('#pddl-plan');
    await page.waitForSelector('#lfd-col-prioritised .lfd-sum', { timeout: 60000 });
    const paperK = Number(await page.getAttribute('#lfd-col-paper .lfd-sum', 'data-k'));
    const prioK = Number(await page.getAttribute('#lfd-col-prioritised .lfd-sum', 'data-k'));
    assert.ok(prioK > paperK, `prioritised joins L_${prioK}, paper L_${paperK}`);
    assert.match(await page.textContent('#lfd-compare'), /prioritised is shorter/);
    await page.locator('#lfd-results').scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(screenshots, 'pddl-lfd-modes.png') });
    // An atom with an unknown object on the state's first line.
    await page.locator('#lfd-state .cm-line').first().click();
    await page.keyboard.press('Home');
    await page.keyboard.type('(clear zz) ');
    await page.waitForSelector('#pddl-errors li[data-source="state"]', { timeout: 15000 });
    assert.match(await page.textContent('#pddl-errors li[data-source="state"]'), /state:1:\d+/);
    await page.waitForSelector('#lfd-state .cm-lint-marker-error', { timeout: 5000 });
    assert.match(await verdict(page), /SC does not read/);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('screenshot on a phone', async () => {
    const { page, errors } = await openLfd({ width: 390, height: 844 });
    await page.selectOption('#lfd-apply', '(pick panda a)');
    await page.click('#lfd-apply-btn');
    await verdictMatches(page, /No demonstration state holds/);
    await page.click('#pddl-plan');
    await page.waitForSelector('#lfd-col-prioritised .lfd-sum', { timeout: 60000 });
    await page.locator('#lfd-view').scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(screenshots, 'pddl-lfd-phone.png') });
    await page.locator('#lfd-results').scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(screenshots, 'pddl-lfd-phone-results.png') });
    // Nothing wider than the screen.
    const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
    assert.ok(overflow <= 0, `the page is ${overflow} px wider than the screen`);
    assert.deepEqual(errors, []);
    await page.close();
  });

  test('Cancel stops a Logic-LfD run at once; the view works again after it', async () => {
    const { page, errors } = await openLfd();
    const { problem, demo } = bigBlocks(40);
    await page.evaluate(([d, p, x]) => window.lfd.setPddl(d, p, x), [await ipc('domain.pddl'), problem, demo]);
    await page.waitForSelector('#lfd-demo button.lfd-lk[data-k="156"]', { timeout: 30000 });
    await page.selectOption('#pddl-search', 'bfs');
    await page.selectOption('#pddl-heuristic', 'blind');
    // L_0 holds: no multi-goal search, but planning from scratch beside it (blind BFS) runs long.
    await page.click('#pddl-plan');
    await page.waitForSelector('#pddl-cancel:not([hidden])');
    await page.waitForSelector('#lfd-col-paper');
    await page.click('#pddl-cancel');
    await page.waitForSelector('#lfd-stopped', { timeout: 2000 });
    assert.match(await page.textContent('#lfd-stopped'), /cancelled/i);
    assert.ok(await page.isHidden('#pddl-cancel'));
    // A fresh worker reads S_C again after an edit (the filter finds the fact among 1600 and more).
    await page.click('#lfd-filter');
    await page.keyboard.type('handempty');
    assert.equal(await page.locator('#lfd-facts li').count(), 1);
    await factBox(page, '(handempty)').click();
    await verdictMatches(page, /No demonstration state holds/);
    assert.deepEqual(errors, []);
    await page.close();
  });
});
