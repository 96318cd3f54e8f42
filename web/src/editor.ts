/**
 * The PDDL editor panel: two CodeMirror 6 editors (domain, problem) with PDDL highlighting, inline
 * diagnostics at line:col from the wasm parser, a Plan button that lists the plan, and a state
 * stepper that shows the facts after each action.
 */
import { EditorState, type Extension } from '@codemirror/state';
import { EditorView, keymap, lineNumbers, highlightActiveLine, drawSelection } from '@codemirror/view';
import { defaultKeymap, history, historyKeymap } from '@codemirror/commands';
import { StreamLanguage, syntaxHighlighting, HighlightStyle, bracketMatching } from '@codemirror/language';
import { linter, lintGutter, setDiagnostics, type Diagnostic as CmDiagnostic } from '@codemirror/lint';
import { tags as t } from '@lezer/highlight';
import type { Diagnostic, PlanOptions, PlanOutcome } from 'logic-lfd';
import { el } from './dom';

const pddl = StreamLanguage.define<{ depth: number }>({
  name: 'pddl',
  startState: () => ({ depth: 0 }),
  token(stream, state) {
    if (stream.eatSpace()) return null;
    const ch = stream.peek();
    if (ch === ';') {
      stream.skipToEnd();
      return 'comment';
    }
    if (ch === '(' || ch === ')') {
      stream.next();
      state.depth += ch === '(' ? 1 : -1;
      return 'paren';
    }
    if (ch === ':') {
      if (!stream.match(/^:[\w-]+/)) stream.next();
      return 'keyword';
    }
    if (ch === '?') {
      if (!stream.match(/^\?[\w-]+/)) stream.next();
      return 'variableName';
    }
    if (ch === '-' && stream.match(/^-\s/, false)) {
      stream.next();
      return 'operator';
    }
    if (stream.match(/^-?\d+(\.\d+)?/)) return 'number';
    if (stream.match(/^(define|domain|problem|and|or|not|imply|forall|exists|when|either|increase)\b/i)) return 'keyword';
    if (!stream.match(/^[^\s();]+/)) stream.next();
    return 'atom';
  },
});

const highlight = HighlightStyle.define([
  { tag: t.comment, color: '#6b7686', fontStyle: 'italic' },
  { tag: t.keyword, color: '#7aa2f7' },
  { tag: t.variableName, color: '#e0af68' },
  { tag: t.number, color: '#ff9e64' },
  { tag: t.atom, color: '#c9d1d9' },
  { tag: t.paren, color: '#6b7686' },
  { tag: t.operator, color: '#bb9af7' },
]);

const theme = EditorView.theme(
  {
    '&': { height: '100%', fontSize: '12.5px', backgroundColor: '#0f1216' },
    '.cm-content': { fontFamily: 'ui-monospace, SFMono-Regular, Menlo, Consolas, monospace', caretColor: '#e6edf3' },
    '.cm-gutters': { backgroundColor: '#0f1216', color: '#4d5662', border: 'none' },
    '.cm-activeLine': { backgroundColor: '#161b22' },
    '.cm-activeLineGutter': { backgroundColor: '#161b22' },
    '&.cm-focused .cm-cursor': { borderLeftColor: '#e6edf3' },
    '.cm-selectionBackground, &.cm-focused .cm-selectionBackground': { backgroundColor: '#264f78 !important' },
    '.cm-scroller': { overflow: 'auto' },
  },
  { dark: true },
);

export type Which = 'domain' | 'problem';

export interface EditorPanelOptions {
  /** Plans in a worker that `cancel` can stop; rejects with a `CancelledError` when stopped. */
  plan: (domain: string, problem: string, options: PlanOptions) => Promise<PlanOutcome>;
  check: (domain: string, problem: string) => Promise<Diagnostic[]>;
  /** Stops a running `plan` (and `check`) at once. */
  cancel: () => void;
}

/** The planner's own time limit (ms); the worker running it is terminated a little after. */
export const PLAN_TIME_LIMIT_MS = 20_000;

function offsetOf(doc: EditorState['doc'], line: number, col: number): number {
  const l = doc.line(Math.min(Math.max(1, line), doc.lines));
  return Math.min(l.from + Math.max(0, col - 1), l.to);
}

export class EditorPanel {
  readonly root: HTMLElement;
  private readonly views: Record<Which, EditorView>;
  private readonly hosts: Record<Which, HTMLElement>;
  private readonly tabs: Record<Which, HTMLButtonElement>;
  private readonly output: HTMLElement;
  private readonly errorList: HTMLElement;
  private readonly stateView: HTMLElement;
  private readonly search: HTMLSelectElement;
  private readonly heuristic: HTMLSelectElement;
  private readonly planButton: HTMLButtonElement;
  private readonly cancelButton: HTMLButtonElement;
  private planning = false;
  private lastPlan: Extract<PlanOutcome, { ok: true }> | null = null;
  private selected = 0;
  private lintTimer = 0;

  constructor(private readonly opts: EditorPanelOptions) {
    const ext = (which: Which): Extension[] => [
      lineNumbers(),
      history(),
      drawSelection(),
      highlightActiveLine(),
      bracketMatching(),
      EditorView.lineWrapping,
      pddl,
      syntaxHighlighting(highlight),
      lintGutter(),
      linter(null),
      theme,
      keymap.of([...defaultKeymap, ...historyKeymap]),
      EditorView.contentAttributes.of({ 'aria-label': `PDDL ${which} editor` }),
      EditorView.updateListener.of((u) => {
        if (u.docChanged) this.scheduleCheck();
      }),
    ];
    this.hosts = { domain: el('div', { class: 'cm-host' }), problem: el('div', { class: 'cm-host', hidden: '' }) };
    this.views = {
      domain: new EditorView({ state: EditorState.create({ doc: '', extensions: ext('domain') }), parent: this.hosts.domain }),
      problem: new EditorView({ state: EditorState.create({ doc: '', extensions: ext('problem') }), parent: this.hosts.problem }),
    };
    this.tabs = {
      domain: el('button', { class: 'tab active', role: 'tab', 'aria-selected': 'true', 'aria-label': 'Show the domain' }, 'domain'),
      problem: el('button', { class: 'tab', role: 'tab', 'aria-selected': 'false', 'aria-label': 'Show the problem' }, 'problem'),
    };
    this.tabs.domain.onclick = () => this.show('domain');
    this.tabs.problem.onclick = () => this.show('problem');
    this.search = el(
      'select',
      { 'aria-label': 'Search algorithm', id: 'pddl-search' },
      ...['astar', 'gbfs', 'bfs'].map((s) => el('option', { value: s }, s)),
    );
    this.heuristic = el(
      'select',
      { 'aria-label': 'Heuristic', id: 'pddl-heuristic' },
      ...['hff', 'lmcut', 'hmax', 'blind'].map((s) => el('option', { value: s }, s)),
    );
    this.planButton = el('button', { class: 'primary', id: 'pddl-plan', 'aria-label': 'Plan the problem' }, 'Plan');
    this.planButton.onclick = () => void this.runPlan();
    this.cancelButton = el('button', { id: 'pddl-cancel', 'aria-label': 'Stop the running search', title: 'Stop the running search', hidden: '' }, 'Cancel');
    this.cancelButton.onclick = () => this.opts.cancel();
    this.errorList = el('ul', { class: 'diagnostics', id: 'pddl-errors', 'aria-live': 'polite' });
    this.output = el('ol', { class: 'plan-list', id: 'pddl-plan-list', 'aria-label': 'Plan found by the planner' });
    this.stateView = el('div', { class: 'state-view', id: 'pddl-state', 'aria-live': 'polite' });
    const prev = el('button', { 'aria-label': 'Previous state', title: 'Previous state' }, '◀');
    const next = el('button', { 'aria-label': 'Next state', title: 'Next state' }, '▶');
    prev.onclick = () => this.selectState(this.selected - 1);
    next.onclick = () => this.selectState(this.selected + 1);
    this.root = el(
      'section',
      { class: 'editor-panel', 'aria-label': 'PDDL editor' },
      el('div', { class: 'editor-tabs', role: 'tablist' }, this.tabs.domain, this.tabs.problem, el('span', { class: 'grow' }), this.search, this.heuristic, this.planButton, this.cancelButton),
      el('div', { class: 'editor-body' }, this.hosts.domain, this.hosts.problem),
      this.errorList,
      el('div', { class: 'plan-out' }, el('div', { class: 'plan-col' }, this.output), el('div', { class: 'state-col' }, el('div', { class: 'stepper' }, prev, next), this.stateView)),
    );
  }

  show(which: Which): void {
    for (const w of ['domain', 'problem'] as Which[]) {
      this.hosts[w].hidden = w !== which;
      this.tabs[w].classList.toggle('active', w === which);
      this.tabs[w].setAttribute('aria-selected', String(w === which));
    }
    this.views[which].requestMeasure();
  }

  setTexts(domain: string, problem: string): void {
    for (const [w, text] of [['domain', domain], ['problem', problem]] as [Which, string][]) {
      const v = this.views[w];
      v.dispatch({ changes: { from: 0, to: v.state.doc.length, insert: text } });
    }
    this.lastPlan = null;
    this.output.replaceChildren();
    this.stateView.replaceChildren();
    this.errorList.replaceChildren();
  }

  text(which: Which): string {
    return this.views[which].state.doc.toString();
  }

  private scheduleCheck(): void {
    clearTimeout(this.lintTimer);
    this.lintTimer = window.setTimeout(() => void this.check(), 600);
  }

  /** Parses and grounds both texts as the user types; shows the located errors. */
  private async check(): Promise<void> {
    // A running search owns the worker; its outcome shows the diagnostics anyway.
    if (this.planning) return;
    try {
      this.showDiagnostics(await this.opts.check(this.text('domain'), this.text('problem')));
    } catch (e) {
      if ((e as Error).name === 'CancelledError' && this.planning) return;
      this.errorList.replaceChildren(el('li', { class: 'diagnostic' }, (e as Error).message));
    }
  }

  private showDiagnostics(diags: Diagnostic[]): void {
    for (const w of ['domain', 'problem'] as Which[]) {
      const v = this.views[w];
      const mine: CmDiagnostic[] = diags
        .filter((d) => d.source === w && d.line > 0)
        .map((d) => {
          const from = offsetOf(v.state.doc, d.line, d.col);
          return { from, to: Math.min(from + 1, v.state.doc.length), severity: 'error', message: d.message };
        });
      v.dispatch(setDiagnostics(v.state, mine));
    }
    this.errorList.replaceChildren(
      ...diags.map((d) => {
        const where = d.line > 0 ? `${d.file}:${d.line}:${d.col}` : d.file || d.source;
        const li = el('li', { class: 'diagnostic' }, el('code', {}, where), ' ', d.message);
        if (d.line > 0 && (d.source === 'domain' || d.source === 'problem')) {
          const src: Which = d.source;
          li.tabIndex = 0;
          li.onclick = () => this.reveal(src, d.line, d.col);
        }
        return li;
      }),
    );
  }

  private reveal(w: Which, line: number, col: number): void {
    this.show(w);
    const v = this.views[w];
    const pos = offsetOf(v.state.doc, line, col);
    v.dispatch({ selection: { anchor: pos }, scrollIntoView: true });
    v.focus();
  }

  async runPlan(): Promise<void> {
    if (this.planning) return;
    this.planning = true;
    clearTimeout(this.lintTimer);
    this.planButton.disabled = true;
    this.planButton.textContent = 'Planning…';
    this.cancelButton.hidden = false;
    this.output.replaceChildren(el('li', { class: 'muted' }, 'Planning… (Cancel stops the search)'));
    this.stateView.replaceChildren();
    try {
      const out = await this.opts.plan(this.text('domain'), this.text('problem'), {
        search: this.search.value as PlanOptions['search'],
        heuristic: this.heuristic.value as PlanOptions['heuristic'],
        timeLimitMs: PLAN_TIME_LIMIT_MS,
      });
      if (!out.ok) {
        this.lastPlan = null;
        this.showDiagnostics(out.diagnostics);
        this.output.replaceChildren(el('li', { class: 'muted' }, out.message));
        this.stateView.replaceChildren();
        return;
      }
      this.showDiagnostics([]);
      this.lastPlan = out;
      const summary = `${out.plan.length} actions, cost ${out.cost}, ${out.expanded} expanded, ${out.timeMs.toFixed(2)} ms`;
      this.output.replaceChildren(
        el('li', { class: 'plan-summary', value: '0' }, el('button', { class: 'step', 'data-index': '0' }, 'initial state'), el('span', { class: 'muted' }, ` — ${summary}`)),
        ...out.plan.map((a, i) => el('li', {}, el('button', { class: 'step', 'data-index': String(i + 1) }, a))),
      );
      this.output.querySelectorAll<HTMLButtonElement>('button.step').forEach((b) => {
        b.onclick = () => this.selectState(Number(b.dataset.index));
      });
      this.selectState(0);
    } catch (e) {
      this.lastPlan = null;
      const err = e as Error;
      const text = err.name === 'CancelledError' ? `Search ${err.message}.` : err.message;
      this.output.replaceChildren(el('li', { class: 'muted', id: 'pddl-stopped' }, text));
    } finally {
      this.planning = false;
      this.planButton.disabled = false;
      this.planButton.textContent = 'Plan';
      this.cancelButton.hidden = true;
    }
  }

  private selectState(i: number): void {
    const p = this.lastPlan;
    if (!p) return;
    this.selected = Math.max(0, Math.min(p.states.length - 1, i));
    this.output.querySelectorAll('button.step').forEach((b, j) => b.classList.toggle('current', j === this.selected));
    const facts = p.states[this.selected] ?? [];
    const before = new Set(this.selected > 0 ? p.states[this.selected - 1] : []);
    const title = this.selected === 0 ? 'Initial state' : `After step ${this.selected}: ${p.plan[this.selected - 1]}`;
    this.stateView.replaceChildren(
      el('div', { class: 'state-title' }, title),
      el('ul', { class: 'facts' }, ...facts.map((f) => el('li', { class: this.selected > 0 && !before.has(f) ? 'added' : '' }, f))),
    );
  }
}
