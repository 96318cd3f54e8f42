// Table I in parts from the wasm package (`table1Task`, `table1Report`, `table1Episode`): items
// run in any order give the same table, the per-level tables split the tasks by level, the
// episode of one method replays, and bad options or indices are refused with a message.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

const zeroed = (t) => ({ ...t, cells: t.cells.map((c) => ({ ...c, plan_ms: c.plan_ms.map(() => 0), search_ms: c.search_ms.map(() => 0), bind_ms: c.bind_ms.map(() => 0) })) });

describe('table1 parts', () => {
  test('B1, 3 tasks: order of the items does not matter; levels split the tasks; an episode replays', () => {
    const options = JSON.stringify({ benchmarks: ['b1'], tasks: 3, seed: 2 });
    const forward = [0, 1, 2].map((i) => lfd.table1Task(options, i));
    const backward = [2, 1, 0].map((i) => lfd.table1Task(options, i)).reverse();
    const a = JSON.parse(lfd.table1Report(options, `[${forward.join(',')}]`));
    const b = JSON.parse(lfd.table1Report(options, `[${backward.join(',')}]`));
    assert.deepEqual(zeroed(a.table), zeroed(b.table));
    assert.deepEqual(a.levels.map((l) => [l.level, l.items]), [['l1', [0]], ['l2', [1]], ['l3', [2]]]);
    a.table.cells.forEach((c, k) => {
      assert.equal(a.levels.reduce((n, l) => n + l.table.cells[k].tasks, 0), c.tasks);
      const [lo, hi] = a.intervals[k];
      const rate = c.successes / c.tasks;
      assert.ok(lo <= rate && rate <= hi, `${c.method}: ${rate} in [${lo}, ${hi}]`);
    });
    const item = JSON.parse(forward[1]);
    const log = lfd.table1Episode(options, 1, 1);
    assert.equal(JSON.parse(log).options.method, 'tamp');
    const s = lfd.Session.replay(log);
    assert.equal(s.frame().status.kind === 'done', item.runs[1].success_actions !== null);
    s.free();
  });

  test('bad options and indices are refused with a message', () => {
    const options = JSON.stringify({ benchmarks: ['b1'], tasks: 2, seed: 1 });
    assert.throws(() => lfd.table1Task(options, 2), /index must be a whole number below 2/);
    assert.throws(() => lfd.table1Task(options, 0.5), /index must be a whole number/);
    assert.throws(() => lfd.table1Task(JSON.stringify({ benchmarks: ['b9'], tasks: 1, seed: 1 }), 0), /unknown benchmark "b9"/);
    assert.throws(() => lfd.table1Task(JSON.stringify({ benchmarks: ['b1'], tasks: 1, seed: 1, extra: 1 }), 0), /unknown field `extra`/);
    assert.throws(() => lfd.table1Report(options, '[]'), /0 given, the sweep has 2/);
    assert.throws(() => lfd.table1Episode(options, 0, 4), /run must be a whole number below 4/);
  });
});
