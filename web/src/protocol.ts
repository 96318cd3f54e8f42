// The one message protocol between the page (main thread) and the worker that owns the wasm.
// Requests carry an `id`; the worker answers each with exactly one `reply` of the same id.
// Frames are pushed by the worker while a session plays.

export interface Request<K extends string, A> {
  kind: K;
  id: number;
  args: A;
}

/** Every request the page can make, with its arguments and the value its reply carries. */
export interface Api {
  version: { args: Record<string, never>; result: string };
}

export type ApiKind = keyof Api;

export type ToWorker = { [K in ApiKind]: Request<K, Api[K]['args']> }[ApiKind];

export type FromWorker =
  | { type: 'ready'; version: string }
  | { type: 'fatal'; message: string }
  | { type: 'reply'; id: number; ok: true; value: unknown }
  | { type: 'reply'; id: number; ok: false; error: string };
