// Page soak: SOAK_CYCLES (default 1000) perturb-and-replan cycles through the
// page's own UI — the L1–L4 buttons and real mouse drags of blocks — while the robot runs at 2×,
// switching benchmark every 25 cycles and resetting whenever an episode ends, with the Charts tab
// open for 10 cycles in 50 (uPlot drawing) and the Run panels the rest of the time. Memory is
// measured after SOAK_WARMUP (default 100) cycles, so first-use allocations (wasm heap, shader
// programs, the benchmarks' meshes, uPlot) are not counted as growth, and again at the end, both
// times in the same state (B1 just opened, paused, garbage collected): main-thread JS heap (CDP
// Runtime.getHeapUsage after HeapProfiler.collectGarbage), the worker's wasm memory, three.js
// geometries/textures alive, DOM nodes and listeners. Asserts zero console errors and uncaught
// exceptions, no geometry/texture leak, and growth ≤ 10 % (SOAK_MAX_GROWTH).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { currentFrame, openApp, useBrowser } from './harness.mjs';

// CI (CI=true, `.ci/run`) runs 200 cycles unless SOAK_CYCLES says otherwise: 1000 take 3–10 min
// on the shared 2-core machine; the README reports a 1000-cycle run.
const CYCLES = Number(process.env.SOAK_CYCLES ?? (process.env.CI ? 200 : 1000));
const WARMUP = Number(process.env.SOAK_WARMUP ?? 100);
const MAX_GROWTH = Number(process.env.SOAK_MAX_GROWTH ?? 0.1);
const BENCHMARKS = ['b1', 'b2', 'b3'];

const ctx = useBrowser();

/**
 * Waits until the page shows a notice again (the outcome of the action just taken); `null` if
 * none came within `timeout` and `optional` (a drag whose press missed the block: no drag at all).
 */
async function act(page, action, { optional = false, timeout = 15000 } = {}) {
  await page.evaluate(() => document.getElementById('notice').setAttribute('hidden', ''));
  await action();
  try {
    await page.waitForSelector('#notice:not([hidden])', { timeout });
  } catch (e) {
    if (optional) return null;
    throw e;
  }
  return page.textContent('#notice');
}

/** A real mouse drag of a free block (clear, not held) to a spot beside it on its table. */
async function drag(page, k) {
  const d = await page.evaluate((k) => {
    const f = window.lfd.frame();
    const held = new Set(f.world.arms.map((a) => a.holding).filter(Boolean));
    const blocks = f.world.bodies.filter((b) => b.kind === 'block' && !b.lost && !held.has(b.name) && f.facts.includes(`(clear ${b.name})`));
    // A block whose centre is on the canvas (not under the status bar or the HUD), with its drop
    // spot on the canvas too.
    const onCanvas = (p) => p && document.elementFromPoint(p.x, p.y)?.tagName === 'CANVAS';
    /** @type {any[]} */
    const tables = f.world.bodies.filter((t) => t.kind === 'table' && t.shape.type === 'cuboid');
    for (let j = 0; j < blocks.length; j++) {
      const b = blocks[(k + j) % blocks.length];
      const [x, y] = b.pose.position;
      const table = tables.find((t) => {
        const [tx, ty] = t.pose.position;
        const [hx, hy] = t.shape.half_extents;
        return Math.abs(x - tx) < hx && Math.abs(y - ty) < hy;
      }) ?? tables[0];
      const top = table.pose.position[2] + table.shape.half_extents[2];
      const a = (k * 2.399) % (2 * Math.PI);
      const from = window.lfd.screenPosition(b.name);
      const to = window.lfd.project([x + 0.12 * Math.cos(a), y + 0.12 * Math.sin(a), top + 0.03]);
      if (onCanvas(from) && onCanvas(to)) return { from, to };
    }
    return null;
  }, k);
  if (!d) return null;
  const text = await act(
    page,
    async () => {
    await page.mouse.move(d.from.x, d.from.y);
    await page.mouse.down();
    for (let i = 1; i <= 6; i++) await page.mouse.move(d.from.x + ((d.to.x - d.from.x) * i) / 6, d.from.y + ((d.to.y - d.from.y) * i) / 6);
    await page.mouse.up();
    },
    { optional: true, timeout: 3000 },
  );
  if (process.env.SOAK_TRACE && text == null) console.log(`drag ${k} from ${JSON.stringify(d)}: no outcome`);
  return text;
}

/** Opens `b` through the benchmark menu and waits for its first frame. */
async function openBenchmark(page, b) {
  const prev = await page.evaluate(() => ({ name: window.lfd.frame().world.name, tick: window.lfd.frame().tick }));
  if ((await page.inputValue('#benchmark')) === b) {
    await page.click('#reset');
  } else {
    await page.selectOption('#benchmark', b);
  }
  // A new episode: another scene, or the same one with its clock restarted.
  await page.waitForFunction(
    ([b, prev]) => {
      const f = window.lfd.frame();
      return f.world.name.startsWith(b) && (f.world.name !== prev.name || f.tick < prev.tick);
    },
    [b, prev],
    { timeout: 30000, polling: 10 },
  );
}

/** The same state both times: B1 just opened and paused, then a full GC. */
async function measure(page, cdp) {
  await openBenchmark(page, 'b1');
  if ((await page.getAttribute('#play', 'aria-pressed')) === 'true') await page.click('#play');
  await page.waitForSelector('#play[aria-pressed="false"]');
  await page.waitForTimeout(300);
  for (let i = 0; i < 3; i++) await cdp.send('HeapProfiler.collectGarbage');
  const heap = await cdp.send('Runtime.getHeapUsage');
  const dom = await cdp.send('Memory.getDOMCounters');
  const m = await page.evaluate(() => window.lfd.memory());
  await page.click('#play');
  return { heap: heap.usedSize, wasm: m.wasmBytes, geometries: m.geometries, textures: m.textures, nodes: dom.nodes, listeners: dom.jsEventListeners };
}

test(`page soak: ${CYCLES} perturb-and-replan cycles, memory flat after ${WARMUP} warm-up cycles`, { timeout: 3_600_000 }, async () => {
  // A smaller window than the other tests: software WebGL draws every frame on the CPU.
  const { page, errors } = await openApp(ctx.browser, ctx.server, '?benchmark=b1&seed=1&speed=2', { width: 960, height: 600 });
  // uPlot is not part of the first load; the Charts tab fetches it, and the soak draws the charts.
  const scripts = await page.evaluate(() => performance.getEntriesByType('resource').map((e) => e.name));
  assert.ok(!scripts.some((u) => /uPlot/i.test(u)), `uPlot loaded at first paint: ${scripts.join(' ')}`);
  await page.click('#tab-charts');
  await page.waitForSelector('#chart-replan .uplot, #chart-ee .uplot', { timeout: 15000 });
  await page.click('#tab-run');
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('HeapProfiler.enable');
  const stats = { missed: 0, unanswered: 0, accepted: 0, refused: 0, drags: 0, injections: 0, replans: 0, episodes: 0, done: 0, failed: 0 };
  let warm = null;
  /** Why episodes ended without success (under a disturbance every cycle, most do). */
  const reasons = new Map();
  const t0 = Date.now();
  let tMain = t0;
  let benchmark = 'b1';
  for (let i = 0; i < WARMUP + CYCLES; i++) {
    if (i === WARMUP) {
      warm = await measure(page, cdp);
      benchmark = 'b1';
      tMain = Date.now();
    }
    // The Charts tab is open for 10 cycles in every 50 (uPlot drawing; the rest shows the panels).
    if (i % 50 === 0) await page.click('#tab-charts');
    if (i % 50 === 10) {
      // Regression: at widths ≤ 1000 px the charts once widened their grid column on every resize
      // (the page grew to 3 900 px and the canvas with it).
      const w = await page.evaluate(() => ({ doc: document.documentElement.scrollWidth, inner: innerWidth }));
      assert.ok(w.doc <= w.inner, `the page is ${w.doc} px wide in a ${w.inner} px window with the charts open`);
      await page.click('#tab-run');
    }
    const want = BENCHMARKS[Math.floor(i / 25) % BENCHMARKS.length];
    if (want !== benchmark) {
      await openBenchmark(page, want);
      benchmark = want;
    }
    let f = await page.evaluate(() => window.lfd.frame());
    if (f.status.kind === 'done' || f.status.kind === 'failed') {
      stats.episodes++;
      stats[f.status.kind]++;
      if (f.status.kind === 'failed') {
        const why = f.status.message.replace(/\b[a-z]\b|\d+(\.\d+)?/g, '·').slice(0, 90);
        reasons.set(why, (reasons.get(why) ?? 0) + 1);
      }
      await openBenchmark(page, benchmark);
      f = await page.evaluate(() => window.lfd.frame());
    }
    const before = f;
    // Four of five cycles press L1–L4, the fifth drags a block with the mouse.
    let text;
    if (i % 5 === 4) {
      text = await drag(page, i);
      if (text != null) stats.drags++;
      else stats.missed++;
    }
    let a;
    if (text == null) {
      // A real click on the L-button, its notice, and the loop running on.
      const level = `l${(i % 5) + (i % 5 === 4 ? -3 : 1)}`;
      // A greyed button still answers with its reason; one that stays silent is counted.
      text = await act(page, () => page.click(`#inject-${level}`, { force: true }), { optional: true });
      if (text == null) {
        stats.unanswered++;
        text = '';
      }
      const tick = (await currentFrame(page)).tick;
      const h = await page.waitForFunction(
        (tick) => {
          const g = window.lfd.frame();
          return (g.tick >= tick + 3 || g.status.kind === 'done' || g.status.kind === 'failed') && { replans: g.replans };
        },
        tick,
        { timeout: 30000, polling: 10 },
      );
      a = { text, ...(await h.jsonValue()) };
      await h.dispose();
      text = a.text;
      stats.injections++;
    } else {
      // The loop runs on after the drop (and replans when the facts changed).
      const h = await page.waitForFunction(
        (tick) => {
          const g = window.lfd.frame();
          return (g.tick >= tick + 3 || g.status.kind === 'done' || g.status.kind === 'failed') && { replans: g.replans };
        },
        before.tick,
        { timeout: 30000, polling: 10 },
      );
      a = await h.jsonValue();
      await h.dispose();
    }
    if (/refused/i.test(text)) stats.refused++;
    else stats.accepted++;
    if (a.replans > before.replans) stats.replans += a.replans - before.replans;
    if (process.env.SOAK_TRACE && i % 50 === 0) {
      const m = await page.evaluate(() => window.lfd.memory());
      let heap = '';
      if (i % 200 === 0) {
        for (let g = 0; g < 3; g++) await cdp.send('HeapProfiler.collectGarbage');
        heap = `, JS heap after GC ${((await cdp.send('Runtime.getHeapUsage')).usedSize / 1e6).toFixed(2)} MB`;
      }
      console.log(`cycle ${i}: wasm ${(m.wasmBytes / 1e6).toFixed(2)} MB${heap}, ${((Date.now() - t0) / 1000).toFixed(0)} s`);
    }
    assert.deepEqual(errors, [], `cycle ${i}`);
  }
  const end = await measure(page, cdp);
  const seconds = (Date.now() - tMain) / 1000;
  const growth = (k) => (end[k] - warm[k]) / warm[k];
  const pct = (x) => `${(100 * x).toFixed(1)} %`;
  console.log(
    `soak: ${CYCLES} cycles in ${seconds.toFixed(0)} s after ${WARMUP} warm-up (${((Date.now() - t0) / 1000).toFixed(0)} s in all); ` +
      `${stats.injections} L1–L4 presses (${stats.unanswered} without a notice in 15 s), ${stats.drags} drags (${stats.missed} without a free block on screen or whose press missed it: L1 instead); ${stats.accepted} accepted, ${stats.refused} refused; ` +
      `${stats.replans} replans; ${stats.episodes} episodes ended (${stats.done} done, ${stats.failed} failed)`,
  );
  console.log(
    `soak memory after warm-up → end: JS heap ${(warm.heap / 1e6).toFixed(2)} → ${(end.heap / 1e6).toFixed(2)} MB (${pct(growth('heap'))}), ` +
      `wasm ${(warm.wasm / 1e6).toFixed(2)} → ${(end.wasm / 1e6).toFixed(2)} MB (${pct(growth('wasm'))}), ` +
      `geometries ${warm.geometries} → ${end.geometries}, textures ${warm.textures} → ${end.textures}, ` +
      `DOM nodes ${warm.nodes} → ${end.nodes}, listeners ${warm.listeners} → ${end.listeners}`,
  );
  if (reasons.size) console.log(`soak: episodes that failed, by reason: ${[...reasons].map(([r, n]) => `${n}× ${r}`).join('; ')}`);
  assert.deepEqual(errors, []);
  assert.ok(stats.accepted > CYCLES / 4, `only ${stats.accepted} perturbations were accepted`);
  assert.ok(stats.replans > 0, 'no replan during the soak');
  assert.ok(end.geometries <= warm.geometries, `three.js geometries leak: ${warm.geometries} → ${end.geometries}`);
  assert.ok(end.textures <= warm.textures, `three.js textures leak: ${warm.textures} → ${end.textures}`);
  assert.ok(growth('heap') <= MAX_GROWTH, `JS heap grew ${pct(growth('heap'))}`);
  // Wasm linear memory is a high-water mark (64 KiB pages, never returned): one larger search
  // late in a short run raises it once without any leak. So it may grow by MAX_GROWTH or by at
  // most SOAK_WASM_SLACK bytes (default 1 MiB); a leak grows with the cycle count and exceeds both
  // in the 1000-cycle run.
  const wasmSlack = Number(process.env.SOAK_WASM_SLACK ?? 1 << 20);
  assert.ok(
    growth('wasm') <= MAX_GROWTH || end.wasm - warm.wasm <= wasmSlack,
    `wasm memory grew ${pct(growth('wasm'))} (${((end.wasm - warm.wasm) / 1e6).toFixed(2)} MB)`,
  );
  assert.ok(end.listeners <= warm.listeners * (1 + MAX_GROWTH), `event listeners ${warm.listeners} → ${end.listeners}`);
  await page.close();
});
