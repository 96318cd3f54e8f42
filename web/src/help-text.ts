/**
 * The help overlay's explanations (loaded when the help first opens, not with the page): the
 * disturbance levels L1–L4, the methods, the multi-goal modes, and the symbols L_k and S_C.
 */
import { el } from './dom';
import { METHOD_NOTES, MODE_NOTES } from './explain';
import { LEVELS } from './state';

const SYMBOLS: [string, string][] = [
  ['S_C', 'the current facts: what the scene graph reads off the geometry now, e.g. (on a b), (clear a). The Run tab lists them.'],
  ['L_0 … L_N', 'the states of the demonstration: L_0 is where it started, L_k the facts after its k-th action, L_N the end. The Run tab shows them in order.'],
  ['joined at L_k', 'after a disturbance the robot plans the shortest way to any state L_k of the demonstration, then follows the demonstration from k on; the highlighted L_k is the one it joined.'],
  ['G', 'the goal of the task (stated above the plan in the Run tab).'],
];

function section(title: string, rows: [string, string][]): HTMLElement {
  return el(
    'section',
    { class: 'help-section' },
    el('h3', {}, title),
    el('dl', {}, ...rows.flatMap(([k, v]) => [el('dt', {}, k), el('dd', {}, v)])),
  );
}

/** The explanations, as one element to put in the help dialog. */
export function helpExplanations(): HTMLElement {
  return el(
    'div',
    { id: 'help-explain', class: 'help-explain' },
    section(
      'Disturbances (buttons L1–L4, keys 1–4)',
      LEVELS.map(([, name, what]) => [name, `${what}.`]),
    ),
    section('Methods (the method select)', METHOD_NOTES.map(([, name, what]) => [name, what])),
    section('Logic-LfD modes (the mode select)', MODE_NOTES.map(([, name, what]) => [name, what])),
    section('Symbols', SYMBOLS),
  );
}
