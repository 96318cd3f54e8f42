/**
 * The Logic-LfD view's results: paper and prioritised mode side by side, each as one plan list
 * (the new prefix the multi-goal search found, then the demonstration suffix it joins at L_k),
 * which mode is shorter, and planning from scratch for comparison. Plain rendering, no state.
 */
import type { LogicLfdResult, LogicLfdStats, Mode } from 'logic-lfd';
import { el, lk } from './dom';

/** What each mode joins, as its column explains it (a new mode needs a line: the type asks). */
const JOINS: Record<Mode, () => (Node | string)[]> = {
  paper: () => ['the first ', lk('k'), ' reached'],
  prioritised: () => ['cheapest prefix + demo left'],
};

function ms(s: LogicLfdStats): string {
  return `${s.expanded} expanded · ${s.timeMs < 10 ? s.timeMs.toFixed(2) : s.timeMs.toFixed(0)} ms`;
}

function how(r: LogicLfdResult): (Node | string)[] {
  if (r.source === 'goal-holds') return ['G holds in S_C: nothing to do'];
  if (r.source === 'logic-in') return ['LogicIn: ', lk(r.k ?? 0), ' ⊆ S_C, no search'];
  return ['multi-goal search: ', ms(r.stats)];
}

/** One mode's column: summary, then the merged plan with prefix lines "new" and suffix lines "demo a_j". */
function column(mode: Mode, r: LogicLfdResult | null, pending: boolean): HTMLElement {
  const head = el('h3', {}, mode, el('span', { class: 'lfd-joins muted' }, ...JOINS[mode]()));
  const col = el('div', { class: 'lfd-col', id: `lfd-col-${mode}`, 'data-mode': mode }, head);
  if (!r) {
    col.append(el('div', { class: 'muted' }, pending ? 'Searching…' : '—'));
    return col;
  }
  if (!r.ok) {
    col.append(el('div', { class: 'lfd-fail' }, r.message || r.kind), el('div', { class: 'muted small' }, ms(r.stats)));
    return col;
  }
  const k = r.k;
  col.append(
    el(
      'div',
      { class: 'lfd-sum', 'data-k': k === null ? '' : String(k) },
      k === null ? 'no L_k · ' : el('span', {}, 'k = ', String(k), ' · '),
      `${r.plan.length} actions · cost ${r.cost ?? '–'}`,
    ),
    el('div', { class: 'muted small' }, ...how(r), r.source === 'multi-goal' ? ` · ${r.prefix.length} new` : ''),
  );
  if (r.valid === false) col.append(el('div', { class: 'lfd-fail small' }, 'The validator rejected this plan from S_C.'));
  const first = (k ?? 0) + 1;
  const items: HTMLElement[] = r.prefix.map((a) => el('li', { class: 'new' }, el('span', { class: 'tag new' }, 'new'), el('span', {}, a)));
  if (k !== null && r.prefix.length > 0) items.push(el('li', { class: 'join' }, '↳ reaches ', lk(k), ', demo follows'));
  r.suffix.forEach((a, i) => items.push(el('li', { class: 'demo' }, el('span', { class: 'tag demo' }, 'demo a', el('sub', {}, String(first + i))), el('span', {}, a))));
  if (items.length === 0) items.push(el('li', { class: 'empty muted' }, 'empty plan: G holds'));
  col.append(el('ol', { class: 'plan-list lfd-plan', 'aria-label': `Logic-LfD plan, ${mode} mode` }, ...items));
  return col;
}

/** Which mode gives the shorter merged plan (by cost, then by length). */
function verdict(paper: LogicLfdResult, prio: LogicLfdResult): string {
  if (!paper.ok || !prio.ok) return '';
  const p = [paper.cost ?? 0, paper.plan.length];
  const q = [prio.cost ?? 0, prio.plan.length];
  const say = (r: LogicLfdResult) => `${r.plan.length} actions (cost ${r.cost})`;
  if (p[0] === q[0] && p[1] === q[1]) return `Same length in both modes: ${say(paper)}.`;
  const prioBetter = q[0] < p[0] || (q[0] === p[0] && q[1] < p[1]);
  return prioBetter
    ? `prioritised is shorter: ${say(prio)} vs ${say(paper)}; paper mode stopped at the first L_k it reached.`
    : `paper is shorter: ${say(paper)} vs ${say(prio)}.`;
}

function scratchLine(paper: LogicLfdResult | null): HTMLElement {
  const s = paper?.scratch;
  if (!s) return el('div', { id: 'lfd-scratch', class: 'muted small' });
  const text = s.ok ? `${s.plan.length} actions · cost ${s.cost} · ${ms(s.stats)}` : `no plan · ${ms(s.stats)}`;
  return el('div', { id: 'lfd-scratch', class: 'lfd-scratch' }, el('strong', {}, 'From scratch'), el('span', { class: 'muted' }, ' (classical, same search, to G): '), text);
}

/** The results panel: both columns, the comparison and the from-scratch line. */
export function renderResults(paper: LogicLfdResult | null, prio: LogicLfdResult | null, running: Mode | null): HTMLElement[] {
  const cols = el(
    'div',
    { class: 'lfd-cols' },
    column('paper', paper, running === 'paper'),
    column('prioritised', prio, running === 'prioritised'),
  );
  const cmp = paper && prio ? verdict(paper, prio) : '';
  return [cols, el('div', { id: 'lfd-compare', class: 'lfd-compare' }, cmp), scratchLine(paper)];
}
