/**
 * The disturbances a comparison applies: one scripted injection (level and time), or the Run's
 * recorded ones — the user's drags, L1–L4 injections and cancels, read from the Run's episode log
 * and applied at the same ticks to every method, as `Session.replay` applies them.
 */
import type { Frame, Level, SessionOptions, WorldSnapshot } from 'logic-lfd';
import type { WorkerClient } from './client';
import type { Vec3 } from './protocol';
import { levelName, withLevel } from './catalogue';

/** One external event of the episode log (`EpisodeLog.events`, the CLI's snake_case JSON). */
export type LoggedEvent =
  | { event: 'perturb'; tick: number; body: string; position: Vec3 }
  | { event: 'inject'; tick: number; level: Level; description: string }
  | { event: 'cancel'; tick: number };

/** A disturbance of a comparison: when, what (in words), and how to apply it to a session. */
export interface Disturbance {
  /** The tick before which it happens, in a world ticking `dt` seconds. */
  tickAt(dt: number): number;
  label: string;
  /** Applies it to `client`'s session; what it did, or why it was not applied. */
  apply(client: WorkerClient): Promise<string>;
  /** Whether it still applies after the episode ended (a recorded drag after the Run's end was
   * made to a finished episode too); else it is skipped. */
  afterEnd: boolean;
}

/** The Run's recorded episode: its options, initial scene, tick length and events. */
export interface Recorded {
  options: Pick<SessionOptions, 'benchmark' | 'seed' | 'blocks' | 'skill'>;
  /** The initial world (scene JSON), so every method starts where the Run started. */
  scene: string;
  /** Simulated seconds per tick. */
  dt: number;
  events: LoggedEvent[];
}

interface EpisodeLog {
  options: SessionOptions;
  scene: WorldSnapshot;
  demo_json?: string | null;
  events: LoggedEvent[];
}

/** The Run's recorded disturbances from its episode log, or the one-line reason why there is
 * nothing to replay. */
export function recordedOf(episodeJson: string): Recorded | string {
  const log = JSON.parse(episodeJson) as EpisodeLog;
  if (log.demo_json) return 'The Run’s recorded disturbances: not available, the Run plays a taught demonstration and Compare runs the benchmark’s task.';
  if (!log.events.length) return 'The Run’s recorded disturbances: none yet (drag a block, inject a disturbance or cancel in the Run first).';
  const { benchmark, seed, blocks, skill } = log.options;
  return {
    options: { benchmark, seed, skill, ...(blocks != null ? { blocks } : {}) },
    scene: JSON.stringify(log.scene),
    dt: log.scene.dt || 0.01,
    events: log.events,
  };
}

/** The time of `tick` in words (simulated seconds). */
const at = (tick: number, dt: number) => `${(tick * dt).toFixed(2)} s`;

/** What a logged event is, in words: "drag a at 3.20 s", "L3 at 0.50 s", "cancel at 1.00 s". */
export function eventLabel(e: LoggedEvent, dt: number): string {
  if (e.event === 'perturb') return `drag ${e.body} at ${at(e.tick, dt)}`;
  if (e.event === 'inject') return `${levelName(e.level)} at ${at(e.tick, dt)}`;
  return `cancel at ${at(e.tick, dt)}`;
}

/** An injection of `level`; a refused one says why. */
async function inject(client: WorkerClient, level: Level): Promise<string> {
  try {
    return withLevel(level, (await client.call('inject', { level })).message);
  } catch (e) {
    return `not injected: ${(e as Error).message}`;
  }
}

/** The recorded events as disturbances, in their order. */
export function recordedDisturbances(r: Recorded): Disturbance[] {
  return r.events.map((e) => {
    const label = eventLabel(e, r.dt);
    const apply = async (client: WorkerClient): Promise<string> => {
      if (e.event === 'inject') return inject(client, e.level);
      if (e.event === 'cancel') {
        await client.call('cancel', {});
        return 'plan dropped';
      }
      const o = await client.call('perturb', { body: e.body, position: e.position });
      return o.ok ? o.message : `not applied: ${o.reason}`;
    };
    return { tickAt: () => e.tick, label, apply, afterEnd: true };
  });
}

/** One scripted injection of `level` at `seconds` of simulated time. */
export function scriptedDisturbance(level: Level, seconds: number): Disturbance {
  // The same whole ticks as `Session.step(seconds)` advances; no label: the comparison's note
  // names the level and time of its one disturbance.
  return { tickAt: (dt) => Math.floor(seconds / dt + 1e-9), label: '', apply: (c) => inject(c, level), afterEnd: false };
}

const finished = (f: Frame) => f.status.kind === 'done' || f.status.kind === 'failed';

/** Steps `f`'s session up to each disturbance's tick and applies it; the frame after the last one
 * and what each did ("label: outcome"). */
export async function applyAll(client: WorkerClient, f: Frame, list: Disturbance[]): Promise<{ frame: Frame; notes: string[] }> {
  const notes: string[] = [];
  const note = (d: Disturbance, what: string) => notes.push(d.label ? `${d.label}: ${what}` : what);
  const dt = f.world.dt || 0.01;
  for (const d of list) {
    const tick = d.tickAt(dt);
    if (!finished(f) && tick > f.tick) f = await client.call('step', { dt: (tick - f.tick) * dt });
    if (finished(f) && f.tick < tick) {
      if (!d.afterEnd) {
        note(d, `not injected: the episode ended at ${f.t.toFixed(2)} s`);
        continue;
      }
      note(d, `applied at ${f.t.toFixed(2)} s, when the episode had ended: ${await d.apply(client)}`);
    } else note(d, await d.apply(client));
    f = (await client.call('pause', {})) ?? f;
  }
  return { frame: f, notes };
}
