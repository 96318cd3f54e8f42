/**
 * What the panels showed at each recorded moment of the timeline: the Run tab's content (plan,
 * demonstration, facts, replans) as a chain of snapshots made only when it changes, sharing the
 * unchanged lists by reference, and per Moment the status line's numbers. Records die with the
 * Moments they belong to, so they are bounded as the Moments are (history.ts). No DOM.
 */
import type { Frame, Replan } from 'logic-lfd';
import type { History, Moment } from './history';
import { MAX_REPLANS_SHOWN, type FactChange, type RunFrame } from './run-panel';
import { meanStepMs, type PageState } from './state';

/** The Run tab's content from one frame until the next change. */
export interface Snapshot {
  frame: RunFrame;
  /** The newest replans of the episode so far (as many as the tab lists). */
  replans: Replan[];
  /** The last change of the facts. */
  change: FactChange | null;
  /** The plan step executed last. */
  step: number | null;
}

/** A moment's status line: its frame's clock and counters and the page's timings then. */
export interface MomentRecord {
  snap: Snapshot;
  t: number;
  tick: number;
  replans: number;
  stepMs: number;
  meanMs: number;
  playing: boolean;
  dragging: boolean;
}

/** A replan: the plan just before it and the one it made. */
export interface ReplanRecord {
  /** Its time as the timeline marks it. */
  t: number;
  replan: Replan;
  before: string[];
  after: string[];
}

/** Replans kept with their plans (as many as the timeline's markers). */
const MAX_REPLANS = 2000;

const same = (a: readonly string[], b: readonly string[]): boolean => a.length === b.length && a.every((x, i) => x === b[i]);
const sameStates = (a: string[][], b: string[][]): boolean => a.length === b.length && a.every((x, i) => same(x, b[i]));

export class RewindRecorder {
  /** The records of the Moments (a Moment dropped by the history takes its record along). */
  private readonly records = new WeakMap<Moment, MomentRecord>();
  readonly replans: ReplanRecord[] = [];
  private snap: Snapshot | null = null;
  private last: { frame: Frame; rec: MomentRecord } | null = null;
  private prev: { frame: Frame; rec: MomentRecord } | null = null;

  constructor(
    private readonly history: History,
    private readonly state: PageState,
  ) {
    history.listen(() => this.changed());
    this.changed();
  }

  /** What the panels showed at moment `m` (null: recorded before the recorder started). */
  at(m: Moment): MomentRecord | null {
    return this.records.get(m) ?? null;
  }

  /** The replan marked at time `t`, with its plans. */
  replanAt(t: number): ReplanRecord | null {
    for (let i = this.replans.length - 1; i >= 0; i--) if (this.replans[i].t === t) return this.replans[i];
    return null;
  }

  /** Called after every change of the history: a new frame (the page's current one), a mark, a
   * reset or a scrub. */
  private changed(): void {
    const h = this.history;
    if (!h.moments.length) {
      this.snap = this.last = this.prev = null;
      this.replans.length = 0;
    }
    const f = this.state.frame;
    if (f && f !== this.last?.frame && h.moments.length) {
      this.prev = this.last;
      this.last = { frame: f, rec: this.note(f) };
    }
    // The newest Moments are this frame's or the previous one's (a disturbance keeps the frame
    // before it too); older ones were recorded before this recorder started.
    const ms = h.moments;
    for (let i = ms.length - 1; i >= Math.max(0, ms.length - 3); i--) {
      const m = ms[i];
      if (this.records.has(m)) continue;
      const by = [this.last, this.prev].find((x) => x?.frame.world === m.world);
      if (by) this.records.set(m, by.rec);
    }
  }

  /** The record of frame `f`: a new snapshot only when the Run tab's content changed. */
  private note(f: Frame): MomentRecord {
    const s = this.snap;
    const r = f.lastReplan;
    const newReplan = !!r && s?.replans[s.replans.length - 1]?.tick !== r.tick;
    const p = s?.frame;
    const changedRun =
      !p ||
      newReplan ||
      p.executing !== f.executing ||
      p.matchedK !== f.matchedK ||
      p.status.kind !== f.status.kind ||
      p.status.message !== f.status.message ||
      p.lastReplan?.tick !== r?.tick ||
      !same(p.plan, f.plan) ||
      !same(p.facts, f.facts) ||
      !same(p.factsAdded, f.factsAdded) ||
      !same(p.factsRemoved, f.factsRemoved) ||
      !same(p.demo, f.demo) ||
      !sameStates(p.demoStates, f.demoStates);
    if (changedRun) {
      const keep = <T>(old: T | undefined, now: T, eq: (a: T, b: T) => boolean): T => (old !== undefined && eq(old, now) ? old : now);
      const frame: RunFrame = {
        t: f.t,
        tick: f.tick,
        replans: f.replans,
        status: f.status,
        plan: keep(p?.plan, f.plan, same),
        executing: f.executing,
        demo: keep(p?.demo, f.demo, same),
        demoStates: keep(p?.demoStates, f.demoStates, sameStates),
        matchedK: f.matchedK,
        facts: keep(p?.facts, f.facts, same),
        factsAdded: f.factsAdded,
        factsRemoved: f.factsRemoved,
        lastReplan: r,
      };
      if (newReplan) {
        this.replans.push({ t: r.tick * (f.world.dt || 0.01), replan: r, before: p?.plan ?? [], after: frame.plan });
        if (this.replans.length > MAX_REPLANS) this.replans.shift();
      }
      this.snap = {
        frame,
        replans: newReplan ? [...(s?.replans ?? []), r].slice(-MAX_REPLANS_SHOWN) : (s?.replans ?? []),
        change: f.factsAdded.length || f.factsRemoved.length ? { added: f.factsAdded, removed: f.factsRemoved, t: f.t } : (s?.change ?? null),
        step: f.executing ?? s?.step ?? null,
      };
    }
    const st = this.state;
    return { snap: this.snap!, t: f.t, tick: f.tick, replans: f.replans, stepMs: st.lastStepMs, meanMs: meanStepMs(st), playing: st.playing, dragging: st.dragging };
  }
}
