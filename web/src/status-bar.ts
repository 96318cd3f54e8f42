/**
 * The stage's overlays: the status line (planning / executing / replanning / done / failed, with
 * Cancel enabled while a plan runs), the clock and timings, and short notices that fade.
 */
import type { Frame } from 'logic-lfd';
import type { Stage } from './layout';
import { meanStepMs, type PageState } from './state';

/** What the status line and the clock say of a frame (live, or a recorded moment's). */
export function frameTexts(f: Pick<Frame, 'status' | 't' | 'tick' | 'replans'>, s: Pick<PageState, 'playing' | 'dragging' | 'lastStepMs'>, mean: number): [string, string] {
  const k = f.status.kind;
  // A reopened episode waits for Play: "planning" would promise work that is not happening.
  const waiting = k === 'planning' && !s.playing && !s.dragging;
  const replans = `${f.replans} replan${f.replans === 1 ? '' : 's'}`;
  const text = f.status.message || k;
  const budget = k === 'failed' && text.includes('budget exhausted') ? ' (stopped at a budget, not proved unsolvable)' : '';
  return [
    waiting ? 'paused: press Play (Space) to go on' : text + budget,
    `t = ${f.t.toFixed(2)} s · tick ${f.tick} · step ${s.lastStepMs.toFixed(2)} ms (mean ${mean.toFixed(2)}) · ${replans}`,
  ];
}

/** How long a notice stays (ms). */
const NOTICE_MS = { info: 3500, error: 6000 };

export class StatusBar {
  private noticeTimer = 0;

  constructor(private readonly ui: Stage) {}

  /** Shows a status of `kind` (a CSS class: idle, planning, executing, done, failed…). */
  show(kind: string, text: string): void {
    this.ui.status.className = `status ${kind}`;
    this.ui.status.dataset.kind = kind;
    this.ui.statusText.textContent = text;
  }

  /** Marks the status failed with `text` (the frame's kind stays in `data-kind`). */
  fail(text: string): void {
    this.ui.status.className = 'status failed';
    this.ui.statusText.textContent = text;
  }

  /** Replaces the status text only. */
  say(text: string): void {
    this.ui.statusText.textContent = text;
  }

  /** The status, Cancel and the clock of a frame. */
  showFrame(f: Frame, s: PageState): void {
    const k = f.status.kind;
    const [text, hud] = frameTexts(f, s, meanStepMs(s));
    this.show(k, text);
    // Cancel appears with the first session's frame: before it there is nothing to cancel.
    this.ui.cancelBtn.hidden = false;
    this.ui.cancelBtn.disabled = !(k === 'planning' || k === 'executing' || k === 'replanning');
    this.ui.hud.textContent = hud;
  }

  /** A search runs inside the worker's step: which method's, how far it got, and Cancel. */
  searching(method: string, expanded: number, ms: number): void {
    this.show('planning', `${method} searching: ${expanded.toLocaleString('en')} states expanded · ${(ms / 1000).toFixed(1)} s`);
    this.ui.cancelBtn.disabled = false;
  }

  /** A short message over the view; errors stay longer (`ms`: how long, when not the default). */
  notice(text: string, kind: 'info' | 'error', ms = NOTICE_MS[kind]): void {
    const n = this.ui.notice;
    n.textContent = text;
    n.className = `notice ${kind}`;
    n.hidden = false;
    clearTimeout(this.noticeTimer);
    this.noticeTimer = window.setTimeout(() => (n.hidden = true), ms);
  }
}
