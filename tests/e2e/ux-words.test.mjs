// Browser tests of the words that keep two things apart: the disturbance buttons are named by what
// they do (the paper's L1–L4 stay in their tooltips and in help), while the demonstration's states
// keep the paper's L_k, written with a subscript wherever the page shows one.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { openApp, useBrowser } from './harness.mjs';

const ctx = useBrowser();

describe('disturbances and demonstration states have different names', () => {
  test('buttons, notices and timeline markers name a disturbance by what it does; L_k has a subscript', async () => {
    // Paused after the first plan: the scrambled state is the same in every run.
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=8&autoplay=0');
    await page.click('#step');
    await page.waitForFunction(() => window.lfd.frame()?.replans === 1, null, { timeout: 30000 });
    // The block count's first item says what it is.
    assert.equal(await page.$eval('#blocks', (s) => s.selectedOptions[0].textContent), 'paper task');
    assert.match(await page.getAttribute('#blocks', 'aria-label'), /Blocks/);
    // The words fit: the top bar stays one row at 1440 px.
    const bar = await page.$eval('.topbar', (e) => e.getBoundingClientRect().height);
    assert.ok(bar < 50, `the top bar is ${bar} px tall`);
    const buttons = await page.$$eval('[data-level]', (bs) => bs.map((b) => ({ text: b.textContent.trim(), title: b.title })));
    assert.equal(buttons.length, 4);
    for (const [i, b] of buttons.entries()) {
      assert.doesNotMatch(b.text, /\bL\d/, `button ${i + 1} reads "${b.text}"`);
      assert.match(b.title, new RegExp(`the paper’s L${i + 1}\\b`), `button ${i + 1}'s tooltip: ${b.title}`);
    }
    await page.click('#inject-l3');
    const notice = await page.waitForSelector('#notice:not([hidden])', { timeout: 10000 });
    const said = await notice.textContent();
    assert.doesNotMatch(said, /\bL\d|refused/, `the notice reads "${said}"`);
    assert.ok(said.startsWith(buttons[2].text), `the notice names the button: "${said}"`);
    await page.waitForFunction(() => (window.lfd.frame()?.replans ?? 0) >= 2, null, { timeout: 30000 });
    // Playing, Play reads Pause: still one row.
    if ((await page.textContent('#play')).includes('Pause')) {
      const playing = await page.$eval('.topbar', (e) => e.getBoundingClientRect().height);
      assert.ok(playing < 50, `the top bar is ${playing} px tall while playing`);
    }
    // The replan line says which demonstration state it joined, as L with a subscript.
    await page.waitForSelector('#replan-info .replan.last', { timeout: 10000 });
    const joined = await page.$eval('#replan-info .replan.last', (r) => r.innerHTML);
    assert.match(joined, /joined (<span[^>]*>)?L<sub>\d+<\/sub>/, joined);
    // The demonstration's states in the Run tab.
    const states = await page.$$eval('#demo .demo-state', (ls) => ls.map((l) => l.innerHTML));
    assert.ok(states.length > 0 && states.every((s) => /^(<span[^>]*>)?L<sub>\d+<\/sub>/.test(s)), states[0]);
    // The timeline's marker of the disturbance.
    const marks = await page.$$eval('.tl-marks [title]', (ms) => ms.map((m) => m.getAttribute('title')));
    const mark = marks.find((m) => m.startsWith(buttons[2].text));
    assert.ok(mark, `no marker named ${buttons[2].text}: ${marks.join(' | ')}`);
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('the first visit', () => {
  test('an episode that ends while the hint is up offers to watch it again', async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=8');
    await page.waitForSelector('#first-hint:not([hidden])', { timeout: 30000 });
    await page.waitForFunction(() => window.lfd.frame()?.status.kind === 'done', null, { timeout: 60000 });
    const again = await page.waitForSelector('#hint-again', { timeout: 10000 });
    assert.match(await page.textContent('#first-hint'), /Watch again and drag a block while the robot works/);
    await again.click();
    await page.waitForFunction(() => window.lfd.frame()?.status.kind !== 'done', null, { timeout: 30000 });
    assert.ok((await page.evaluate(() => window.lfd.frame().t)) < 5, 'the episode started over');
    assert.equal(await page.$('#hint-again'), null);
    assert.deepEqual(errors, []);
    await page.close();
  });
});

describe('while Teach records', () => {
  test("the Run's Play, Step, Reset, speed and disturbance buttons wait", async () => {
    const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&autoplay=0');
    const runControls = () => page.$$eval('#play, #step, #reset, #speed, [data-level]', (es) => es.map((e) => `${e.id}:${e.disabled}`));
    assert.ok((await runControls()).every((s) => s.endsWith(':false')), (await runControls()).join(' '));
    await page.click('#tab-teach');
    await page.click('#teach-record');
    await page.waitForFunction(() => window.lfdTeach.state() !== null);
    const recording = await runControls();
    assert.equal(recording.length, 8);
    assert.ok(recording.every((s) => s.endsWith(':true')), recording.join(' '));
    await page.click('#tab-run');
    assert.ok((await runControls()).every((s) => s.endsWith(':false')), (await runControls()).join(' '));
    assert.deepEqual(errors, []);
    await page.close();
  });
});
