/**
 * The help overlay's content (loaded when the help first opens, not with the page): what the page
 * shows, the disturbance levels L1–L4, the methods, the multi-goal modes and the benchmarks (from
 * the catalogue), the symbols L_k and S_C, the keyboard shortcuts, and links to the project's documentation (the repository's
 * docs/*.md, which the build copies beside the page: see vite.config.ts).
 */
import type { Catalogue, CatalogueEntry } from 'logic-lfd';
import { el } from './dom';

const KEYS: [string, string][] = [
  ['Space', 'play / pause'],
  ['N', 'step 0.1 s'],
  ['R', 'reset (same seed)'],
  ['C', 'cancel the current plan'],
  ['1 – 4', 'inject disturbance L1 – L4'],
  ['B', 'next benchmark'],
  ['+ / −', 'faster / slower'],
  ['P', 'open the PDDL editor'],
  ['?', 'this help; Esc closes it'],
  ['mouse', 'left-drag a block to move it; drag elsewhere to orbit; wheel to zoom'],
  ['G', 'Teach tab, gripper mode: close / open the gripper'],
];

/** The project's documentation: file in docs/, link text, what it holds. */
const DOCS: [string, string, string][] = [
  ['architecture.md', 'Architecture', 'data flow, layers, where to change what'],
  ['reproduction.md', 'Reproduction', "the paper's tables, command by command"],
  ['reliability.md', 'Reliability', 'tests, fuzzing, soak, known limitations'],
  ['formats.md', 'Formats', 'scene, demo, recording and episode files'],
];

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

/** A catalogue list as a section's rows: label, description. */
const rows = <T extends string>(entries: CatalogueEntry<T>[]): [string, string][] => entries.map((e) => [e.label, e.description]);

/** The explanations, as one element of the help dialog. */
function helpExplanations(c: Catalogue): HTMLElement {
  return el(
    'div',
    { id: 'help-explain', class: 'help-explain' },
    section('Disturbances (the paper’s L1–L4; buttons and keys 1–4)', c.levels.map((e) => [`${e.label} (${e.id.toUpperCase()})`, e.description])),
    section('Methods (the method select)', rows(c.methods)),
    section('Logic-LfD modes (the mode select)', rows(c.modes)),
    section('Benchmarks (the benchmark select)', rows(c.benchmarks)),
    section('Symbols', SYMBOLS),
  );
}

/** Everything the dialog shows above its Close button, the explanations from catalogue `c`. */
export function helpContent(c: Catalogue): HTMLElement[] {
  return [
    el('h2', {}, 'logic-lfd — learning a task from one demonstration'),
    el(
      'p',
      {},
      'The robot was shown the task once. It plans with PDDL to reach ',
      el('em', {}, 'any'),
      ' state seen in that demonstration, then follows the rest of it. Drag a block with the mouse (or a finger) while it works: it notices the change, replans in milliseconds and still finishes. Compare runs the same disturbance with every method.',
    ),
    helpExplanations(c),
    el('table', { class: 'keys' }, ...KEYS.map(([k, v]) => el('tr', {}, el('th', {}, el('kbd', {}, k)), el('td', {}, v)))),
    el(
      'ul',
      { id: 'help-docs', class: 'docs', 'aria-label': 'Documentation' },
      ...DOCS.map(([file, name, what]) =>
        el('li', {}, el('a', { href: `docs/${file}`, target: '_blank', rel: 'noopener' }, name), el('span', { class: 'muted' }, ` — ${what}`)),
      ),
    ),
  ];
}
