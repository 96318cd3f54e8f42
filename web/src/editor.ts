/**
 * The PDDL editor panel: three CodeMirror 6 editors (domain, problem, demonstration) with PDDL
 * highlighting and inline diagnostics at line:col from the wasm parser, and two modes: classical
 * planning (a Plan button that lists the plan and a state stepper that shows the facts after each
 * action) and Logic-LfD (lfd-view.ts: the demonstration reused from a current state).
 */
import type { EditorView } from '@codemirror/view';
import type {
  Diagnostic,
  LogicLfdDiagnostic,
  LogicLfdInput,
  LogicLfdPerturbInput,
  LogicLfdPerturbResult,
  LogicLfdResult,
  PlanOptions,
  PlanOutcome,
} from 'logic-lfd';
import { el } from './dom';
import { LfdView } from './lfd-view';
import { lint, pddlEditor, revealAt, setText } from './pddl-codemirror';
import { initAtoms, withInit } from './pddl-init';
import { InitNotice, copyLinkButton, wideToggle } from './pddl-workspace';

export type Which = 'domain' | 'problem' | 'demo';
const WHICH: Which[] = ['domain', 'problem', 'demo'];

/** Classical planning to G, or Logic-LfD from a current state with the demonstration. */
export type PanelMode = 'classical' | 'lfd';

/** A located message about one of the inputs (the parser's and Logic-LfD's alike). */
type AnyDiagnostic = Pick<LogicLfdDiagnostic, 'file' | 'line' | 'col' | 'message'> & { source: string };

export interface EditorPanelOptions {
  /** Plans in a worker that `cancel` can stop; rejects with a `CancelledError` when stopped. */
  plan: (domain: string, problem: string, options: PlanOptions) => Promise<PlanOutcome>;
  check: (domain: string, problem: string) => Promise<Diagnostic[]>;
  /** Logic-LfD in the same worker (rejects with a `CancelledError` when stopped or after `timeoutMs`). */
  logicLfd: (input: LogicLfdInput, timeoutMs: number) => Promise<LogicLfdResult>;
  logicLfdPerturb: (input: LogicLfdPerturbInput) => Promise<LogicLfdPerturbResult>;
  /** Stops a running request at once. */
  cancel: () => void;
}

/** The planner's own time limit (ms); the worker running it is terminated a little after. */
export const PLAN_TIME_LIMIT_MS = 20_000;

const TAB_LABELS: Record<Which, string> = {
  domain: 'Show the domain',
  problem: 'Show the problem',
  demo: 'Show the demonstration (an IPC plan, one action a line)',
};

export class EditorPanel {
  readonly root: HTMLElement;
  private readonly views: Record<Which, EditorView>;
  private readonly hosts: Record<Which, HTMLElement>;
  private readonly tabs: Record<Which, HTMLButtonElement>;
  private readonly modeButtons: Record<PanelMode, HTMLButtonElement>;
  private readonly lfd: LfdView;
  private readonly planOut: HTMLElement;
  private readonly output: HTMLElement;
  private readonly errorList: HTMLElement;
  private readonly stateView: HTMLElement;
  private readonly search: HTMLSelectElement;
  private readonly heuristic: HTMLSelectElement;
  private readonly planButton: HTMLButtonElement;
  private readonly cancelButton: HTMLButtonElement;
  private mode: PanelMode = 'classical';
  private planning = false;
  private lastPlan: Extract<PlanOutcome, { ok: true }> | null = null;
  private selected = 0;
  private lintTimer = 0;
  private readonly initNotice: InitNotice;
  private readonly linkNote: HTMLElement;
  /** The problem as last loaded: its (:init …) is the demonstration's start. */
  private loadedProblem = '';

  constructor(private readonly opts: EditorPanelOptions) {
    this.hosts = { domain: el('div', { class: 'cm-host' }), problem: el('div', { class: 'cm-host', hidden: '' }), demo: el('div', { class: 'cm-host', hidden: '' }) };
    const make = (w: Which) => pddlEditor(this.hosts[w], `PDDL ${w} editor`, () => this.edited(w));
    this.views = { domain: make('domain'), problem: make('problem'), demo: make('demo') };
    const tab = (w: Which, on: boolean) =>
      el('button', { class: on ? 'tab active' : 'tab', role: 'tab', id: `pddl-tab-${w}`, 'aria-selected': String(on), 'aria-label': TAB_LABELS[w], title: TAB_LABELS[w] }, w);
    this.tabs = { domain: tab('domain', true), problem: tab('problem', false), demo: tab('demo', false) };
    for (const w of WHICH) this.tabs[w].onclick = () => this.show(w);
    const modeButton = (m: PanelMode, text: string, label: string) =>
      el('button', { type: 'button', class: 'seg', id: `pddl-mode-${m}`, 'aria-pressed': String(m === this.mode), title: label }, text);
    this.modeButtons = {
      classical: modeButton('classical', 'Plan (classical)', 'Plan from the initial state to the goal'),
      lfd: modeButton('lfd', 'Logic-LfD', 'Reuse the demonstration from a current state S_C'),
    };
    this.modeButtons.classical.onclick = () => this.setMode('classical');
    this.modeButtons.lfd.onclick = () => this.setMode('lfd');
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
    this.planButton.onclick = () => void (this.mode === 'lfd' ? this.runLfd() : this.runPlan());
    this.cancelButton = el('button', { id: 'pddl-cancel', 'aria-label': 'Stop the running search', title: 'Stop the running search', hidden: '' }, 'Cancel');
    this.cancelButton.onclick = () => this.opts.cancel();
    this.errorList = el('ul', { class: 'diagnostics', id: 'pddl-errors', 'aria-live': 'polite' });
    this.output = el('ol', { class: 'plan-list', id: 'pddl-plan-list', 'aria-label': 'Plan found by the planner' });
    this.stateView = el('div', { class: 'state-view', id: 'pddl-state', 'aria-live': 'polite' });
    this.lfd = new LfdView({
      texts: () => ({ domain: this.text('domain'), problem: this.text('problem'), demo: this.text('demo') }),
      search: () => ({ search: this.search.value as LogicLfdInput['search'], heuristic: this.heuristic.value as LogicLfdInput['heuristic'] }),
      logicLfd: opts.logicLfd,
      logicLfdPerturb: opts.logicLfdPerturb,
      diagnostics: (d) => this.showDiagnostics(d),
      busy: () => this.planning,
    });
    this.initNotice = new InitNotice(() => this.moveInitToState());
    this.linkNote = el('span', { class: 'muted pddl-link-note', id: 'pddl-link-note', 'aria-live': 'polite' });
    const copyLink = copyLinkButton(
      () => ({ domain: this.text('domain'), problem: this.text('problem'), demo: this.text('demo') }),
      (t) => (this.linkNote.textContent = t),
    );
    const prev = el('button', { 'aria-label': 'Previous state', title: 'Previous state' }, '◀');
    const next = el('button', { 'aria-label': 'Next state', title: 'Next state' }, '▶');
    prev.onclick = () => this.selectState(this.selected - 1);
    next.onclick = () => this.selectState(this.selected + 1);
    this.planOut = el('div', { class: 'plan-out' }, el('div', { class: 'plan-col' }, this.output), el('div', { class: 'state-col' }, el('div', { class: 'stepper' }, prev, next), this.stateView));
    this.root = el(
      'section',
      { class: 'editor-panel', 'aria-label': 'PDDL editor', 'data-mode': this.mode },
      el(
        'p',
        { id: 'pddl-own', class: 'pddl-own' },
        'A sandbox: this tab plans on its own. Edits here never change the robot’s task in the Run (edits are kept per task: benchmark, block count or task folder).',
      ),
      el(
        'div',
        { class: 'editor-modes' },
        el('div', { class: 'seg-group', role: 'group', 'aria-label': 'Planning mode' }, this.modeButtons.classical, this.modeButtons.lfd),
        el('span', { class: 'grow' }),
        this.linkNote,
        copyLink,
        this.planButton,
        this.cancelButton,
      ),
      el('div', { class: 'editor-tabs', role: 'tablist' }, this.tabs.domain, this.tabs.problem, this.tabs.demo, el('span', { class: 'grow' }), this.search, this.heuristic),
      el('div', { class: 'editor-body' }, this.hosts.domain, this.hosts.problem, this.hosts.demo),
      this.initNotice.root,
      this.errorList,
      this.planOut,
      this.lfd.root,
    );
    this.wide();
  }

  private wide(): void {
    const toggle = wideToggle(this.root, () => {
      for (const w of WHICH) this.views[w].requestMeasure();
    });
    this.planButton.before(toggle);
  }

  show(which: Which): void {
    for (const w of WHICH) {
      this.hosts[w].hidden = w !== which;
      this.tabs[w].classList.toggle('active', w === which);
      this.tabs[w].setAttribute('aria-selected', String(w === which));
    }
    this.views[which].requestMeasure();
  }

  /** Classical planning or Logic-LfD; the editors' texts stay as they are. */
  setMode(mode: PanelMode): void {
    if (this.mode === mode) return;
    this.mode = mode;
    this.root.dataset.mode = mode;
    for (const m of ['classical', 'lfd'] as PanelMode[]) this.modeButtons[m].setAttribute('aria-pressed', String(m === mode));
    this.planOut.hidden = mode === 'lfd';
    this.lfd.root.hidden = mode !== 'lfd';
    this.planButton.setAttribute('aria-label', mode === 'lfd' ? 'Run Logic-LfD from S_C in both modes' : 'Plan the problem');
    this.planButton.textContent = mode === 'lfd' ? 'Run' : 'Plan';
    if (!this.planning) void this.check();
  }

  /** Puts texts in the editors (a benchmark's, or the tests'); the demonstration stays when not given. */
  setTexts(domain: string, problem: string, demo?: string): void {
    const texts: [Which, string | undefined][] = [['domain', domain], ['problem', problem], ['demo', demo]];
    for (const [w, text] of texts) if (text !== undefined) setText(this.views[w], text);
    this.loadedProblem = problem;
    this.initNotice.show(false);
    this.lastPlan = null;
    this.output.replaceChildren();
    this.stateView.replaceChildren();
    this.errorList.replaceChildren();
    this.lfd.reset();
  }

  text(which: Which): string {
    return this.views[which].state.doc.toString();
  }

  /** An edit: what was said about the old texts goes at once; a check follows when typing stops. */
  private edited(w: Which): void {
    this.errorList.replaceChildren();
    this.output.querySelector('#pddl-no-plan')?.remove();
    this.lfd.stale();
    // Inside CodeMirror's update: the inline marks are cleared right after it.
    queueMicrotask(() => {
      for (const x of WHICH) lint(this.views[x], []);
    });
    if (w === 'problem') this.noteInit();
    this.scheduleCheck();
  }

  /** In Logic-LfD mode, whether the (:init …) now differs from the demonstration's start. */
  private noteInit(): void {
    const now = initAtoms(this.text('problem'));
    const was = initAtoms(this.loadedProblem);
    const differs = this.mode === 'lfd' && now !== null && was !== null && [...now].sort().join() !== [...was].sort().join();
    this.initNotice.show(differs);
  }

  /** The edited initial state becomes S_C; the problem's (:init …) goes back to the demonstration's start. */
  private moveInitToState(): void {
    const now = initAtoms(this.text('problem'));
    const was = initAtoms(this.loadedProblem);
    if (!now || !was) return;
    const restored = withInit(this.text('problem'), was);
    if (restored) setText(this.views.problem, restored);
    this.lfd.useAsState(now);
    this.initNotice.show(false);
  }

  private scheduleCheck(): void {
    clearTimeout(this.lintTimer);
    this.lintTimer = window.setTimeout(() => void this.check(), 600);
  }

  /** Parses and grounds the texts as the user types; shows the located errors. */
  private async check(): Promise<void> {
    // A running search owns the worker; its outcome shows the diagnostics anyway.
    if (this.planning) return;
    if (this.mode === 'lfd') return this.lfd.inspect();
    try {
      this.showDiagnostics(await this.opts.check(this.text('domain'), this.text('problem')));
    } catch (e) {
      if ((e as Error).name === 'CancelledError' && this.planning) return;
      this.errorList.replaceChildren(el('li', { class: 'diagnostic' }, (e as Error).message));
    }
  }

  private showDiagnostics(diags: AnyDiagnostic[]): void {
    for (const w of WHICH) lint(this.views[w], diags.filter((d) => d.source === w));
    this.lfd.state.showErrors(diags.filter((d) => d.source === 'state'));
    this.errorList.replaceChildren(
      ...diags.map((d) => {
        const where = d.line > 0 ? `${d.file}:${d.line}:${d.col}` : d.file || d.source;
        const li = el('li', { class: 'diagnostic', 'data-source': d.source }, el('code', {}, where), ' ', d.message);
        if (d.line > 0 && (WHICH as string[]).includes(d.source)) {
          const src = d.source as Which;
          li.tabIndex = 0;
          li.onclick = () => this.reveal(src, d.line, d.col);
        } else if (d.line > 0 && d.source === 'state') {
          li.tabIndex = 0;
          li.onclick = () => this.lfd.state.reveal(d.line, d.col);
        }
        return li;
      }),
    );
  }

  private reveal(w: Which, line: number, col: number): void {
    this.show(w);
    revealAt(this.views[w], line, col);
  }

  /** Marks the panel busy (Plan disabled, Cancel shown) while `work` runs. */
  private async busy(label: string, work: () => Promise<void>): Promise<void> {
    if (this.planning) return;
    this.planning = true;
    clearTimeout(this.lintTimer);
    this.planButton.disabled = true;
    this.planButton.textContent = label;
    this.cancelButton.hidden = false;
    try {
      await work();
    } finally {
      this.planning = false;
      this.planButton.disabled = false;
      this.planButton.textContent = this.mode === 'lfd' ? 'Run' : 'Plan';
      this.cancelButton.hidden = true;
    }
  }

  /** Logic-LfD from S_C, paper and prioritised side by side. */
  runLfd(): Promise<void> {
    return this.busy('Running…', () => this.lfd.run());
  }

  runPlan(): Promise<void> {
    return this.busy('Planning…', () => this.plan());
  }

  private async plan(): Promise<void> {
    this.output.replaceChildren(el('li', { class: 'muted empty' }, 'Planning… (Cancel stops the search)'));
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
        // A message, not a step: no number in front of it.
        this.output.replaceChildren(el('li', { class: 'muted empty', id: 'pddl-no-plan' }, out.message));
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
      this.output.replaceChildren(el('li', { class: 'muted empty', id: 'pddl-stopped' }, text));
    }
  }

  private selectState(i: number): void {
    const p = this.lastPlan;
    if (!p) return;
    this.selected = Math.max(0, Math.min(p.states.length - 1, i));
    this.output.querySelectorAll('button.step').forEach((b, j) => b.classList.toggle('current', j === this.selected));
    const facts = p.states[this.selected] ?? [];
    const before = new Set(this.selected > 0 ? p.states[this.selected - 1] : []);
    const now = new Set(facts);
    const removed = [...before].filter((f) => !now.has(f));
    const title = this.selected === 0 ? 'Initial state' : `After step ${this.selected}: ${p.plan[this.selected - 1]}`;
    this.stateView.replaceChildren(
      el('div', { class: 'state-title' }, title),
      el(
        'ul',
        { class: 'facts' },
        ...facts.map((f) => el('li', { class: this.selected > 0 && !before.has(f) ? 'added' : '' }, f)),
        ...removed.map((f) => el('li', { class: 'removed', title: 'removed by this step' }, f)),
      ),
    );
  }
}
