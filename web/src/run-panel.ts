/**
 * The Run tab: the current plan (done / current / ahead), the demonstration's states L0..LN and
 * actions with the state the robot joined, the current facts S_C with the last change, and the
 * last replan. Redrawn only when what it shows changed.
 */
import type { Frame, Mode, Replan } from 'logic-lfd';

import { demoStateItem, el, factChips, lk } from './dom';
import type { RunLists } from './layout';

/** Replans listed under the plan (the newest). */
export const MAX_REPLANS_SHOWN = 6;

/** What the tab draws of a frame: all of it but the world (a recorded moment has no more). */
export type RunFrame = Omit<Frame, 'world' | 'ee'>;

type WhyJoin = typeof import('./why-join');

/** The last change of the facts: kept on screen until the next one. */
export interface FactChange {
  added: string[];
  removed: string[];
  t: number;
}

/** The fields up to `why` are what earlier frames left and what is open: the timeline's rewind
 * sets them on a panel of its own to draw a recorded moment. */
export class RunPanel {
  private lastKey = '';
  lastChange: FactChange | null = null;
  /** The plan step being executed in the latest frame that executed one (the failed step). */
  lastStep: number | null = null;
  /** The episode's replans so far (the frame carries the last one only). */
  replans: Replan[] = [];
  /** The tick of the replan whose "why L_k?" panel is open. */
  whyOpen: number | null = null;
  /** The panel's chunk, once loaded. */
  why: WhyJoin | null = null;

  constructor(
    private readonly ui: RunLists,
    private readonly mode: () => Mode = () => 'paper',
  ) {}

  /** Forgets what was drawn, so the next frame redraws the lists. */
  invalidate(): void {
    this.lastKey = '';
  }

  /** A new episode: forgets the last change and step too. */
  restart(): void {
    this.invalidate();
    this.lastChange = null;
    this.lastStep = null;
    this.replans = [];
    this.whyOpen = null;
  }

  /** Notes what frame `f` changed (its replan, its facts' change, its step). Called with every
   * frame: `show` draws only the latest of an animation frame, and a replan or change carried by
   * a frame drawn over would be lost. */
  record(f: RunFrame): void {
    if (f.factsAdded.length || f.factsRemoved.length) this.lastChange = { added: f.factsAdded, removed: f.factsRemoved, t: f.t };
    if (f.executing != null) this.lastStep = f.executing;
    const r = f.lastReplan;
    if (r && this.replans[this.replans.length - 1]?.tick !== r.tick) this.replans.push(r);
  }

  /** Draws frame `f` (after `record`). */
  show(f: RunFrame): void {
    const key = JSON.stringify([f.plan, f.executing, f.demo.length, f.matchedK, f.facts, f.lastReplan?.tick, f.status.kind, this.lastChange?.t]);
    if (key === this.lastKey) return;
    this.lastKey = key;
    this.showPlan(f);
    this.showDemo(f);
    this.showFacts(f);
  }

  private showPlan(f: RunFrame): void {
    const list = this.ui.plan;
    this.ui.planCount.textContent = f.plan.length ? `${f.plan.length} actions` : '';
    const done = stepsDone(f);
    const failed = f.status.kind === 'failed' ? this.lastStep : null;
    list.replaceChildren(
      ...f.plan.map((a, i) => {
        const cls = i === failed ? 'failed' : f.executing === i ? 'current' : i < done ? 'done' : '';
        const li = el('li', { class: cls, 'aria-current': f.executing === i ? 'step' : 'false' }, a);
        if (i === failed) li.title = f.status.message;
        return li;
      }),
    );
    if (!f.plan.length) list.append(el('li', { class: 'muted empty' }, 'no plan yet'));
    // Scroll the panel only: scrollIntoView also scrolls the window when the page is taller than
    // it, which moves the controls away from under the pointer while the plan advances.
    const cur = list.querySelector<HTMLElement>('.current');
    const box = cur?.closest<HTMLElement>('.panel');
    if (cur && box) {
      const c = cur.getBoundingClientRect();
      const b = box.getBoundingClientRect();
      if (c.top < b.top) box.scrollTop -= b.top - c.top;
      else if (c.bottom > b.bottom) box.scrollTop += c.bottom - b.bottom;
    }
  }

  private showDemo(f: RunFrame): void {
    const k = f.matchedK ?? null;
    const at = demoPosition(f);
    this.ui.matched.replaceChildren(...(k == null ? [] : ['joined at ', lk(k), ...(at != null && at !== k ? [', now at ', lk(at)] : [])]));
    const items: HTMLElement[] = [];
    f.demoStates.forEach((facts, i) => {
      items.push(demoStateItem(i, facts, `demo-state${k === i ? ' matched' : ''}${at === i ? ' at' : ''}`));
      if (i < f.demo.length) items.push(el('li', { class: `demo-action${k != null && i >= k ? ' ahead' : ''}` }, `a${i + 1} ${f.demo[i]}`));
    });
    this.ui.demo.replaceChildren(...items);
  }

  private showFacts(f: RunFrame): void {
    const added = new Set(f.factsAdded);
    this.ui.facts.replaceChildren(...f.facts.map((x) => el('li', { class: added.has(x) ? 'added' : '' }, x)));
    const c = this.lastChange;
    this.ui.factsDiff.replaceChildren(
      ...(c ? [el('span', { class: 'muted small' }, `last change at ${c.t.toFixed(1)} s:`), ...factChips(c.added, c.removed)] : []),
    );
    this.showReplans();
  }

  /** Every replan of the episode, newest first: why, how long, which L_k it joined, and for
   * Logic-LfD a "why L_k?" button opening the candidates its search weighed. */
  private showReplans(): void {
    this.ui.replanInfo.replaceChildren(
      ...[...this.replans]
        .reverse()
        .slice(0, MAX_REPLANS_SHOWN)
        .flatMap((r, i) => {
          const joined = () => (r.k != null ? lk(r.k) : 'G');
          const joins = r.k != null || r.alternatives?.some((a) => a.status === 'joined');
          const line = el(
            'div',
            { class: i === 0 ? 'replan last' : 'replan' },
            `${i === 0 ? 'Last replan' : 'Replan'} at tick ${r.tick}: ${r.reason} — ${r.timeMs.toFixed(2)} ms`,
            ...(joins ? [', joined ', joined(), ` (${r.newActions} new actions)`] : []),
            r.fallback ? ', no skeleton joining the demo bound: planned to G from scratch (TAMP fallback)' : '',
          );
          if (!joins || !r.alternatives?.length) return [line];
          const open = this.whyOpen === r.tick;
          const btn = el('button', { class: 'why-btn link', type: 'button', 'aria-expanded': String(open) }, 'why ', joined(), '?');
          btn.addEventListener('click', () => void this.toggleWhy(r.tick));
          line.append(' ', btn);
          return open && this.why ? [line, this.why.whyJoinPanel(r, this.mode())] : [line];
        }),
    );
  }

  private async toggleWhy(tick: number): Promise<void> {
    this.whyOpen = this.whyOpen === tick ? null : tick;
    if (this.whyOpen != null && !this.why) this.why = await import('./why-join');
    this.showReplans();
  }
}

/** How many leading steps of the plan are finished (all of them once the goal holds). */
function stepsDone(f: RunFrame): number {
  if (f.status.kind === 'done') return f.plan.length;
  return f.executing ?? 0;
}

/** The demonstration state the robot is at on its way: L_k once the new prefix is done, then one
 * further per demonstration action executed (null without a joined state). */
function demoPosition(f: RunFrame): number | null {
  const k = f.matchedK;
  if (k == null) return null;
  const prefix = f.plan.length - (f.demo.length - k);
  return Math.min(f.demo.length, k + Math.max(0, stepsDone(f) - prefix));
}
