// Generated N-block tower tasks through the npm package: `blocks` in the Session options.
import { describe, test } from 'node:test';
import assert from 'node:assert/strict';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

const blocksOf = (frame) => frame.world.bodies.filter((b) => b.kind === 'block');

describe('Session with blocks', () => {
  test('B1 with 8 blocks builds its 8-block tower', () => {
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: 8 });
    assert.equal(blocksOf(s.frame()).length, 8);
    let f = s.frame();
    for (let i = 0; i < 6000 && f.status.kind !== 'done' && f.status.kind !== 'failed'; i++) f = s.step(0.1);
    assert.equal(f.status.kind, 'done', f.status.message);
    assert.equal(blocksOf(f).length, 8);
    // Every block but the bottom one stands on another: 7 `on` facts between blocks.
    const names = new Set(blocksOf(f).map((b) => b.name));
    const on = f.facts.filter((x) => {
      const m = /^\(on (\S+) (\S+)\)$/.exec(x);
      return m && names.has(m[1]) && names.has(m[2]);
    });
    assert.equal(on.length, 7, on.join(' '));
    s.free();
  });

  test('blockRange gives the counts each benchmark takes', () => {
    assert.deepEqual(lfd.blockRange('b1'), [3, 20]);
    assert.equal(lfd.blockRange('b2'), null);
    assert.deepEqual(lfd.blockRange('b3'), [2, 10]);
    assert.throws(() => lfd.blockRange('b4'), (e) => e instanceof Error && /unknown benchmark `b4`/.test(e.message));
  });

  test('B1 with 20 blocks starts with two towers to build', () => {
    const s = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: 20 });
    assert.equal(blocksOf(s.frame()).length, 20);
    // The demonstration ends with 18 `on` facts: two towers of 10.
    const last = s.frame().demoStates.at(-1);
    const on = last.filter((x) => /^\(on [a-t] [a-t]\)$/.test(x));
    assert.equal(on.length, 18, on.join(' '));
    assert.ok(on.includes('(on a b)') && on.includes('(on k l)') && !on.includes('(on j k)'), on.join(' '));
    s.free();
  });

  test('a block count out of range throws an Error naming the allowed range', () => {
    assert.throws(
      () => new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: 40 }),
      (e) => e instanceof Error && /allowed: 3 to 20/.test(e.message),
    );
    assert.throws(
      () => new lfd.Session({ benchmark: 'b3', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: 11 }),
      (e) => e instanceof Error && /allowed: 2 to 10/.test(e.message),
    );
  });

  test('B2 has no N-block variant', () => {
    assert.throws(
      () => new lfd.Session({ benchmark: 'b2', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: 4 }),
      (e) => e instanceof Error && /B2 has no N-block variant/i.test(e.message),
    );
  });

  test('blocks: null and an omitted blocks run the template task', () => {
    const a = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1, blocks: null });
    const b = new lfd.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 });
    assert.equal(blocksOf(a.frame()).length, 4);
    assert.deepEqual(a.frame().world.bodies, b.frame().world.bodies);
    a.free();
    b.free();
  });
});
