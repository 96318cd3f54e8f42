/**
 * Guidance for a first-time visitor: the goal of the current task in words (from the problem's
 * `:goal`, or for a generated tower from the demonstration's last state), and a hint over the
 * view ("drag a block…") that stays until it is closed or a block is dragged, and does not come
 * back once dismissed (localStorage).
 */
import { el } from './dom';

const SEEN_KEY = 'logic-lfd.hint-dismissed';

/** Whether the page is used by touch (a phone, a tablet): the hint then names a tap, not a key. */
const TOUCH = typeof matchMedia === 'function' && matchMedia('(pointer: coarse)').matches;

/** The facts inside a problem's `(:goal …)`, as `(pred arg …)` strings. */
export function goalFacts(problem: string): string[] {
  const i = problem.indexOf(':goal');
  if (i < 0) return [];
  return [...problem.slice(i).matchAll(/\((?!and\b|or\b|not\b)[a-z][\w-]*(?:\s+[\w-]+)*\)/gi)].map((m) => m[0].replace(/\s+/g, ' '));
}

/** One fact in words: `(on a b)` → "a on b", `(onshelf a)` → "a on the shelf". */
export function factWords(fact: string): string {
  const [p, ...args] = fact.slice(1, -1).split(' ');
  if ((p === 'on' || p === 'on-block') && args.length === 2) return `${args[0]} on ${args[1]}`;
  if (p === 'onshelf' && args.length === 1) return `${args[0]} on the shelf`;
  if ((p === 'ontable' || p === 'on-table') && args.length === 1) return `${args[0]} on the table`;
  if (p === 'at' && args.length === 2) return `${args[0]} at ${args[1]}`;
  return fact;
}

/** The goal in words: "a on b, b on c and c on d". */
export function goalWords(facts: string[]): string {
  const w = facts.map(factWords);
  return w.length > 1 ? `${w.slice(0, -1).join(', ')} and ${w[w.length - 1]}` : (w[0] ?? '');
}

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
