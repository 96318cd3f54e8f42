// Helpers of the interaction tests: a real mouse drag of a body, the screen point of a spot on the
// table, and waiting for a status.

/** The screen point of the table top at world (x, y) (the support under `p`; `p[2]` is ignored). */
export async function dropPoint(page, p) {
  return page.evaluate(([x, y]) => {
    const f = window.lfd.frame();
    const tops = [];
    for (const b of f.world.bodies) {
      if ((b.kind !== 'table' && b.kind !== 'shelf') || b.shape.type !== 'cuboid') continue;
      const [hx, hy, hz] = b.shape.half_extents;
      const [bx, by, bz] = b.pose.position;
      if (Math.abs(bx - x) <= hx && Math.abs(by - y) <= hy) tops.push(bz + hz);
    }
    const z = tops.length ? Math.max(...tops) : 0;
    return window.lfd.project([x, y, z]);
  }, p);
}

/** Drags body `name` with the mouse to the screen point `to` and releases it. */
export async function dragBody(page, name, to, steps = 12) {
  const from = await page.evaluate((n) => window.lfd.screenPosition(n), name);
  if (!from) throw new Error(`no body ${name} on screen`);
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move(to.x, to.y, { steps });
  await page.mouse.up();
}

/** Waits until the frame's status kind is one of `kinds` (or, with `not`, none of them). */
export async function waitStatus(page, kinds, { not = false, timeout = 30000 } = {}) {
  await page.waitForFunction(
    ([kinds, not]) => {
      const f = window.lfd.frame();
      return !!f && kinds.includes(f.status.kind) !== not;
    },
    [kinds, not],
    { timeout, polling: 50 },
  );
}

/** Drags the timeline's thumb with the mouse to time `t`. */
export async function scrubTo(page, t) {
  const r = await page.$eval('#timeline-range', (e) => {
    const b = e.getBoundingClientRect();
    return { left: b.left, width: b.width, y: b.top + b.height / 2, max: Number(e.max), value: Number(e.value) };
  });
  // The thumb (14 px) travels between the track's ends inset by its half width.
  const x = (v) => r.left + 7 + ((r.width - 14) * v) / r.max;
  await page.mouse.move(x(r.value), r.y);
  await page.mouse.down();
  await page.mouse.move(x(t), r.y, { steps: 8 });
  await page.mouse.up();
}

/** Waits for the L3 marker and a replan marker at or after it; returns the L3 marker's time. */
export async function waitL3Replan(page) {
  await page.waitForFunction(
    () => {
      const m = window.lfd.marks();
      const l3 = m.find((x) => x.kind === 'l3');
      return !!l3 && m.some((x) => x.kind === 'replan' && x.t >= l3.t - 1e-9);
    },
    null,
    { timeout: 30000, polling: 50 },
  );
  return page.evaluate(() => window.lfd.marks().find((x) => x.kind === 'l3').t);
}
