/**
 * The PDDL tab's Logic-LfD view, for whatever domain, problem and demonstration the editors hold:
 * the demonstration states L_0 … L_N (click one for its facts), the current state S_C and its
 * editor, LogicIn's verdict, and a run of both multi-goal modes side by side with planning from
 * scratch. Every request goes to the search worker; the view only renders plain data.
 */
import type {
  LogicLfdDemo,
  LogicLfdDiagnostic,
  LogicLfdInput,
  LogicLfdPerturbInput,
  LogicLfdPerturbResult,
  LogicLfdResult,
  Mode,
} from 'logic-lfd';
import './lfd.css';
import { el, lk } from './dom';
import { renderResults } from './lfd-results';
import { StateEditor } from './lfd-state-editor';
import { withInit } from './pddl-init';

export interface LfdViewOptions {
  /** The editors' texts. */
  texts: () => { domain: string; problem: string; demo: string };
  /** The search and heuristic chosen in the tab. */
  search: () => Pick<LogicLfdInput, 'search' | 'heuristic'>;
  logicLfd: (input: LogicLfdInput, timeoutMs: number) => Promise<LogicLfdResult>;
  logicLfdPerturb: (input: LogicLfdPerturbInput) => Promise<LogicLfdPerturbResult>;
  /** Shows the inputs' located errors (every source; an empty list clears them). */
  diagnostics: (d: LogicLfdDiagnostic[]) => void;
  /** Whether a search owns the worker (checks wait for it). */
  busy: () => boolean;
}

/** Each search's own time limit (ms); the worker is terminated a little after. */
export const LFD_TIME_LIMIT_MS = 15_000;
/** A check of S_C runs no search (`maxExpanded: 0`): it is quick, unless the grounding is not. */
const CHECK_TIMEOUT_MS = 15_000;
/** Kinds of result that stop before S_C is read. */
const INPUT_KINDS = new Set(['parse', 'demo', 'options']);

export class LfdView {
  readonly root: HTMLElement;
  readonly state: StateEditor;
  private readonly demoList: HTMLOListElement;
  private readonly demoInfo: HTMLElement;
  private readonly lkFacts: HTMLElement;
  private readonly verdict: HTMLElement;
  private readonly results: HTMLElement;
  private demo: LogicLfdDemo | null = null;
  /** The problem's static facts, as last read. */
  private statics: string[] = [];
  private logicIn: number | null = null;
  private selectedK: number | null = null;
  private seq = 0;
  private timer = 0;

  constructor(private readonly opts: LfdViewOptions) {
    this.state = new StateEditor({
      changed: (typed) => this.schedule(typed ? 600 : 60),
      apply: (facts, action) => this.apply(facts, action),
      walk: (seed, steps) => this.walk(seed, steps),
      demoState: (k) => this.demo?.states[k] ?? null,
    });
    this.demoList = el('ol', { id: 'lfd-demo', class: 'demo-list lfd-demo', 'aria-label': 'Demonstration states L_k and actions a_k' });
    this.demoInfo = el('span', { class: 'muted', id: 'lfd-demo-info' });
    this.lkFacts = el('div', { id: 'lfd-lk-facts', class: 'lfd-lk-facts', hidden: '' });
    this.verdict = el('div', { id: 'lfd-verdict', class: 'lfd-verdict', 'aria-live': 'polite' });
    this.results = el('div', { id: 'lfd-results', class: 'lfd-results', 'aria-live': 'polite' });
    this.root = el(
      'section',
      { class: 'lfd-view', id: 'lfd-view', 'aria-label': 'Logic-LfD', hidden: '' },
      help(),
      el('h2', {}, 'Demonstration ', this.demoInfo),
      this.demoList,
      this.lkFacts,
      el('h2', {}, 'Current state S', el('sub', {}, 'C')),
      this.state.root,
      this.verdict,
      el('h2', {}, 'Logic-LfD from S', el('sub', {}, 'C'), el('span', { class: 'muted' }, ' · Run compares both modes')),
      this.results,
    );
  }

  /** New texts from a benchmark: S_C follows the new problem's initial state; results go. */
  reset(): void {
    this.results.replaceChildren();
    this.selectedK = null;
    this.lkFacts.hidden = true;
    this.state.followInit();
  }

  /** S_C := the atoms of an edited (:init …), less the static facts (S_C holds only fluents). */
  useAsState(atoms: string[]): void {
    const statics = new Set(this.statics);
    this.state.setFacts(atoms.filter((a) => !statics.has(a)), 'S_C set to the edited (:init …).');
  }

  /** The inputs changed: a failure shown by the last Run is about texts that are gone. */
  stale(): void {
    if (this.results.querySelector('.lfd-fail')) this.results.replaceChildren();
  }

  /** Checks the inputs and S_C soon (after typing stops). */
  schedule(delayMs = 600): void {
    clearTimeout(this.timer);
    this.timer = window.setTimeout(() => void this.inspect(), delayMs);
  }

  private base(): { domain: string; problem: string; demo: string; state?: string } {
    const t = this.opts.texts();
    const state = this.state.text();
    return state === undefined ? t : { ...t, state };
  }

  /** Reads the inputs and S_C (no search): the demonstration states, LogicIn, the applicable actions. */
  async inspect(): Promise<void> {
    clearTimeout(this.timer);
    // Hidden (classical mode): showing Logic-LfD's diagnostics there would confuse.
    if (this.root.hidden || this.opts.busy()) return;
    const seq = ++this.seq;
    let r: LogicLfdResult;
    try {
      r = await this.opts.logicLfd({ ...this.base(), maxExpanded: 0, timeLimitMs: CHECK_TIMEOUT_MS }, CHECK_TIMEOUT_MS + 5000);
    } catch (e) {
      if (seq === this.seq && (e as Error).name !== 'CancelledError') this.verdict.textContent = (e as Error).message;
      return;
    }
    if (seq === this.seq) this.absorb(r);
  }

  /** Takes in what a result says about the inputs and S_C. */
  private absorb(r: LogicLfdResult): void {
    this.opts.diagnostics(r.diagnostics);
    this.demo = r.demo;
    if (r.demo) this.statics = r.statics;
    const stateRead = r.demo !== null && !INPUT_KINDS.has(r.kind) && r.kind !== 'state';
    if (stateRead) {
      this.logicIn = r.logicIn;
      this.state.update(r.fluents, r.state, r.applicable, r.demo?.states.length ?? 0);
    }
    this.renderDemo();
    if (!r.demo) this.verdict.replaceChildren(el('span', { class: 'lfd-fail' }, 'Fix the error above to see the demonstration states.'));
    else if (r.kind === 'state') this.verdict.replaceChildren(el('span', { class: 'lfd-fail' }, sc(), ' does not read: ', r.message));
    else this.verdict.replaceChildren(...this.verdictText(r));
  }

  private verdictText(r: LogicLfdResult): (Node | string)[] {
    const n = (this.demo?.states.length ?? 1) - 1;
    const k = r.logicIn;
    if (r.source === 'goal-holds') return [el('strong', {}, 'G holds in ', sc()), ': nothing to do.'];
    if (k === null) return [el('strong', {}, 'No demonstration state holds'), ' (no ', lk('k'), ' ⊆ ', sc(), '): search for one, then follow the demo.'];
    const then = k < n ? ['follow the demo from ', lk(k + 1, 'a'), '.'] : ['the demonstration is complete.'];
    return [el('strong', {}, lk(k), ' ⊆ ', sc()), ': LogicIn = ', String(k), ', ', ...then];
  }

  private renderDemo(): void {
    const d = this.demo;
    if (!d) {
      this.demoList.replaceChildren();
      this.demoInfo.textContent = '';
      this.lkFacts.hidden = true;
      return;
    }
    const sc = this.state.current();
    const holds = d.states.map((s) => s.every((f) => sc.has(f)));
    this.demoInfo.textContent = `N = ${d.actions.length}: L0 … L${d.actions.length}`;
    const items: HTMLElement[] = [];
    d.states.forEach((facts, k) => {
      const cls = ['lfd-lk', k === this.logicIn ? 'matched' : holds[k] ? 'holds' : '', k === this.selectedK ? 'current' : ''].join(' ');
      const b = el('button', { type: 'button', class: cls, 'data-k': String(k), title: `L${k}: ${facts.length} facts${holds[k] ? ', all in S_C' : ''} (click for the facts)` }, lk(k));
      b.onclick = () => this.selectK(k);
      items.push(el('li', { class: 'lfd-lk-item' }, b));
      if (k < d.actions.length) items.push(el('li', { class: 'demo-action', title: `a${k + 1}` }, d.actions[k]));
    });
    this.demoList.replaceChildren(...items);
    if (this.selectedK !== null) this.renderLk(this.selectedK);
  }

  private selectK(k: number): void {
    this.selectedK = this.selectedK === k ? null : k;
    this.renderDemo();
    if (this.selectedK === null) this.lkFacts.hidden = true;
  }

  /** The facts of L_k; those not in S_C marked. */
  private renderLk(k: number): void {
    const facts = this.demo?.states[k];
    if (!facts) return;
    const now = this.state.current();
    const missing = facts.filter((f) => !now.has(f)).length;
    const set = el('button', { type: 'button', id: 'lfd-set-lk' }, 'Set ', sc(), ' to ', lk(k));
    set.onclick = () => this.state.setToDemoState(k);
    this.lkFacts.hidden = false;
    this.lkFacts.replaceChildren(
      el('div', { class: 'lfd-row' }, el('strong', {}, lk(k)), el('span', { class: 'muted' }, ` · ${facts.length} facts · ${missing ? `${missing} not in ` : 'all in '}`, sc()), el('span', { class: 'grow' }), set),
      el('ul', { class: 'facts' }, ...facts.map((f) => el('li', now.has(f) ? {} : { class: 'missing', title: 'not in S_C' }, f))),
    );
  }

  private async apply(facts: string[], action: string): Promise<string[] | null> {
    const t = this.opts.texts();
    const problem = withInit(t.problem, [...this.statics, ...facts]);
    if (!problem) return this.fail('the problem has no (:init …) section');
    try {
      const r = await this.opts.logicLfd({ domain: t.domain, problem, demo: t.demo, after: action, maxExpanded: 0 }, CHECK_TIMEOUT_MS);
      return r.kind === 'state' || INPUT_KINDS.has(r.kind) ? this.fail(r.message) : r.state;
    } catch (e) {
      return this.fail((e as Error).message);
    }
  }

  private async walk(seed: number, maxSteps: number): Promise<{ facts: string[]; steps: number } | null> {
    try {
      const r = await this.opts.logicLfdPerturb({ ...this.opts.texts(), count: 1, seed, maxSteps });
      const s = r.states[0];
      if (!r.ok || !s) return this.fail(r.message || 'no state drawn');
      return { facts: s.facts, steps: s.steps };
    } catch (e) {
      return this.fail((e as Error).message);
    }
  }

  private fail(message: string): null {
    this.verdict.replaceChildren(el('span', { class: 'lfd-fail' }, message));
    return null;
  }

  /** Runs Logic-LfD from S_C in both modes (paper with planning from scratch beside it). */
  async run(): Promise<void> {
    clearTimeout(this.timer);
    ++this.seq;
    const input: LogicLfdInput = { ...this.base(), ...this.opts.search(), timeLimitMs: LFD_TIME_LIMIT_MS };
    const show = (p: LogicLfdResult | null, q: LogicLfdResult | null, running: Mode | null) =>
      this.results.replaceChildren(...renderResults(p, q, running));
    this.state.setBusy(true);
    try {
      show(null, null, 'paper');
      const paper = await this.opts.logicLfd({ ...input, mode: 'paper', compare: true }, 2 * LFD_TIME_LIMIT_MS + 5000);
      this.absorb(paper);
      if (INPUT_KINDS.has(paper.kind) || paper.kind === 'state') {
        this.results.replaceChildren(el('div', { class: 'lfd-fail' }, paper.message));
        return;
      }
      show(paper, null, 'prioritised');
      const prio = await this.opts.logicLfd({ ...input, mode: 'prioritised' }, LFD_TIME_LIMIT_MS + 5000);
      show(paper, prio, null);
    } catch (e) {
      const err = e as Error;
      const text = err.name === 'CancelledError' ? `Search ${err.message}.` : err.message;
      this.results.replaceChildren(el('div', { class: 'muted', id: 'lfd-stopped' }, text));
    } finally {
      this.state.setBusy(false);
    }
  }
}

/** S_C, the current state. */
function sc(): HTMLElement {
  return lk('C', 'S');
}

function help(): HTMLElement {
  return el(
    'p',
    { class: 'lfd-help' },
    'The demonstration passes through states ', lk(0), ' … ', lk('N'), ' (before and after each action ', lk('k', 'a'), '). ',
    'From the current state ', sc(), ', LogicIn takes the largest k with ', lk('k'), ' ⊆ ', sc(), ' and follows the demo from there; ',
    'when none holds, one search runs to some ', lk('k'), ' and the rest of the demo follows. ',
    'Paper mode joins the first ', lk('k'), ' reached, which may leave a longer merged plan (the paper’s stated drawback); ',
    'prioritised mode picks the cheapest prefix + demo left. ',
    el('a', { href: 'docs/your-own-domain.md', target: '_blank', rel: 'noopener' }, 'Your own domain'),
    '.',
  );
}
