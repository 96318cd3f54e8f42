// Security of the page: no eval / innerHTML with user text in the page's
// source; hostile names in a permalink, a loaded scene JSON or the PDDL editor never run script
// and are displayed as text. A payload "ran" if it set window.__pwned, opened a dialog, or added an
// element (img, svg, script, iframe) to the document.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile, readdir } from 'node:fs/promises';
import { join } from 'node:path';
import { openApp, root, useBrowser } from './harness.mjs';

const ctx = useBrowser();

/** Classic injection payloads; each one that ran would set window.__pwned or open a dialog. */
const PAYLOADS = [
  '<img src=x onerror="window.__pwned=1">',
  '"><script>window.__pwned=2</script>',
  '<svg/onload=window.__pwned=3>',
  '<iframe srcdoc="<script>parent.__pwned=4</script>"></iframe>',
  "'><img src=x onerror=alert(5)>",
  'javascript:window.__pwned=6',
  '{{constructor.constructor("window.__pwned=7")()}}',
];

/** Opens the app and records dialogs; `check()` asserts nothing ran. */
async function openGuarded(query) {
  const { page, errors } = await openApp(ctx.browser, ctx.server, query);
  const dialogs = [];
  page.on('dialog', (d) => {
    dialogs.push(d.message());
    void d.dismiss();
  });
  const baseline = await page.evaluate(() => document.querySelectorAll('img, svg, script, iframe, object, embed').length);
  const check = async (what) => {
    const s = await page.evaluate(() => ({
      pwned: /** @type {any} */ (window).__pwned,
      injected: document.querySelectorAll('img, svg, script, iframe, object, embed').length,
    }));
    assert.equal(s.pwned, undefined, `${what}: a payload ran`);
    assert.deepEqual(dialogs, [], `${what}: a dialog opened`);
    assert.equal(s.injected, baseline, `${what}: markup was injected into the document`);
  };
  return { page, errors, check };
}

describe('security', () => {
  test('the page source has no eval, Function, innerHTML, outerHTML, insertAdjacentHTML or document.write', async () => {
    const dir = join(root, 'web', 'src');
    const bad = /\b(eval\s*\(|new\s+Function\s*\(|innerHTML|outerHTML|insertAdjacentHTML|document\.write|srcdoc)/;
    const hits = [];
    for (const f of await readdir(dir)) {
      if (!/\.(ts|js)$/.test(f)) continue;
      (await readFile(join(dir, f), 'utf8')).split('\n').forEach((line, i) => {
        if (bad.test(line)) hits.push(`web/src/${f}:${i + 1}: ${line.trim()}`);
      });
    }
    assert.deepEqual(hits, []);
    // And a Content-Security-Policy forbids inline script and eval, should markup ever get in.
    const html = await readFile(join(root, 'web', 'index.html'), 'utf8');
    const csp = /http-equiv="Content-Security-Policy"\s+content="([^"]+)"/.exec(html)?.[1] ?? '';
    assert.match(csp, /script-src 'self'/);
    const scriptSrc = /script-src([^;]*)/.exec(csp)?.[1] ?? '';
    assert.doesNotMatch(scriptSrc, /'unsafe-(inline|eval)'|\*|data:/, `script-src${scriptSrc}`);
  });

  test('a permalink with hostile parameters falls back to the defaults and runs nothing', async () => {
    for (const p of PAYLOADS) {
      const q = new URLSearchParams({ benchmark: p, method: p, mode: p, seed: p, speed: p, quality: p, autoplay: '0' });
      const { page, errors, check } = await openGuarded(`?${q}`);
      await check(`permalink ${p}`);
      const sel = await page.evaluate(() => ['benchmark', 'method', 'mode', 'seed'].map((id) => /** @type {HTMLInputElement} */ (document.getElementById(id)).value));
      assert.deepEqual(sel, ['b1', 'logic-lfd', 'paper', '0'], `permalink ${p}`);
      const f = await page.evaluate(() => window.lfd.frame());
      assert.ok(f && f.world.name.startsWith('b1'), 'the default benchmark did not load');
      // The URL the page writes back (the Link button) holds only the sanitised values.
      assert.doesNotMatch(await page.evaluate(() => location.search), /pwned|script|onerror/);
      assert.deepEqual(errors, []);
      await page.close();
    }
  });

  test('a scene JSON with hostile names is refused with the name shown as text; nothing runs', async () => {
    const { page, errors, check } = await openGuarded('?benchmark=b1&autoplay=0');
    const scene = JSON.parse(await page.evaluate(() => JSON.stringify(window.lfd.frame().world)));
    const load = async (s, what) => {
      await page.evaluate(() => {
        document.getElementById('status-text').textContent = 'Loading (test)';
        document.getElementById('notice').hidden = true;
      });
      await page.setInputFiles('input[type=file]', { name: 'scene.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(s)) });
      // Wait for the page to settle on the outcome of this load (a refusal is a notice).
      await page.waitForFunction(() => !/Loading/.test(document.getElementById('status-text').textContent) || !document.getElementById('notice').hidden, null, { timeout: 20000 });
      await check(what);
    };
    const shown = [];
    for (const p of PAYLOADS) {
      // A block renamed to the payload.
      const s = structuredClone(scene);
      s.bodies.find((b) => b.kind === 'block').name = p;
      await load(s, `block named ${p}`);
      const status = await page.evaluate(() => {
        const e = document.getElementById('notice');
        return { text: e.textContent, children: e.children.length };
      });
      // The core quotes the name as a Rust string literal (`"` becomes `\"`).
      const quoted = JSON.stringify(p).slice(1, -1);
      assert.ok(status.text.includes(p) || status.text.includes(quoted), `the refusal does not show the name as text: ${status.text}`);
      assert.equal(status.children, 0);
      shown.push(status.text);
      // A region and the world's own name.
      const r = structuredClone(scene);
      r.name = p;
      r.regions = [{ name: p, min: [0, 0], max: [0.1, 0.1], color: '#ff0000' }];
      await load(r, `region named ${p}`);
    }
    // An accepted scene with a hostile world name: the session runs.
    const w = structuredClone(scene);
    w.name = `b1-${PAYLOADS[1]}`;
    await load(w, 'world name');
    await page.click('#step');
    await check('world name, stepped');
    assert.deepEqual(errors, []);
    console.log(`refusal shown as text, e.g.: ${shown[0]}`);
    await page.close();
  });

  test('hostile names in the PDDL editor are shown as text in its diagnostics', async () => {
    const { page, errors, check } = await openGuarded('?benchmark=b1&autoplay=0');
    const domain = await readFile(new URL('../data/ipc/blocks/domain.pddl', import.meta.url), 'utf8');
    for (const p of PAYLOADS.filter((x) => !/[\s()]/.test(x)).concat(['<img/src/onerror=window.__pwned=8>'])) {
      const problem = `(define (problem x) (:domain BLOCKS)\n (:objects ${p} b)\n (:init (handempty) (ontable b) (clear b))\n (:goal (clear b)))\n`;
      await page.evaluate(([d, q]) => window.lfd.setPddl(d, q), [domain, problem]);
      await page.click('#pddl-plan');
      await page.waitForFunction(
        (name) => [...document.querySelectorAll('#pddl-errors li, #pddl-plan-list li')].some((li) => li.textContent.includes(name)),
        p,
        { timeout: 20000 },
      );
      await check(`PDDL object ${p}`);
    }
    assert.deepEqual(errors, []);
    await page.close();
  });
});
