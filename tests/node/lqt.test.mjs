// LQT-CP through the npm package: the shared example case, object and JSON-text inputs, errors.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);
const caseText = readFileSync(fileURLToPath(new URL('../data/lqt/lqt-cp-example.json', import.meta.url)), 'utf8');
const input = JSON.parse(caseText);

test('the shared example solves with the documented shapes', () => {
  const out = lfd.lqt(input);
  const T = input.n_steps;
  const N = T - 1;
  const D = input.dim;
  const nx = D * input.order;
  assert.equal(out.x.length, T);
  assert.equal(out.x[0].length, nx);
  assert.equal(out.u.length, N);
  assert.equal(out.pos.length, T);
  assert.equal(out.phi.length, N);
  assert.equal(out.phi[0].length, input.basis.n_fct);
  assert.deepEqual(out.x[0], input.x0);
  assert.ok(Number.isFinite(out.cost) && out.cost >= 0);
  // The goal target is reached to goal-level precision (weight 1 against r = 1e-6).
  const goal = out.target_errors.find((e) => e.role === 'goal');
  assert.ok(goal.pos_dist < 0.01, `goal error ${goal.pos_dist}`);
  // x_init == x0: the nominal feedback rollout replays the batch trajectory.
  const nominal = out.feedback.nominal;
  for (let t = 0; t < T; t++) {
    for (let i = 0; i < nx; i++) assert.ok(Math.abs(nominal.x[t][i] - out.x[t][i]) < 1e-6);
  }
  // The perturbed rollout is pushed away and pulled back near the goal by the feedback gains.
  assert.ok(out.feedback.perturbed.final_goal_pos_dist < 0.05);
});

test('JSON text and object inputs give the same answer', () => {
  assert.deepEqual(lfd.lqt(caseText).pos, lfd.lqt(input).pos);
});

test('a malformed case rejects with a message naming the key, never a panic', () => {
  assert.throws(() => lfd.lqt({ ...input, n_steps: 'sixty' }), /n_steps/);
  assert.throws(() => lfd.lqt('{ not json'), /./);
  // The module still works after an error.
  assert.equal(lfd.lqt(input).x.length, input.n_steps);
});
