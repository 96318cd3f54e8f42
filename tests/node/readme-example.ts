// The README's TypeScript example, type-checked against the package's declarations by `npm test`
// (tsc --noEmit); keep it identical to the README.
import init, { plan, LogicLfd, Session } from 'logic-lfd';
import { readFileSync } from 'node:fs';

await init(); // fetches the .wasm in a browser; a no-op in node

// Plan the B1 tower task (errors come back as { ok: false, diagnostics: [{ file, line, col, message }] }).
const out = plan(
  readFileSync('domains/b1-tower/domain.pddl', 'utf8'),
  readFileSync('domains/b1-tower/problem.pddl', 'utf8'),
  { search: 'astar', heuristic: 'lmcut' },
);
if (out.ok) console.log(`${out.plan.length} actions:`, out.plan.join(' '));
else for (const d of out.diagnostics) console.error(`${d.file}:${d.line}:${d.col}: ${d.message}`);

// Run a B1 episode (the tower A on B on C on D) and disturb it once.
const session = new Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1 });
let frame = session.frame();
for (let i = 0; i < 3000 && frame.status.kind !== 'done' && frame.status.kind !== 'failed'; i++) {
  frame = session.step(0.1); // 0.1 s of simulated time; replans happen inside
  if (i === 30) console.log(session.inject('l3').description); // facts change to an unseen state
}
console.log(frame.status.message, `(${frame.replans} replans, last ${frame.lastReplan?.timeMs.toFixed(2)} ms)`);
session.free();

// Logic-LfD on any PDDL domain: read the task once, then replan from each observed state.
const read = (f: string) => readFileSync(`domains/delivery/${f}`, 'utf8');
const lfd = new LogicLfd({ domain: read('domain.pddl'), problem: read('problem.pddl'), demo: read('demo.plan') });
const next = lfd.replan(read('disturbed.facts'), { mode: 'prioritised' });
console.log(`joins L_${next.k} after ${next.prefix.length} new actions, valid: ${next.valid}`);
lfd.free();
