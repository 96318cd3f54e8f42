/**
 * The one message protocol between the page (main thread) and the worker that owns the wasm
 * module and the Session. Requests carry an `id`; the worker answers each with exactly one `reply`
 * of the same id. While a session plays, the worker pushes `frame` messages on its own.
 */
import type {
  Benchmark,
  BenchmarkInfo,
  Catalogue,
  Diagnostic,
  FolderOptions,
  Frame,
  LogicLfdInput,
  LogicLfdPerturbInput,
  LogicLfdPerturbResult,
  LogicLfdResult,
  Level,
  PlanOptions,
  PlanOutcome,
  RobotChoice,
  SessionOptions,
  TaskFiles,
} from 'logic-lfd';
import type { SpeedUpState } from './speed-up';
import type { TeachApi } from './teach-protocol';

export type Vec3 = [number, number, number];

/** The result of a user's drop: accepted (with what the world did) or refused with a reason. */
export type DropOutcome = { ok: true; message: string; frame: Frame } | { ok: false; reason: string };

/** What an injected disturbance did. */
export interface InjectOutcome {
  message: string;
  frame: Frame;
  /** The bodies it moved. */
  moved: string[];
  /** A push of an arm's hand (L1 while the arm moves): where its tool centre was and went. */
  push?: { arm: string; from: Vec3; to: Vec3 };
}

/** Every request the page can make: its arguments and the value its reply carries. */
export interface Api extends TeachApi {
  version: { args: Record<string, never>; result: string };
  plan: { args: { domain: string; problem: string; options: PlanOptions }; result: PlanOutcome };
  check: { args: { domain: string; problem: string }; result: Diagnostic[] };
  /** Logic-LfD on the texts of the PDDL tab (plain data in and out). */
  logicLfd: { args: { input: LogicLfdInput }; result: LogicLfdResult };
  logicLfdPerturb: { args: { input: LogicLfdPerturbInput }; result: LogicLfdPerturbResult };
  benchmark: { args: { id: Benchmark }; result: BenchmarkInfo };
  /** A session on a benchmark (`new Session`, `Session.fromScene`), `robot` in the arms' place. */
  open: { args: { options: SessionOptions & { robot?: RobotChoice }; scene?: string }; result: Frame };
  /** A session on a task folder given by its files (`Session.fromFolder`). */
  openFolder: { args: { files: Record<string, string>; options: FolderOptions & { robot?: RobotChoice } }; result: Frame };
  replay: { args: { episode: string }; result: Frame };
  /** The domain, problem and demonstration plan the session runs (a folder's, a generated task's). */
  task: { args: Record<string, never>; result: TaskFiles };
  play: { args: { speed: number }; result: null };
  pause: { args: Record<string, never>; result: Frame | null };
  step: { args: { dt: number }; result: Frame };
  speed: { args: { speed: number }; result: null };
  perturb: { args: { body: string; position: Vec3 }; result: DropOutcome };
  inject: { args: { level: Level }; result: InjectOutcome };
  /** Per level, why an injection would be refused now (null: it would apply). */
  levels: { args: Record<string, never>; result: Record<Level, string | null> };
  reset: { args: { seed: number }; result: Frame };
  /** `appliedAt`: when the worker dropped the plan (ms, `performance.timeOrigin + performance.now()`). */
  cancel: { args: Record<string, never>; result: { frame: Frame; appliedAt: number } };
  /** The episode log; `withFiles`: a folder's log carries its files. */
  episode: { args: { withFiles?: boolean }; result: string };
  /** The worker's wasm linear memory (bytes; it grows, never shrinks), and its size when the
   * modules were instantiated. */
  memory: { args: Record<string, never>; result: { wasmBytes: number; freshBytes: number } };
  scene: { args: Record<string, never>; result: string };
  /** Fetch the full-speed module and move the session onto it (starts it; answers at once). */
  speedUp: { args: Record<string, never>; result: null };
  speedUpState: { args: Record<string, never>; result: SpeedUpState };
}

export type ApiKind = keyof Api;

export type ToWorker = { [K in ApiKind]: { kind: K; id: number; args: Api[K]['args'] } }[ApiKind];

/** Timing of one worker tick: wall time of `Session::step` and of the whole tick (ms). */
export interface TickTiming {
  stepMs: number;
  simSeconds: number;
}

/** The block counts `[fewest, most]` of each benchmark's generated N-block tower task (null: none),
 * as the wasm module's `blockRange` gives them. */
export type BlockRanges = Record<Benchmark, [number, number] | null>;

/** What the worker says once its module is loaded. */
export interface Ready {
  version: string;
  blockRanges: BlockRanges;
  /** The methods, modes, benchmarks and disturbance levels, as the module's `catalogue()` lists them. */
  catalogue: Catalogue;
}

export type FromWorker =
  | ({ type: 'ready' } & Ready)
  | { type: 'fatal'; message: string }
  | { type: 'frame'; frame: Frame; timing: TickTiming; playing: boolean }
  /** A search inside the running step has expanded `expanded` states in `ms` so far. */
  | { type: 'progress'; expanded: number; ms: number }
  | { type: 'reply'; id: number; ok: true; value: unknown }
  | { type: 'reply'; id: number; ok: false; error: string };
