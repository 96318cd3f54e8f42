/**
 * The episode's history on the page side: recorded frames (what the 3-D view needs to show a past
 * moment) and the markers of disturbances and replans, shared by the timeline and the charts.
 * No DOM: the timeline and the charts read it and listen for changes.
 */
import type { EePoint, Frame, Level, WorldSnapshot } from 'logic-lfd';

/** What a marker stands for: a user's drag, an injected disturbance (L1–L4) or a replan. */
export type MarkKind = 'drag' | Level | 'replan';

export interface Mark {
  kind: MarkKind;
  /** Simulated time (s). */
  t: number;
  /** What happened (the tooltip). */
  text: string;
  /** A replan's planning time (ms). */
  ms?: number;
}

/** One recorded moment: enough to draw the 3-D view as it was. */
export interface Moment {
  t: number;
  world: WorldSnapshot;
  ee: EePoint[];
}

/** The colour of each kind of marker, the same in the timeline and the charts (a new level needs
 * one: the type asks for it). */
export const MARK_COLOURS: Record<MarkKind, string> = {
  drag: '#e6e6e6',
  l1: '#4cc38a',
  l2: '#3e9bff',
  l3: '#e5484d',
  l4: '#c77dff',
  replan: '#ffb224',
};

/** Simulated seconds between recorded moments (more often only around a disturbance). */
const RECORD_EVERY = 0.1;
/** Moments kept (240 s at 10 per second); the oldest are dropped first. */
const MAX_MOMENTS = 2400;
/** Markers kept; the oldest are dropped first. */
const MAX_MARKS = 2000;

export class History {
  readonly moments: Moment[] = [];
  readonly marks: Mark[] = [];
  /** The simulated time shown in the view when scrubbed back (null: live). */
  viewing: number | null = null;
  private last: Frame | null = null;
  private lastKept = -Infinity;
  private lastReplanKey = '';
  private readonly listeners = new Set<() => void>();

  /** Calls `f` after every change (a new moment or marker, a reset, a scrub). */
  listen(f: () => void): () => void {
    this.listeners.add(f);
    return () => this.listeners.delete(f);
  }

  private changed(): void {
    for (const f of this.listeners) f();
  }

  /** The latest simulated time seen (0 before the first frame). */
  get end(): number {
    return this.last?.t ?? 0;
  }

  /** Forgets everything (a new episode begins). */
  reset(): void {
    this.moments.length = 0;
    this.marks.length = 0;
    this.last = null;
    this.lastKept = -Infinity;
    this.lastReplanKey = '';
    this.viewing = null;
    this.changed();
  }

  /** Records a frame of the live session. */
  push(f: Frame): void {
    if (this.last && f.t < this.last.t) this.reset();
    this.last = f;
    const r = f.lastReplan;
    if (r) {
      const key = `${r.tick}:${r.reason}`;
      if (key !== this.lastReplanKey) {
        this.lastReplanKey = key;
        this.addMark({ kind: 'replan', t: r.tick * (f.world.dt || 0.01), text: r.reason, ms: r.timeMs });
      }
    }
    if (f.t >= this.lastKept + RECORD_EVERY) this.keep(f);
    this.changed();
  }

  /** Marks a disturbance at frame `before`'s time: that frame is kept (the world just before it)
   * and so is `after` (the world it made). */
  mark(kind: Exclude<MarkKind, 'replan'>, text: string, before: Frame | null, after: Frame): void {
    if (before && this.moments[this.moments.length - 1]?.world !== before.world && before.t <= after.t) this.keep(before);
    this.addMark({ kind, t: after.t, text });
    this.last = after;
    this.keep(after);
    this.changed();
  }

  /** The moment shown at time `t`: the last one recorded at or before it (the first if none). */
  at(t: number): Moment | null {
    const m = this.moments;
    if (!m.length) return null;
    let lo = 0;
    let hi = m.length - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (m[mid].t <= t) lo = mid;
      else hi = mid - 1;
    }
    return m[lo];
  }

  /** Shows time `t` instead of the live session (null: back to live). */
  view(t: number | null): void {
    this.viewing = t;
    this.changed();
  }

  private keep(f: Frame): void {
    this.moments.push({ t: f.t, world: f.world, ee: f.ee });
    this.lastKept = f.t;
    if (this.moments.length > MAX_MOMENTS) this.moments.shift();
  }

  private addMark(m: Mark): void {
    this.marks.push(m);
    if (this.marks.length > MAX_MARKS) this.marks.shift();
  }
}
