/**
 * What the page knows, in one object: the scenario it runs (benchmark, method, mode, seed, blocks), the
 * playback (speed, playing), the latest frame from the worker (status, plan, demo, facts), the step
 * timings, the open tab and the last cancel. Also the block counts the controls offer and the URL
 * that restores a scenario (the permalink); the methods, modes, benchmarks and levels they offer
 * come from the catalogue (catalogue.ts).
 */
import type { Benchmark, Catalogue, Frame, Method, Mode, SessionOptions } from 'logic-lfd';
import { entryOf } from './catalogue';
import type { OpenFolder } from './folder';
import { robotFromUrl, type RobotPick } from './robot-choice';
import type { BlockRanges } from './protocol';

export type TabId = 'run' | 'teach' | 'charts' | 'pddl' | 'compare';

/** The scenario the Run's session runs: its options with every choice made. */
export type Scenario = SessionOptions & { method: Method; mode: Mode; seed: number };

/** What a page without a choice in its URL runs. */
const DEFAULTS = { benchmark: 'b1', method: 'logic-lfd', mode: 'paper' } as const satisfies Pick<Scenario, 'benchmark' | 'method' | 'mode'>;

/**
 * The block counts of each benchmark's generated N-block tower task (`[fewest, most]`; null: none),
 * from the wasm module's `blockRange` (the worker sends them when it is ready); null until then.
 */
let blockRanges: BlockRanges | null = null;

/** Takes the block counts the worker sent (see `blockRanges`). */
export function setBlockRanges(r: BlockRanges): void {
  blockRanges = r;
}

/**
 * The block counts benchmark `b` takes: `[fewest, most]`, null if it has no N-block task, or
 * 'unknown' before the worker sent them.
 */
export function blockRange(b: Benchmark): [number, number] | null | 'unknown' {
  return blockRanges === null ? 'unknown' : blockRanges[b];
}

/**
 * `n` if benchmark `b` has an N-block tower task with `n` blocks, else undefined (its template).
 * Before the counts are known, any whole number from 1 passes (checked again once they are).
 */
export function blocksFor(b: Benchmark, n: number | null | undefined): number | undefined {
  if (n == null || !Number.isInteger(n)) return undefined;
  const r = blockRange(b);
  if (r === 'unknown') return n >= 1 ? n : undefined;
  return r && n >= r[0] && n <= r[1] ? n : undefined;
}

/** The block select's items for benchmark `b`: the template ('') and each allowed count. */
export function blockItems(b: Benchmark): [string, string][] {
  const r = blockRange(b);
  // Says what it is: "template" alone did not read as a block count.
  const items: [string, string][] = [['', 'paper task']];
  if (r && r !== 'unknown') for (let n = r[0]; n <= r[1]; n++) items.push([String(n), `${n} blocks`]);
  return items;
}

export const SPEEDS: [string, string][] = [
  ['0.25', '¼×'],
  ['0.5', '½×'],
  ['1', '1×'],
  ['2', '2×'],
  ['4', '4×'],
  ['8', '8×'],
];

/** Step timings kept for the HUD's mean and the tests (oldest dropped first). */
const MAX_STEP_TIMES = 600;

/** Times of a cancel (ms since the epoch, `performance.timeOrigin` based), for the tests. */
export interface CancelTiming {
  clickedAt: number;
  appliedAt: number;
  repliedAt: number;
}

export interface PageState {
  /** The scenario the session runs. */
  options: Scenario;
  /** Playback speed (simulated seconds per wall-clock second). */
  speed: number;
  /** Whether a freshly opened or reset episode starts playing (`?autoplay=0` turns it off). */
  autoplay: boolean;
  playing: boolean;
  /** Whether to resume playing after the user's drag (it was playing when the drag began). */
  resumeAfterDrag: boolean;
  /** Whether the Run runs a task taught in Teach mode (no permalink restores it). */
  taught: boolean;
  /** The task folder the Run runs instead of a benchmark (null: the benchmark's task). */
  folder: OpenFolder | null;
  /** The folder URL the page was opened with (`?folder=URL`), until it is opened. */
  folderUrl: string | null;
  /** The robot in the arms' place (null: the default, the Panda). */
  robot: RobotPick | null;
  /** Whether the user is dragging a block (the world is paused meanwhile). */
  dragging: boolean;
  /** The latest frame: session status, plan, demo states, facts. */
  frame: Frame | null;
  /** Wall time of the worker's last `Session::step` (ms), and the recent ones. */
  lastStepMs: number;
  stepTimes: number[];
  currentTab: TabId;
  /** The task whose PDDL the editor holds (`taskKey`; null: none loaded yet). */
  editorTask: string | null;
  lastCancel: CancelTiming | null;
}

/** A seed from user text: a whole number >= 0 (anything else is 0). */
export function parseSeed(text: string): number {
  return Math.max(0, Math.floor(Number(text)) || 0);
}

/** The state a page opened at `search` (its URL's query) starts from. Its benchmark, method and
 * mode are taken as written until the catalogue arrives (see `settleChoices`). */
export function initialState(search: string): PageState {
  const params = new URLSearchParams(search);
  const benchmark = (params.get('benchmark') ?? DEFAULTS.benchmark) as Benchmark;
  const blocks = blocksFor(benchmark, params.has('blocks') ? Number(params.get('blocks')) : undefined);
  return {
    options: {
      benchmark,
      method: (params.get('method') ?? DEFAULTS.method) as Method,
      mode: (params.get('mode') ?? DEFAULTS.mode) as Mode,
      seed: parseSeed(params.get('seed') ?? '1'),
      ...(blocks === undefined ? {} : { blocks }),
    },
    speed: Number(params.get('speed') ?? '1') || 1,
    autoplay: params.get('autoplay') !== '0',
    playing: false,
    resumeAfterDrag: false,
    dragging: false,
    taught: false,
    folder: null,
    folderUrl: params.get('folder') || null,
    robot: robotFromUrl(params.get('robot')),
    frame: null,
    lastStepMs: 0,
    stepTimes: [],
    currentTab: 'run',
    editorTask: null,
    lastCancel: null,
  };
}

/** The task the Run runs, as a key: `folder:NAME`, `b1:8` (a generated task) or `b1`. */
export function taskKey(s: PageState): string {
  if (s.folder) return `folder:${s.folder.name}`;
  return s.options.blocks != null ? `${s.options.benchmark}:${s.options.blocks}` : s.options.benchmark;
}

/** Replaces a benchmark, method or mode the catalogue does not list (a mistyped link) by the
 * default. */
export function settleChoices(s: PageState, c: Catalogue): void {
  const o = s.options;
  if (!entryOf(c.benchmarks, o.benchmark)) o.benchmark = DEFAULTS.benchmark;
  if (!entryOf(c.methods, o.method)) o.method = DEFAULTS.method;
  if (!entryOf(c.modes, o.mode)) o.mode = DEFAULTS.mode;
}

/** Records the wall time of one worker step. */
export function recordStep(s: PageState, stepMs: number): void {
  s.lastStepMs = stepMs;
  s.stepTimes.push(stepMs);
  if (s.stepTimes.length > MAX_STEP_TIMES) s.stepTimes.shift();
}

/** Mean of the recent step times (ms; 0 before the first). */
export function meanStepMs(s: PageState): number {
  return s.stepTimes.length ? s.stepTimes.reduce((a, b) => a + b, 0) / s.stepTimes.length : 0;
}

/** Puts the scenario into the address bar (without a new history entry), so a reload or a copied
 * link restores it. */
export function updateUrl(s: PageState): void {
  if (s.taught) return;
  const p = new URLSearchParams();
  if (s.folder) {
    // An uploaded folder has no address: no link restores it (Save keeps it with the run).
    if (!s.folder.url) return history.replaceState(null, '', location.pathname);
    p.set('folder', s.folder.url);
  } else p.set('benchmark', s.options.benchmark);
  p.set('method', s.options.method);
  p.set('mode', s.options.mode);
  p.set('seed', String(s.options.seed));
  if (s.options.blocks != null && !s.folder) p.set('blocks', String(s.options.blocks));
  // A robot folder from this computer has no address: the link names shipped robots only.
  if (s.robot && !s.robot.files) p.set('robot', s.robot.name);
  if (s.speed !== 1) p.set('speed', String(s.speed));
  history.replaceState(null, '', `${location.pathname}?${p}`);
}
