/**
 * The editor of the current state S_C in the Logic-LfD view: S_C as PDDL atoms in a small
 * CodeMirror (with its errors inline), and ways to change it without typing: apply an applicable
 * action, toggle a fact, a seeded random walk, reset to L_0 or set it to a demonstration state.
 * It holds no planner: the view checks every new S_C in the worker and calls `update` with what
 * it learnt (the fluents, S_C's facts, the actions applicable in it).
 */
import type { EditorView } from '@codemirror/view';
import { el } from './dom';
import { lint, pddlEditor, revealAt, setText, type Located } from './pddl-codemirror';

export interface StateEditorOptions {
  /** S_C changed (typed: `typed` is true; the view waits a little longer before checking it). */
  changed: (typed: boolean) => void;
  /** The state after applying `action` to S_C (`facts`), or null when that failed. */
  apply: (facts: string[], action: string) => Promise<string[] | null>;
  /** A seeded random walk from L_0: its end state and length, or null when that failed. */
  walk: (seed: number, steps: number) => Promise<{ facts: string[]; steps: number } | null>;
  /** The facts of demonstration state L_k. */
  demoState: (k: number) => string[] | null;
}

/** How many facts the fact list shows at most (the filter narrows it). */
const MAX_FACTS_SHOWN = 400;

export class StateEditor {
  readonly root: HTMLElement;
  private readonly view: EditorView;
  private readonly applySel: HTMLSelectElement;
  private readonly applyBtn: HTMLButtonElement;
  private readonly setK: HTMLSelectElement;
  private readonly filter: HTMLInputElement;
  private readonly factList: HTMLUListElement;
  private readonly factCount: HTMLElement;
  private readonly seed: HTMLInputElement;
  private readonly steps: HTMLInputElement;
  private readonly note: HTMLElement;
  private readonly controls: HTMLButtonElement[] = [];
  /** S_C follows the problem's initial state until the user changes it. */
  private custom = false;
  private quiet = false;
  private fluents: string[] = [];
  private facts = new Set<string>();

  constructor(private readonly opts: StateEditorOptions) {
    const host = el('div', { class: 'lfd-state-text' });
    this.view = pddlEditor(host, 'Current state S_C as PDDL atoms', () => {
      if (this.quiet) return;
      this.custom = true;
      this.opts.changed(true);
    });
    const reset = el('button', { type: 'button', id: 'lfd-reset', title: 'S_C := L_0, the problem’s initial state' }, 'Reset to L', el('sub', {}, '0'));
    reset.onclick = () => this.followInit();
    this.setK = el('select', { id: 'lfd-set-k', 'aria-label': 'Set S_C to a demonstration state', title: 'Set S_C to a demonstration state' });
    this.setK.onchange = () => {
      if (this.setK.value !== '') this.setToDemoState(Number(this.setK.value));
      this.setK.value = '';
    };
    this.seed = el('input', { type: 'number', id: 'lfd-seed', min: '0', step: '1', value: '1', 'aria-label': 'Random walk seed', title: 'Random walk seed' });
    this.steps = el('input', { type: 'number', id: 'lfd-steps', min: '1', max: '50', step: '1', value: '4', 'aria-label': 'Random walk: most steps', title: 'Random walk: most steps' });
    const walk = el('button', { type: 'button', id: 'lfd-walk', title: 'S_C := a seeded random walk of the domain’s actions from L_0' }, 'Random walk');
    walk.onclick = () => void this.randomWalk();
    this.applySel = el('select', { id: 'lfd-apply', 'aria-label': 'An action applicable in S_C' });
    this.applyBtn = el('button', { type: 'button', id: 'lfd-apply-btn', 'aria-label': 'Apply the chosen action to S_C' }, 'Apply');
    this.applyBtn.onclick = () => void this.applyChosen();
    this.filter = el('input', { type: 'search', id: 'lfd-filter', placeholder: 'filter facts', 'aria-label': 'Filter the facts' });
    this.filter.oninput = () => this.renderFacts();
    this.factList = el('ul', { id: 'lfd-facts', class: 'lfd-facts', 'aria-label': 'Facts: checked ones hold in S_C' });
    this.factList.onchange = (e) => {
      const box = e.target as HTMLInputElement;
      if (box.dataset.fact) this.toggle(box.dataset.fact, box.checked);
    };
    this.factCount = el('span', { class: 'muted', id: 'lfd-fact-count' });
    this.note = el('div', { class: 'lfd-note muted', id: 'lfd-state-note', 'aria-live': 'polite' });
    this.controls.push(reset, walk, this.applyBtn);
    this.root = el(
      'div',
      { class: 'lfd-state', id: 'lfd-state' },
      el('div', { class: 'lfd-row' }, reset, this.setK),
      el('div', { class: 'lfd-row' }, this.applySel, this.applyBtn),
      el('div', { class: 'lfd-row' }, walk, el('label', { class: 'lfd-inline' }, 'seed', this.seed), el('label', { class: 'lfd-inline' }, 'at most', this.steps, 'steps')),
      host,
      el('div', { class: 'lfd-row' }, this.filter, this.factCount),
      this.factList,
      this.note,
    );
  }

  /** S_C as text for the worker; undefined while S_C is the problem's initial state. */
  text(): string | undefined {
    return this.custom ? this.view.state.doc.toString() : undefined;
  }

  /** S_C's facts as last checked. */
  current(): Set<string> {
    return this.facts;
  }

  /** Back to the problem's initial state (a new benchmark, or Reset to L_0). */
  followInit(): void {
    this.custom = false;
    this.note.textContent = '';
    this.opts.changed(false);
  }

  /** Disables the buttons while a search runs (its result is about this S_C). */
  setBusy(busy: boolean): void {
    for (const b of [...this.controls, this.applySel, this.setK, this.seed, this.steps]) b.disabled = busy;
    this.factList.querySelectorAll('input').forEach((b) => (b.disabled = busy));
    if (!busy) this.applyBtn.disabled = this.applySel.options.length === 0;
  }

  /** What the worker learnt about S_C: every fluent, S_C's facts, the applicable actions. */
  update(fluents: string[], state: string[], applicable: string[], demoStates: number): void {
    this.fluents = fluents;
    this.facts = new Set(state);
    if (!this.custom) this.write(state);
    this.applySel.replaceChildren(...applicable.map((a) => el('option', { value: a }, a)));
    this.applySel.title = `${applicable.length} actions applicable in S_C`;
    this.applyBtn.disabled = applicable.length === 0;
    if (this.setK.options.length !== demoStates + 1) {
      this.setK.replaceChildren(
        el('option', { value: '' }, 'Set S_C to a demo state…'),
        ...Array.from({ length: demoStates }, (_, k) => el('option', { value: String(k) }, `Set to L${k}`)),
      );
    }
    this.renderFacts();
  }

  /** S_C's located errors, inline in its text. */
  showErrors(diags: Located[]): void {
    lint(this.view, diags);
  }

  /** Shows S_C's text at `line`:`col`. */
  reveal(line: number, col: number): void {
    revealAt(this.view, line, col);
  }

  /** S_C := the facts of L_k. */
  setToDemoState(k: number): void {
    const facts = this.opts.demoState(k);
    if (!facts) return;
    this.setFacts(facts, `S_C set to L${k}.`);
  }

  /** S_C := `facts`, with `note` saying where they came from. */
  setFacts(facts: string[], note: string): void {
    this.custom = true;
    this.facts = new Set(facts);
    this.write(facts);
    this.note.textContent = note;
    this.renderFacts();
    this.opts.changed(false);
  }

  private write(facts: string[]): void {
    const text = [...facts].sort().join('\n');
    if (text === this.view.state.doc.toString()) return;
    this.quiet = true;
    try {
      setText(this.view, text);
    } finally {
      this.quiet = false;
    }
  }

  private toggle(fact: string, on: boolean): void {
    const next = new Set(this.facts);
    if (on) next.add(fact);
    else next.delete(fact);
    this.setFacts([...next], `${on ? 'Added' : 'Removed'} ${fact}.`);
  }

  private async applyChosen(): Promise<void> {
    const action = this.applySel.value;
    if (!action) return;
    const next = await this.opts.apply([...this.facts], action);
    if (next) this.setFacts(next, `Applied ${action}.`);
  }

  private async randomWalk(): Promise<void> {
    const seed = Math.max(0, Math.floor(Number(this.seed.value) || 0));
    const steps = Math.min(50, Math.max(1, Math.floor(Number(this.steps.value) || 1)));
    const w = await this.opts.walk(seed, steps);
    if (w) this.setFacts(w.facts, `Random walk from L0, seed ${seed}: ${w.steps} step${w.steps === 1 ? '' : 's'}.`);
  }

  private renderFacts(): void {
    const q = this.filter.value.trim().toLowerCase();
    const shown = this.fluents.filter((f) => !q || f.toLowerCase().includes(q));
    this.factList.replaceChildren(
      ...shown.slice(0, MAX_FACTS_SHOWN).map((f) => {
        const box = el('input', { type: 'checkbox', 'data-fact': f, 'aria-label': `${f} holds in S_C` });
        box.checked = this.facts.has(f);
        return el('li', { class: box.checked ? 'on' : '' }, el('label', {}, box, f));
      }),
    );
    const more = shown.length > MAX_FACTS_SHOWN ? `, first ${MAX_FACTS_SHOWN} shown` : '';
    this.factCount.textContent = `${this.facts.size} of ${this.fluents.length} facts in S_C${q ? ` · ${shown.length} match` : ''}${more}`;
  }
}
