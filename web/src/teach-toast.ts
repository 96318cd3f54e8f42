/**
 * The toast over the 3-D view that says what a drop (or an Undo) just recorded: the actions and
 * their net fact change, e.g. "a3 (pick panda c) · a4 (stack panda c d)  + (on c d) − (ontable c)".
 * It sits over the view so that the answer is where the eyes are, also on a phone.
 */
import type { Segment } from 'logic-lfd';
import { el, factChips } from './dom';
import { netChange } from './teach-moves';

/** How long a toast stays (ms). */
const SHOW_MS = 7000;

export class MoveToast {
  readonly root = el('div', { id: 'teach-toast', class: 'teach-toast', role: 'status', 'aria-live': 'polite', hidden: '' });
  private timer = 0;

  constructor(stage: HTMLElement) {
    stage.append(this.root);
  }

  /** Shows the actions just recorded (`kind` 'recorded') or undone. */
  show(segs: readonly Segment[], kind: 'recorded' | 'undone'): void {
    if (!segs.length) return this.hide();
    const sorted = [...segs].sort((a, b) => a.index - b.index);
    const change = netChange(sorted);
    const names = sorted.map((s) => `a${s.index + 1} ${s.action}`).join(' · ');
    // Undone: the world goes back, so the change is shown reversed.
    const chips = kind === 'recorded' ? factChips(change.added, change.removed) : factChips(change.removed, change.added);
    this.root.replaceChildren(
      el('div', { class: 'teach-toast-title' }, kind === 'recorded' ? 'Recorded ' : 'Undone ', el('span', { class: 'teach-toast-acts' }, names)),
      el('div', { class: 'teach-toast-facts' }, ...(chips.length ? chips : [el('span', { class: 'muted' }, 'facts unchanged (only positions moved)')])),
    );
    this.root.dataset.kind = kind;
    this.root.hidden = false;
    window.clearTimeout(this.timer);
    this.timer = window.setTimeout(() => this.hide(), SHOW_MS);
  }

  hide(): void {
    window.clearTimeout(this.timer);
    this.root.hidden = true;
  }
}
