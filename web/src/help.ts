/**
 * The help overlay: what the page shows, its keyboard shortcuts and links to the project's
 * documentation (the repository's docs/*.md, which the build copies beside the page: see
 * vite.config.ts). Opens with the ? button or key; closes with its button, Escape or a click
 * beside the dialog.
 */
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

export class HelpOverlay {
  readonly root: HTMLElement;
  private readonly closeBtn = el('button', { id: 'help-close', class: 'primary', type: 'button', 'aria-label': 'Close help' }, 'Close');

  /** `opener` gets the focus back when the overlay closes. */
  constructor(private readonly opener: HTMLElement) {
    this.root = el(
      'div',
      { id: 'help-overlay', class: 'overlay', role: 'dialog', 'aria-modal': 'true', 'aria-label': 'Help', hidden: '' },
      el(
        'div',
        { class: 'dialog' },
        el('h2', {}, 'logic-lfd — learning a task from one demonstration'),
        el(
          'p',
          {},
          'The robot was shown the task once. It plans with PDDL to reach ',
          el('em', {}, 'any'),
          ' state seen in that demonstration, then follows the rest of it. Drag a block with the mouse (or a finger) while it works: it notices the change, replans in milliseconds and still finishes. Compare runs the same disturbance with every method.',
        ),
        el('table', { class: 'keys' }, ...KEYS.map(([k, v]) => el('tr', {}, el('th', {}, el('kbd', {}, k)), el('td', {}, v)))),
        el(
          'ul',
          { id: 'help-docs', class: 'docs', 'aria-label': 'Documentation' },
          ...DOCS.map(([file, name, what]) =>
            el('li', {}, el('a', { href: `docs/${file}`, target: '_blank', rel: 'noopener' }, name), el('span', { class: 'muted' }, ` — ${what}`)),
          ),
        ),
        this.closeBtn,
      ),
    );
    opener.onclick = () => this.open();
    this.closeBtn.onclick = () => this.close();
    this.root.onclick = (e) => {
      if (e.target === this.root) this.close();
    };
  }

  get shown(): boolean {
    return !this.root.hidden;
  }

  open(): void {
    this.root.hidden = false;
    this.closeBtn.focus();
    this.explained ??= import('./help-text').then(({ helpExplanations }) => {
      this.root.querySelector('.keys')?.before(helpExplanations());
    });
  }

  /** The explanations' chunk, once asked for. */
  private explained: Promise<void> | null = null;

  close(): void {
    this.root.hidden = true;
    this.opener.focus();
  }
}
