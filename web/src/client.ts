/**
 * The page's side of the protocol: typed promises over postMessage.
 */
import type { Api, ApiKind, FromWorker, Ready, ToWorker } from './protocol';

/** A request that was cancelled (or timed out) before the worker answered. */
export class CancelledError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'CancelledError';
  }
}

export class WorkerClient {
  private worker!: Worker;
  private nextId = 1;
  private readonly pending = new Map<number, { resolve: (v: unknown) => void; reject: (e: Error) => void }>();
  /** The worker's module is loaded: its version, the block counts of the N-block tasks and the catalogue. */
  ready: Promise<Ready>;

  constructor(private readonly onPush: (m: FromWorker) => void) {
    this.ready = this.start();
  }

  /** Replaces the worker by a fresh one: wasm memory only grows, so this is how a long search's
   * memory returns. Pending calls reject; the new worker has no session. */
  respawn(): Promise<Ready> {
    this.terminate('the planner restarted');
    return (this.ready = this.start());
  }

  private start(): Promise<Ready> {
    const onPush = this.onPush;
    this.worker = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
    let resolveReady!: (v: Ready) => void;
    let rejectReady!: (e: Error) => void;
    const ready = new Promise<Ready>((res, rej) => {
      resolveReady = res;
      rejectReady = rej;
    });
    this.worker.onmessage = (e: MessageEvent<FromWorker>) => {
      const m = e.data;
      if (m.type === 'reply') {
        const p = this.pending.get(m.id);
        if (!p) return;
        this.pending.delete(m.id);
        if (m.ok) p.resolve(m.value);
        else p.reject(new Error(m.error));
      } else if (m.type === 'ready') {
        resolveReady({ version: m.version, blockRanges: m.blockRanges, catalogue: m.catalogue });
      } else if (m.type === 'fatal') {
        rejectReady(new Error(m.message));
        onPush(m);
      } else {
        onPush(m);
      }
    };
    this.worker.onerror = (e) => rejectReady(new Error(e.message || 'worker failed to start'));
    return ready;
  }

  call<K extends ApiKind>(kind: K, args: Api[K]['args']): Promise<Api[K]['result']> {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve: resolve as (v: unknown) => void, reject });
      this.worker.postMessage({ kind, id, args } as ToWorker);
    });
  }

  /** Whether a request is waiting for its reply. */
  get busy(): boolean {
    return this.pending.size > 0;
  }

  /** Stops the worker at once (even in the middle of a computation); pending calls reject. */
  terminate(message: string): void {
    this.worker.terminate();
    for (const p of this.pending.values()) p.reject(new CancelledError(message));
    this.pending.clear();
  }
}

/**
 * Runs the PDDL editor's requests (plan, check) in a worker of their own, so that a pathological
 * problem typed into the editor never blocks the session's worker or the page: a request that
 * runs longer than its time limit, or that the user cancels, terminates that worker (wasm cannot
 * be interrupted from outside any other way); the next request starts a fresh one.
 */
export class SearchRunner {
  private client: WorkerClient | null = null;
  private timers = new Set<number>();

  /** Sends `kind` to the search worker; rejects with `CancelledError` after `timeoutMs`. */
  call<K extends ApiKind>(kind: K, args: Api[K]['args'], timeoutMs: number): Promise<Api[K]['result']> {
    const client = (this.client ??= new WorkerClient(() => {}));
    const timer = window.setTimeout(() => {
      if (this.client === client) this.cancel(`stopped after ${(timeoutMs / 1000).toFixed(0)} s: the search took too long`);
    }, timeoutMs);
    this.timers.add(timer);
    return client.call(kind, args).finally(() => {
      clearTimeout(timer);
      this.timers.delete(timer);
    });
  }

  /** Whether a request is running. */
  get busy(): boolean {
    return this.client?.busy ?? false;
  }

  /** Terminates the search worker (pending requests reject with `message`). */
  cancel(message = 'cancelled'): void {
    const c = this.client;
    this.client = null;
    for (const t of this.timers) clearTimeout(t);
    this.timers.clear();
    c?.terminate(message);
  }
}
