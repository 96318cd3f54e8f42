/**
 * The help overlay: a dialog whose content (help-text.ts: what the page shows, the explanations,
 * the keyboard shortcuts and links to the documentation) is loaded when it first opens. Opens
 * with the ? button or key; closes with its button, Escape or a click beside the dialog.
 */
import { catalogueReady } from './catalogue';
import { el } from './dom';

export class HelpOverlay {
  readonly root: HTMLElement;
  /** Filled from the help's own chunk when it first opens. */
  private readonly content = el('div', { class: 'help-content' }, el('h2', {}, 'logic-lfd — learning a task from one demonstration'));
  private readonly closeBtn = el('button', { id: 'help-close', class: 'primary', type: 'button', 'aria-label': 'Close help' }, 'Close');

  /** `opener` gets the focus back when the overlay closes. */
  constructor(private readonly opener: HTMLElement) {
    this.root = el(
      'div',
      { id: 'help-overlay', class: 'overlay', role: 'dialog', 'aria-modal': 'true', 'aria-label': 'Help', hidden: '' },
      el(
        'div',
        { class: 'dialog' },
        // Close first: it stays in view at the top of a long help (a phone scrolls it).
        this.closeBtn,
        this.content,
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
    this.explained ??= Promise.all([import('./help-text'), catalogueReady]).then(([{ helpContent }, catalogue]) => this.content.replaceChildren(...helpContent(catalogue)));
  }

  /** The explanations' chunk, once asked for. */
  private explained: Promise<void> | null = null;

  close(): void {
    this.root.hidden = true;
    this.opener.focus();
  }
}
