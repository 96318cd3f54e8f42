/**
 * The PDDL tab's workspace controls: a wide mode that hides the 3-D view so the editors take the
 * page's width (Alt+W), a "Copy link" that carries the texts in the URL, and the notice that an
 * `(:init …)` edit in Logic-LfD mode moves the demonstration's start rather than the current state.
 */
import './pddl-workspace.css';
import { el } from './dom';
import { linkFor, type PddlTexts } from './pddl-link';

/** A toggle (and Alt+W while the PDDL tab shows) for the wide editor mode. */
export function wideToggle(panel: HTMLElement, changed: () => void): HTMLButtonElement {
  const b = el('button', { type: 'button', id: 'pddl-wide', 'aria-pressed': 'false', title: 'Hide the 3-D view: the editor takes the width (Alt+W)' }, 'Wide');
  const set = (on: boolean) => {
    document.body.classList.toggle('pddl-wide', on);
    b.setAttribute('aria-pressed', String(on));
    changed();
  };
  b.onclick = () => set(!document.body.classList.contains('pddl-wide'));
  document.addEventListener('keydown', (e) => {
    if (!e.altKey || e.ctrlKey || e.metaKey || e.code !== 'KeyW' || panel.closest('[hidden]')) return;
    e.preventDefault();
    set(!document.body.classList.contains('pddl-wide'));
  });
  // The Run's view needs the width back when another tab opens (observed once the panel is placed).
  queueMicrotask(() =>
    new MutationObserver(() => {
      if (panel.closest('[hidden]') && document.body.classList.contains('pddl-wide')) set(false);
    }).observe(panel.closest('.panel') ?? panel, { attributes: true, attributeFilter: ['hidden'] }),
  );
  return b;
}

/** "Copy link": the page's address with the texts, put in the address bar and the clipboard. */
export function copyLinkButton(texts: () => PddlTexts, say: (text: string) => void): HTMLButtonElement {
  const b = el('button', { type: 'button', id: 'pddl-copy-link', title: 'A link that opens this page with these domain, problem and demonstration texts' }, 'Copy link');
  b.onclick = async () => {
    const url = linkFor(texts());
    history.replaceState(history.state, '', url);
    try {
      await navigator.clipboard.writeText(url);
      say(`Link copied (${url.length} characters).`);
    } catch {
      say('The address bar holds the link (the clipboard refused it).');
    }
  };
  return b;
}

/** Says, in Logic-LfD mode, that the edited initial state belongs in the S_C editor. */
export class InitNotice {
  readonly root: HTMLElement;
  private readonly use: HTMLButtonElement;

  constructor(onUse: () => void) {
    this.use = el('button', { type: 'button', id: 'pddl-init-use' }, 'Use this state as S_C');
    this.use.onclick = onUse;
    this.root = el(
      'div',
      { class: 'pddl-init-notice', id: 'pddl-init-notice', role: 'status', hidden: '' },
      el(
        'span',
        {},
        'The problem’s (:init …) is where the demonstration starts (L0): editing it changes the demonstration, not the robot’s situation. A disturbed state belongs in the S_C editor below. ',
      ),
      this.use,
    );
  }

  show(on: boolean): void {
    this.root.hidden = !on;
  }
}
