/**
 * Guidance for a first-time visitor: a hint over the view ("drag a block…") with the task's goal,
 * that stays until it is closed or a block is dragged, and does not come back once dismissed
 * (localStorage). Loaded after the first frame.
 */
import { el } from './dom';

const SEEN_KEY = 'logic-lfd.hint-dismissed';

/** Whether the page is used by touch (a phone, a tablet): the hint then names a tap, not a key. */
const TOUCH = typeof matchMedia === 'function' && matchMedia('(pointer: coarse)').matches;

/** The hint card over the view; `dismiss()` hides it for good. */
export class FirstVisitHint {
  readonly root: HTMLElement;
  private readonly goal = el('span', { id: 'hint-goal' });

  constructor(stage: HTMLElement) {
    const close = el('button', { id: 'hint-close', type: 'button', 'aria-label': 'Close the hint', title: 'Close the hint' }, '✕');
    this.root = el(
      'div',
      { id: 'first-hint', class: 'hint', role: 'note' },
      el('p', {}, el('strong', {}, 'The robot learned this task from one demonstration. '), 'Goal: ', this.goal, '.'),
      el('p', {}, `Drag a block to disturb it: the robot notices, replans in milliseconds and still finishes. ${TOUCH ? 'Tap' : 'Press'} ? for help.`),
      close,
    );
    close.onclick = () => this.dismiss();
    this.root.hidden = readSeen();
    stage.append(this.root);
  }

  setGoal(words: string): void {
    this.goal.textContent = words;
  }

  /** The episode finished while the hint is still read: offer to watch it again (`again`). */
  ended(again: () => void): void {
    if (this.root.hidden || this.root.querySelector('#hint-again')) return;
    const b = el('button', { id: 'hint-again', type: 'button', class: 'primary' }, '▶ Watch again');
    b.onclick = () => {
      b.parentElement?.remove();
      again();
    };
    this.root.append(el('p', {}, 'Done. ', b, ' and drag a block while the robot works.'));
  }

  dismiss(): void {
    this.root.hidden = true;
    try {
      localStorage.setItem(SEEN_KEY, '1');
    } catch {
      /* private mode: it shows again next time */
    }
  }
}

function readSeen(): boolean {
  try {
    return localStorage.getItem(SEEN_KEY) === '1';
  } catch {
    return false;
  }
}
