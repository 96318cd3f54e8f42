/**
 * A worker of the Compare tab's experiment pool: it loads the full wasm module (Table I's items
 * need B2, B3 and the task generator, which the first-load module leaves out) and runs Table I's
 * parts on request: one item (`table1Task`), the report of all items (`table1Report`) and one
 * episode's log for a replay (`table1Episode`). Planning blocks this worker only.
 */
import init, * as lfd from 'logic-lfd-teach';
import type { ExperimentReply, ExperimentRequest } from './experiment-pool';

const post = (m: ExperimentReply) => (self as unknown as Worker).postMessage(m);

function run(r: ExperimentRequest): string {
  switch (r.kind) {
    case 'task':
      return lfd.table1Task(r.options, r.index);
    case 'report':
      return lfd.table1Report(r.options, r.items);
    case 'episode': {
      // How the Run's replay (default parameters: TAMP fallback on) ends, to check it against the
      // table's run before showing it.
      const log = lfd.table1Episode(r.options, r.index, r.run);
      const s = lfd.Session.replay(log);
      const end = s.frame().status.kind;
      s.free();
      return JSON.stringify({ log, end });
    }
  }
}

function message(e: unknown): string {
  if (e instanceof WebAssembly.RuntimeError) {
    let why = '';
    try {
      why = lfd.lastPanic();
    } catch {
      /* the module is gone */
    }
    return `internal error in the planner (${why || e.message})`;
  }
  return e instanceof Error ? e.message : String(e);
}

const ready = init();
self.onmessage = (e: MessageEvent<ExperimentRequest>) => {
  const r = e.data;
  void ready.then(
    () => {
      try {
        post({ id: r.id, ok: true, value: run(r) });
      } catch (err) {
        post({ id: r.id, ok: false, error: message(err) });
      }
    },
    (err: unknown) => post({ id: r.id, ok: false, error: `could not load the wasm module: ${message(err)}` }),
  );
};
