/**
 * One-line explanations of the methods and the multi-goal modes: the tooltips of their selects
 * and options (set once the page is ready: this is a chunk of its own), the help overlay and the
 * Compare view's table.
 */
import type { Method, Mode } from './state';

export const METHOD_NOTES: [Method, string, string][] = [
  ['logic-lfd', 'Logic-LfD', 'Plans with PDDL to the nearest state of the demonstration (any L_k), then follows the rest of it; replans whenever the facts change.'],
  ['linear', 'Linear', 'Replays the demonstrated actions in order, blind to the facts: a changed scene makes an action fail.'],
  ['rlds', 'RLDS', 'Jumps back or forward along the demonstration to the state that matches; never makes a new plan, so an unseen state stops it.'],
  ['tamp', 'TAMP', 'Plans from scratch to the goal G after every change, ignoring the demonstration (slower planning, same robot).'],
];

export const MODE_NOTES: [Mode, string, string][] = [
  ['paper', 'paper', 'As in the paper: the shortest plan to any demonstration state L_k, then the demonstration from k on.'],
  ['prioritised', 'prioritised', 'Minimises the whole: the actions to reach L_k plus the demonstration actions left after k, so the merged plan is never longer than needed.'],
];

/** The one-line explanation of method `m` (or mode). */
export const noteOf = (notes: [string, string, string][], v: string): string => notes.find(([k]) => k === v)?.[2] ?? '';

/** Gives each option of `sel` its one-line explanation as a tooltip, and the select the chosen
 * one's (kept up to date on change). */
function explain(sel: HTMLSelectElement, notes: [string, string, string][], label: string): void {
  for (const o of sel.options) o.title = noteOf(notes, o.value);
  const update = () => (sel.title = `${label}: ${noteOf(notes, sel.value)}`);
  sel.addEventListener('change', update);
  update();
}

/** The tooltips of the method and mode selects. */
export function explainSelects(method: HTMLSelectElement, mode: HTMLSelectElement): void {
  explain(method, METHOD_NOTES, 'Method');
  explain(mode, MODE_NOTES, 'Multi-goal mode');
}
