/**
 * The Compare tab's pool of experiment workers (experiment-worker.ts, each with the full wasm
 * module): Table I's items are handed out one at a time to whichever worker is free, so a long
 * task never holds up the others; Cancel terminates every worker at once (wasm cannot be
 * interrupted any other way).
 */

/** What a pool worker is asked: `options` is the sweep's JSON (`table1Task`'s options). */
export type ExperimentRequest =
  | { id: number; kind: 'task'; options: string; index: number }
  | { id: number; kind: 'report'; options: string; items: string }
  | { id: number; kind: 'episode'; options: string; index: number; run: number };

/** A worker's answer: the JSON text the module returned, or its error. */
export type ExperimentReply = { id: number; ok: true; value: string } | { id: number; ok: false; error: string };

type Body<R> = R extends { id: number } ? Omit<R, 'id'> : never;

/** Workers for a machine: one per hardware thread, at least one, at most 8 (each holds a module
 * of its own, some 20 MB of memory). */
export function poolSize(items: number): number {
  const threads = Math.max(1, navigator.hardwareConcurrency || 1);
  return Math.max(1, Math.min(threads, 8, items));
}

/** One dedicated worker with typed requests, one at a time. */
export class ExperimentWorker {
  private readonly worker = new Worker(new URL('./experiment-worker.ts', import.meta.url), { type: 'module' });
  private nextId = 1;
  private readonly pending = new Map<number, { resolve: (v: string) => void; reject: (e: Error) => void }>();

  constructor() {
    this.worker.onmessage = (e: MessageEvent<ExperimentReply>) => {
      const m = e.data;
      const p = this.pending.get(m.id);
      if (!p) return;
      this.pending.delete(m.id);
      if (m.ok) p.resolve(m.value);
      else p.reject(new Error(m.error));
    };
    this.worker.onerror = (e) => this.fail(e.message || 'the experiment worker failed to start');
  }

  call(body: Body<ExperimentRequest>): Promise<string> {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ ...body, id } as ExperimentRequest);
    });
  }

  terminate(why: string): void {
    this.worker.terminate();
    this.fail(why);
  }

  private fail(why: string): void {
    for (const p of this.pending.values()) p.reject(new Error(why));
    this.pending.clear();
  }
}

/** Thrown by a pool's run once it was cancelled. */
export class PoolCancelled extends Error {}

/** Runs items `0..count` of a sweep on `size` workers; resolves to their JSON in item order. */
export class Pool {
  private readonly workers: ExperimentWorker[];
  private cancelled = false;

  constructor(size: number) {
    this.workers = Array.from({ length: size }, () => new ExperimentWorker());
  }

  get size(): number {
    return this.workers.length;
  }

  async run(options: string, count: number, progress: (done: number) => void): Promise<string[]> {
    const out: string[] = new Array<string>(count);
    let next = 0;
    let done = 0;
    const drain = async (w: ExperimentWorker) => {
      while (next < count && !this.cancelled) {
        const index = next++;
        out[index] = await w.call({ kind: 'task', options, index });
        progress(++done);
      }
    };
    try {
      await Promise.all(this.workers.map(drain));
    } catch (e) {
      if (this.cancelled) throw new PoolCancelled('cancelled');
      throw e;
    }
    if (this.cancelled) throw new PoolCancelled('cancelled');
    return out;
  }

  /** Joins the items on the first worker (`table1Report`). */
  report(options: string, items: string[]): Promise<string> {
    return this.workers[0].call({ kind: 'report', options, items: `[${items.join(',')}]` });
  }

  /** Stops every worker at once; the run in progress rejects with `PoolCancelled`. */
  cancel(): void {
    this.cancelled = true;
    this.close('cancelled');
  }

  close(why: string): void {
    for (const w of this.workers) w.terminate(why);
  }
}
