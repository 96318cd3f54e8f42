/**
 * Rewinds the panels with the timeline: while a past moment is viewed, the status line, the clock
 * and the Run tab (plan, demonstration, facts, replans with "why L_k?") show what they showed then,
 * dimmed under a note; a replan marker's click adds the plan before and after that replan. Play
 * (the timeline back at live) redraws the live frame. Loaded with the timeline, after the first frame.
 */
import './rewind.css';
import { el, lk } from './dom';
import type { History, Moment } from './history';
import type { Layout } from './layout';
import { RewindRecorder, type MomentRecord, type ReplanRecord } from './rewind-record';
import { RunPanel } from './run-panel';
import type { PageState } from './state';
import { frameTexts, type StatusBar } from './status-bar';

export interface RewindParts {
  history: History;
  state: PageState;
  ui: Pick<Layout, 'stage' | 'run'>;
  status: StatusBar;
  /** The live Run tab. */
  run: RunPanel;
}

export class Rewind {
  readonly recorder: RewindRecorder;
  private readonly panel: HTMLElement;
  private readonly note: HTMLElement;
  /** The next replan after the viewed moment: a button showing its plans (the markers' keyboard way). */
  private readonly next: HTMLElement;
  private readonly diff: HTMLElement;
  /** The moment drawn (undefined: live). */
  private shown: Moment | null | undefined = undefined;
  /** The moment the replan's plans were shown at (they go when another is viewed). */
  private diffAt: Moment | null = null;

  constructor(private readonly p: RewindParts) {
    this.recorder = new RewindRecorder(p.history, p.state);
    this.panel = p.ui.run.plan.closest<HTMLElement>('.panel') ?? p.ui.run.plan.parentElement!;
    this.note = el('p', { id: 'rewind-note', class: 'rw-note', role: 'status', 'aria-live': 'polite', hidden: '' });
    this.diff = el('section', { id: 'rewind-replan', class: 'rw-replan', 'aria-label': 'The plan before and after the replan', hidden: '' });
    this.next = el('p', { id: 'rewind-next', class: 'rw-next', hidden: '' });
    this.panel.prepend(this.note, this.next);
    p.ui.run.plan.after(this.diff);
    p.ui.stage.root.addEventListener('click', (e) => this.clicked(e.target as HTMLElement));
    p.history.listen(() => this.update());
    window.lfd.rewind = () => this.usage();
  }

  /** What the record holds now: Moments with a record, the snapshots and plan lists they share. */
  private usage(): { moments: number; recorded: number; snapshots: number; plans: number; replans: number } {
    const ms = this.p.history.moments;
    const recs = ms.map((m) => this.recorder.at(m)).filter((r) => r !== null);
    const snaps = new Set(recs.map((r) => r.snap));
    const plans = new Set([...snaps].map((s) => s.frame.plan)).size;
    return { moments: ms.length, recorded: recs.length, snapshots: snaps.size, plans, replans: this.recorder.replans.length };
  }

  private update(): void {
    const h = this.p.history;
    const m = h.viewing === null ? undefined : h.at(h.viewing);
    if (m === this.shown) return;
    this.shown = m;
    if (m === undefined) this.live();
    else this.past(m);
    if (!this.diff.hidden && this.diffAt !== m) this.hideReplan();
  }

  /** Back to live: the live frame drawn again in full. */
  private live(): void {
    this.setPast(false);
    this.note.textContent = '';
    this.next.hidden = true;
    this.drawLive();
  }

  private drawLive(): void {
    const { state, status, run } = this.p;
    if (!state.frame) return;
    status.showFrame(state.frame, state);
    run.invalidate();
    run.show(state.frame);
  }

  /** Moment `m`: the panels as they were, under a note saying so. */
  private past(m: Moment | null): void {
    const rec = m && this.recorder.at(m);
    this.setPast(true);
    this.note.dataset.t = m ? m.t.toFixed(2) : '';
    if (!m || !rec) {
      this.note.textContent = 'Viewing a moment from before the panels were recorded: they show the live run. Play returns to live.';
      this.drawLive();
      this.offerNext(m);
      return;
    }
    this.note.textContent = `Viewing t = ${m.t.toFixed(2)} s — Play returns to live`;
    this.draw(rec);
    this.offerNext(m);
  }

  /** A button for the first replan after moment `m`: jumps there and shows its plans. */
  private offerNext(m: Moment | null): void {
    const r = m && this.recorder.replans.find((x) => x.t > m.t);
    this.next.hidden = !r;
    if (!r) return this.next.replaceChildren();
    const b = el('button', { type: 'button', class: 'link' }, `Next replan at t = ${r.t.toFixed(2)} s: its plans before and after`);
    b.addEventListener('click', () => this.jump(r.t, r.replan.reason));
    this.next.replaceChildren(b);
  }

  private draw(rec: MomentRecord): void {
    const { status, run, ui, state } = this.p;
    const [text, hud] = frameTexts(
      { status: rec.snap.frame.status, t: rec.t, tick: rec.tick, replans: rec.replans },
      { playing: rec.playing, dragging: rec.dragging, lastStepMs: rec.stepMs },
      rec.meanMs,
    );
    status.show(rec.snap.frame.status.kind, text);
    ui.stage.hud.textContent = hud;
    // A panel of its own, so the live one keeps what the frames left it; an open "why L_k?" stays open.
    const p = new RunPanel(ui.run, () => state.options.mode);
    p.replans = [...rec.snap.replans];
    p.lastChange = rec.snap.change;
    p.lastStep = rec.snap.step;
    p.whyOpen = run.whyOpen;
    p.why = run.why;
    p.show(rec.snap.frame);
  }

  private setPast(on: boolean): void {
    this.note.hidden = !on;
    this.panel.classList.toggle('rw-rewound', on);
    this.p.ui.stage.root.classList.toggle('rw-rewound', on);
  }

  /** A replan marker's click: its time and plans. */
  private clicked(target: HTMLElement): void {
    if (!target.matches('.tl-mark[data-kind="replan"]')) return;
    const mark = [...this.p.history.marks].reverse().find((m) => m.kind === 'replan' && m.t.toFixed(2) === target.dataset.t);
    if (mark) this.jump(mark.t, mark.text);
  }

  /** Goes to the replan at time `t` (as a drag of the scrubber there would: the run pauses) and
   * adds its plans and `reason` to the Run tab. */
  private jump(t: number, reason: string): void {
    const h = this.p.history;
    const range = document.querySelector<HTMLInputElement>('#timeline-range');
    if (!range) return;
    range.value = String(t);
    range.dispatchEvent(new Event('input'));
    // The scrubber rounds to its step: the view goes to the replan's own time.
    h.view(Math.min(t, h.end));
    const rec = this.recorder.replanAt(t);
    this.diff.replaceChildren(
      ...(rec ? replanDiff(rec) : [el('p', { class: 'muted small' }, `Replan at t = ${t.toFixed(2)} s: ${reason} (recorded before the panels were).`)]),
    );
    this.diff.hidden = false;
    // The button would offer this replan again.
    this.next.hidden = true;
    this.diffAt = this.shown ?? null;
  }

  private hideReplan(): void {
    this.diff.hidden = true;
    this.diff.replaceChildren();
  }
}

/** The two plans of a replan: actions it dropped struck out, actions it added tagged new. */
export function replanDiff(rec: ReplanRecord): HTMLElement[] {
  const { replan: r, before, after } = rec;
  const left = counts(after);
  const beforeItems = before.map((a) => {
    if (take(left, a)) return el('li', {}, a);
    return el('li', { class: 'rw-removed' }, el('del', {}, a), el('span', { class: 'rw-tag removed' }, 'removed'));
  });
  const old = counts(before);
  const afterItems = after.map((a) => {
    if (take(old, a)) return el('li', {}, a);
    return el('li', { class: 'rw-new' }, el('span', { class: 'rw-tag new' }, 'new'), a);
  });
  const list = (label: string, items: HTMLElement[]) =>
    el('div', { class: 'rw-plan' }, el('h3', {}, label), el('ol', { class: 'plan-list', 'aria-label': label }, ...(items.length ? items : [el('li', { class: 'muted' }, 'empty')])));
  const joined = r.k != null ? [', joined ', lk(r.k), ` (${r.newActions} new actions)`] : [];
  return [
    el('p', { class: 'rw-reason' }, el('strong', {}, `Replan at t = ${rec.t.toFixed(2)} s`), `: ${r.reason} — ${r.timeMs.toFixed(2)} ms`, ...joined),
    el('div', { class: 'rw-plans' }, list(`Plan before (${before.length})`, beforeItems), list(`Plan after (${after.length})`, afterItems)),
  ];
}

/** How often each action occurs. */
function counts(xs: string[]): Map<string, number> {
  const m = new Map<string, number>();
  for (const x of xs) m.set(x, (m.get(x) ?? 0) + 1);
  return m;
}

/** Takes one `x` from `m`; false when none is left. */
function take(m: Map<string, number>, x: string): boolean {
  const n = m.get(x) ?? 0;
  if (n) m.set(x, n - 1);
  return n > 0;
}
