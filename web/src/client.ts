// The page's side of the protocol: typed promises over postMessage.
import type { Api, ApiKind, FromWorker, ToWorker } from './protocol';

export class WorkerClient {
  private readonly worker: Worker;
  private nextId = 1;
  private readonly pending = new Map<number, { resolve: (v: unknown) => void; reject: (e: Error) => void }>();
  readonly ready: Promise<string>;

  constructor(onPush: (m: FromWorker) => void) {
    this.worker = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
    let resolveReady!: (v: string) => void;
    let rejectReady!: (e: Error) => void;
    this.ready = new Promise((res, rej) => {
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
        resolveReady(m.version);
      } else if (m.type === 'fatal') {
        rejectReady(new Error(m.message));
      } else {
        onPush(m);
      }
    };
    this.worker.onerror = (e) => rejectReady(new Error(e.message || 'worker failed to start'));
  }

  call<K extends ApiKind>(kind: K, args: Api[K]['args']): Promise<Api[K]['result']> {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve: resolve as (v: unknown) => void, reject });
      this.worker.postMessage({ kind, id, args } as ToWorker);
    });
  }
}
