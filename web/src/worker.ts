// The Web Worker that owns the wasm module (and the Session): the page never blocks on planning.
import init, * as lfd from 'logic-lfd';
import type { Api, ApiKind, FromWorker, ToWorker } from './protocol';

const post = (m: FromWorker) => (self as unknown as Worker).postMessage(m);

type Handlers = { [K in ApiKind]: (args: Api[K]['args']) => Api[K]['result'] | Promise<Api[K]['result']> };

const handlers: Handlers = {
  version: () => lfd.version(),
};

function message(e: unknown): string {
  if (e instanceof Error) return e.message;
  return typeof e === 'string' ? e : JSON.stringify(e);
}

async function handle(req: ToWorker): Promise<void> {
  try {
    const h = handlers[req.kind] as (a: unknown) => unknown;
    const value = await h(req.args);
    post({ type: 'reply', id: req.id, ok: true, value });
  } catch (e) {
    post({ type: 'reply', id: req.id, ok: false, error: message(e) });
  }
}

const ready = init().then(
  () => post({ type: 'ready', version: lfd.version() }),
  (e) => post({ type: 'fatal', message: `could not load the wasm module: ${message(e)}` }),
);

self.onmessage = (e: MessageEvent<ToWorker>) => {
  void ready.then(() => handle(e.data));
};
