/**
 * Moves the worker's closed loop onto the full-speed wasm module. The first load carries a
 * size-built module; once the page has drawn its first frame, the worker fetches the full one (the
 * module Teach mode uses, built for speed), warms its hot paths up on throw-away B1 episodes in
 * short slices between ticks (V8 runs wasm in its baseline compiler until a function is hot, and
 * a replan is too rare to get hot on its own), then replays the running session's episode on it
 * and switches only if the replayed episode and frame are identical to the live ones.
 */
import type { Frame } from 'logic-lfd';
import { teachModule } from './teach-worker';

export type FullModule = Awaited<ReturnType<typeof teachModule>>;
export type FullSession = InstanceType<FullModule['Session']>;

/** What the worker knows of its session: the structural API both modules share. */
export interface LiveSession {
  frame(): Frame;
  episodeJson(): string;
  free(): void;
}

/** Where the speed-up stands, for the page's tests and the bench. */
export interface SpeedUpState {
  /** `idle` (not asked yet), `loading`, `warming`, `ready` (new sessions open on the full module),
   * `refused` (a replay differed: everything stays on the first-load module), `failed` (no module). */
  stage: 'idle' | 'loading' | 'warming' | 'ready' | 'refused' | 'failed';
  /** Throw-away replans run while warming. */
  warmReplans: number;
  /** Sessions moved onto the full module by replay. */
  moved: number;
  /** Why the last move was refused or the module failed, or "". */
  reason: string;
}

/** Throw-away episodes run to warm the full module up: each disturbs B1 at several moments of its
 * task, as a user does, so the replans and the motions after them both get hot. */
const WARM_EPISODES = 6;
const WARM_LEVELS = ['l3', 'l4', 'l3', 'l2'] as const;
/** Simulated seconds between two disturbances, stepped in slices of `WARM_SLICE_S`. */
const WARM_GAP_S = 0.6;
const WARM_SLICE_S = 0.1;

const state: SpeedUpState = { stage: 'idle', warmReplans: 0, moved: 0, reason: '' };
let full: FullModule | null = null;

export function speedUpState(): SpeedUpState {
  return { ...state };
}

/** The full module once it is warm and trusted for new sessions, else null. */
export function fullModule(): FullModule | null {
  return state.stage === 'ready' ? full : null;
}

/** The episode log with wall-clock times zeroed: a replay computes everything else. */
function canonicalEpisode(json: string): string {
  const log = JSON.parse(json) as { replans: { time_ms: number; bind_ms: number }[] };
  for (const r of log.replans) {
    r.time_ms = 0;
    r.bind_ms = 0;
  }
  return JSON.stringify(log);
}

/** What the last `step` changed (`factsAdded`, `factsRemoved`) is not state: a replay has none. */
const NOT_STATE = new Set(['timeMs', 'bindMs', 'factsAdded', 'factsRemoved']);

function canonicalFrame(f: Frame): string {
  return JSON.stringify(f, (k, v: unknown) => (NOT_STATE.has(k) ? 0 : v));
}

/** Runs `work` in slices, one per macrotask, so the worker's ticks and requests interleave. */
function sliced(work: Generator<void>): Promise<void> {
  return new Promise((resolve, reject) => {
    const next = () => {
      try {
        if (work.next().done) resolve();
        else setTimeout(next, 0);
      } catch (e) {
        reject(e);
      }
    };
    setTimeout(next, 0);
  });
}

/** Throw-away B1 episodes on `m`, one wasm call per slice; counts their replans. */
function* warmUp(m: FullModule): Generator<void> {
  for (let i = 0; i < WARM_EPISODES; i++) {
    const s = new m.Session({ benchmark: 'b1', method: 'logic-lfd', mode: 'paper', seed: 1000 + i });
    try {
      let replans = 0;
      for (const level of [null, ...WARM_LEVELS]) {
        if (level && s.canInject(level) === undefined) s.inject(level);
        for (let t = 0; t < WARM_GAP_S; t += WARM_SLICE_S) {
          yield;
          const f = s.step(WARM_SLICE_S);
          replans = f.replans;
          if (f.status.kind === 'done' || f.status.kind === 'failed') break;
        }
      }
      state.warmReplans += replans;
    } finally {
      s.free();
    }
  }
}

/**
 * Replays `live` on the full module: the new session when its episode and frame are identical to
 * the live ones (wall-clock times aside), else null (and the move is refused for good).
 */
function moveOnto(m: FullModule, live: LiveSession): FullSession | null {
  const episode = live.episodeJson();
  const next = m.Session.replay(episode);
  const same = canonicalEpisode(next.episodeJson()) === canonicalEpisode(episode) && canonicalFrame(next.frame()) === canonicalFrame(live.frame());
  if (same) return next;
  next.free();
  return null;
}

/**
 * Starts the speed-up once (later calls do nothing). `current` reads the worker's session when the
 * move happens; `install` puts the moved session in its place (the worker keeps playing).
 */
export function speedUp(current: () => LiveSession | null, install: (s: FullSession) => void): void {
  if (state.stage !== 'idle') return;
  state.stage = 'loading';
  void (async () => {
    try {
      const m = await teachModule();
      state.stage = 'warming';
      await sliced(warmUp(m));
      full = m;
      const live = current();
      // A session opened from the full module (Teach mode's) is there already.
      if (live && !(live instanceof m.Session)) {
        const moved = moveOnto(m, live);
        if (!moved) {
          state.stage = 'refused';
          state.reason = 'the replayed episode differs from the live one';
          return;
        }
        install(moved);
        state.moved++;
      }
      state.stage = 'ready';
    } catch (e) {
      state.stage = 'failed';
      state.reason = e instanceof Error ? e.message : String(e);
    }
  })();
}
