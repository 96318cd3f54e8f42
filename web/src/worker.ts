/**
 * The Web Worker that owns the wasm module and the closed-loop Session: planning and simulation
 * never run on the page's thread, so the page never freezes. It plays the session in real time
 * (scaled by `speed`) and pushes a frame after every tick. Its first module is the page's
 * size-built first load ('logic-lfd-page': the Session on B1's template task, `benchmark`,
 * `blockRange` and `catalogue`, whose block counts and catalogue it sends with its `ready` message);
 * teach-worker.ts fetches the full one (built for speed) when Teach mode, `Session.replay`, the
 * PDDL tab's calls, a loaded scene, a task folder, B2, B3 or an N-block task need it, and
 * speed-up.ts moves the session onto it after the first frame.
 */
import init, * as lfd from 'logic-lfd-page';
import type { Frame, Level, RobotChoice, SessionOptions } from 'logic-lfd';
import type { Api, ApiKind, BlockRanges, FromWorker, ToWorker } from './protocol';
import { teachHandlers, teachLastPanic, teachMemoryBytes, teachModule } from './teach-worker';
import { type FullSession, fullModule, speedUp, speedUpState } from './speed-up';

const post = (m: FromWorker) => (self as unknown as Worker).postMessage(m);

/** The live session: on the first-load module until speed-up.ts moves it onto the full one. */
let session: lfd.Session | FullSession | null = null;
let wasmMemory: WebAssembly.Memory | null = null;
/** The first-load module's memory when it was instantiated (bytes). */
let freshBytes = 0;
/** The disturbance levels of the module's catalogue (read once it is loaded). */
let levels: Level[] = [];
let playing = false;
let speed = 1;
let timer: ReturnType<typeof setTimeout> | null = null;
let last = 0;
/** Ticks aim at 60 Hz; a tick advances the simulation by the wall time elapsed times `speed`. */
const TICK_MS = 1000 / 60;
/** Never advance more than this much simulated time in one tick (s), so a stalled tab catches up gently. */
const MAX_DT = 0.1;

function need(): lfd.Session | FullSession {
  if (!session) throw new Error('no session: choose a benchmark first');
  return session;
}

function replace(s: lfd.Session | FullSession): Frame {
  stop();
  session?.free();
  session = watched(s);
  return s.frame();
}

/** `s`, telling the page how a long search inside a step goes (the full module's sessions; the
 * page can show it while this worker is busy). */
function watched<S extends lfd.Session | FullSession>(s: S): S {
  if ('onProgress' in s) s.onProgress((expanded, ms) => post({ type: 'progress', expanded, ms }));
  return s;
}

function stop(): void {
  playing = false;
  if (timer !== null) clearTimeout(timer);
  timer = null;
}

function tick(): void {
  timer = null;
  if (!playing || !session) return;
  const now = performance.now();
  const dt = Math.min(MAX_DT, ((now - last) / 1000) * speed);
  last = now;
  const t0 = performance.now();
  let frame: Frame;
  try {
    frame = session.step(dt);
  } catch (e) {
    post({ type: 'fatal', message: errorMessage(e) });
    return;
  }
  const stepMs = performance.now() - t0;
  const finished = frame.status.kind === 'done' || frame.status.kind === 'failed';
  if (finished) playing = false;
  post({ type: 'frame', frame, timing: { stepMs, simSeconds: dt }, playing });
  if (playing) timer = setTimeout(tick, Math.max(0, TICK_MS - (performance.now() - now)));
}

/**
 * Whether the first-load module runs a session: it carries B1's template task only (B2's and B3's
 * demonstrations and the generator of N-block tasks are left out to keep the first load small);
 * the rest opens on the full module, fetched on demand if speed-up.ts has not fetched it yet.
 */
function firstLoadRuns(options: Pick<SessionOptions, 'benchmark' | 'blocks'> & { robot?: RobotChoice }): boolean {
  // A robot other than the default runs on the full module: the first-load one has no URDFs.
  return options.benchmark === 'b1' && options.blocks == null && options.robot === undefined;
}

/** The module for a session or benchmark: the full one once it is ready, else the first-load one
 * when that runs it, else the full one, fetched now. */
async function moduleFor(options: Pick<SessionOptions, 'benchmark' | 'blocks'> & { robot?: RobotChoice }) {
  return fullModule() ?? (firstLoadRuns(options) ? lfd : await teachModule());
}

type Handlers = { [K in ApiKind]: (args: Api[K]['args']) => Api[K]['result'] | Promise<Api[K]['result']> };

const handlers: Handlers = {
  version: () => lfd.version(),
  // The PDDL tab's calls live in the full module (the tab opens after the first load).
  plan: async ({ domain, problem, options }) => (await teachModule()).plan(domain, problem, options),
  check: async ({ domain, problem }) => (await teachModule()).check(domain, problem),
  logicLfd: async ({ input }) => (await teachModule()).logicLfd(input),
  logicLfdPerturb: async ({ input }) => (await teachModule()).logicLfdPerturb(input),
  benchmark: async ({ id }) => (await moduleFor({ benchmark: id })).benchmark(id),
  open: async ({ options, scene }) => {
    // A loaded scene opens on the full module, whose errors name the JSON path at fault.
    if (scene !== undefined) return replace((await teachModule()).Session.fromScene(options, scene));
    return replace(new (await moduleFor(options)).Session(options));
  },
  // Task folders run on the full module (recording a demonstration, JSON paths in errors).
  openFolder: async ({ files, options }) => replace((await teachModule()).Session.fromFolder(files, options)),
  task: async () => {
    const s = need();
    // A first-load session runs B1's template task, which the full module describes as well.
    if ('taskFiles' in s) return s.taskFiles();
    const b = (await teachModule()).benchmark('b1');
    return { domain: b.domain, problem: b.problem, demoPlan: b.demoPlan, dir: `domains/${b.name}` };
  },
  speedUp: () => {
    speedUp(
      () => session,
      (s) => {
        // Same episode, same frame: the loop keeps playing on the new session.
        session?.free();
        session = watched(s);
      },
    );
    return null;
  },
  speedUpState: () => speedUpState(),
  replay: async ({ episode }) => replace((await teachModule()).Session.replay(episode)),
  play: ({ speed: s }) => {
    need();
    speed = s;
    if (!playing) {
      playing = true;
      last = performance.now();
      timer = setTimeout(tick, 0);
    }
    return null;
  },
  pause: () => {
    stop();
    return session ? session.frame() : null;
  },
  step: ({ dt }) => {
    stop();
    return need().step(dt);
  },
  speed: ({ speed: s }) => {
    speed = s;
    return null;
  },
  perturb: ({ body, position }) => {
    const s = need();
    try {
      const o = s.perturb(body, position);
      const others = o.alsoMoved.length ? `; ${o.alsoMoved.map(([b]) => b).join(', ')} settled below` : '';
      return { ok: true, message: `Moved ${o.body} onto ${o.support}${others}`, frame: s.frame() };
    } catch (e) {
      return { ok: false, reason: errorMessage(e) };
    }
  },
  inject: ({ level }) => {
    const s = need();
    const i = s.inject(level);
    const push = i.push && { arm: i.push.arm, from: i.push.from, to: i.push.to };
    return { message: i.description, frame: s.frame(), moved: i.moved.map(([b]) => b), push };
  },
  levels: () => {
    const s = need();
    return Object.fromEntries(levels.map((l) => [l, s.canInject(l) ?? null])) as Record<Level, string | null>;
  },
  reset: ({ seed }) => {
    stop();
    const s = need();
    s.reset(seed);
    return s.frame();
  },
  cancel: () => {
    const s = need();
    s.cancel();
    const appliedAt = performance.timeOrigin + performance.now();
    return { frame: s.frame(), appliedAt };
  },
  episode: ({ withFiles }) => need().episodeJson(withFiles ? { withFiles } : undefined),
  scene: () => need().sceneJson(),
  memory: () => {
    const [teach, teachFresh] = teachMemoryBytes();
    return { wasmBytes: (wasmMemory?.buffer.byteLength ?? 0) + teach, freshBytes: freshBytes + teachFresh };
  },
  ...teachHandlers(replace),
};

function errorMessage(e: unknown): string {
  if (e instanceof WebAssembly.RuntimeError) {
    // A panic aborted the module (a bug): say so, with the panic's message, and stop playing.
    stop();
    session = null;
    let why = '';
    for (const lastPanic of [lfd.lastPanic, teachLastPanic]) {
      try {
        why ||= lastPanic();
      } catch {
        /* the module is gone */
      }
    }
    return `internal error in the planner (${why || e.message}); reload the page`;
  }
  if (e instanceof Error) return e.message;
  return typeof e === 'string' ? e : JSON.stringify(e);
}

async function handle(req: ToWorker): Promise<void> {
  try {
    const h = handlers[req.kind] as (a: unknown) => unknown;
    const value = await h(req.args);
    post({ type: 'reply', id: req.id, ok: true, value });
  } catch (e) {
    post({ type: 'reply', id: req.id, ok: false, error: errorMessage(e) });
  }
}

const ready = init().then(
  (wasm) => {
    wasmMemory = wasm.memory;
    freshBytes = wasm.memory.buffer.byteLength;
    const catalogue = lfd.catalogue();
    levels = catalogue.levels.map((l) => l.id);
    const blockRanges = Object.fromEntries(catalogue.benchmarks.map(({ id }) => [id, lfd.blockRange(id)])) as BlockRanges;
    post({ type: 'ready', version: lfd.version(), blockRanges, catalogue });
  },
  (e) => post({ type: 'fatal', message: `could not load the wasm module: ${errorMessage(e)}` }),
);

// One request at a time, in order, even when a handler waits (for Teach mode's module).
let queue: Promise<void> = ready;
self.onmessage = (e: MessageEvent<ToWorker>) => {
  queue = queue.then(() => handle(e.data));
};
