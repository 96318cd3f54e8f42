// The catalogue through the npm package: every method, mode, benchmark and disturbance level with
// a label and a description, and ids the rest of the package takes.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

describe('catalogue', () => {
  const c = lfd.catalogue();

  test('lists the four methods, two modes, three benchmarks and four levels', () => {
    const ids = (list) => list.map((e) => e.id);
    assert.deepEqual(ids(c.methods).sort(), ['linear', 'logic-lfd', 'rlds', 'tamp']);
    assert.deepEqual(ids(c.modes), ['paper', 'prioritised']);
    assert.deepEqual(ids(c.benchmarks), ['b1', 'b2', 'b3']);
    assert.deepEqual(ids(c.levels), ['l1', 'l2', 'l3', 'l4']);
  });

  test('every entry has a label and a one-sentence description', () => {
    for (const [kind, list] of Object.entries(c)) {
      for (const e of list) {
        assert.deepEqual(Object.keys(e).sort(), ['description', 'id', 'label'], `${kind} ${e.id}`);
        assert.ok(e.label.length > 0, `${kind} ${e.id} has no label`);
        assert.match(e.description, /^\S.*\.$/, `${kind} ${e.id}`);
      }
    }
  });

  test('its ids are the names the package takes', () => {
    for (const b of c.benchmarks) assert.equal(lfd.benchmark(b.id).id, b.id);
    const s = new lfd.Session({ benchmark: 'b1', method: c.methods[0].id, mode: c.modes[1].id, seed: 1 });
    for (const l of c.levels) assert.ok(s.canInject(l.id) === undefined || typeof s.canInject(l.id) === 'string');
    s.free();
  });
});
