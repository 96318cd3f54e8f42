/**
 * "Why L_k?": the candidates of one Logic-LfD replan as a table — the prefix cost its search found
 * from S_C to each L_k, the demonstration left after it (c_k) and the total — and one sentence on
 * why the mode joined the L_k it did. Loaded only when the user first asks (a chunk of its own).
 */
import type { Alternative, Mode, Replan } from 'logic-lfd';
import { el, lk, lkText } from './dom';
import './why-join.css';

const name = (a: Alternative): string => (a.k == null ? 'G' : lkText(a.k));

const STATUS: Record<Alternative['status'], string> = {
  joined: 'joined',
  reached: 'reached',
  unreached: 'not reached (search stopped)',
  'not-searched': 'not searched',
  'not-cheaper': 'no cheaper plan (proved)',
};

/** The rule the mode applied, and where the other mode would have chosen differently. */
export function whySentence(r: Replan, mode: Mode): string {
  const alts = r.alternatives;
  const j = alts.find((a) => a.status === 'joined');
  if (!j) return '';
  if (j.prefix === 0 && alts.every((a) => a === j || a.status === 'not-searched')) {
    return `LogicIn: ${name(j)} already holds in S_C (the highest such k), so the plan is the demonstration after it; no search ran.`;
  }
  const withTotal = alts.filter((a) => a.total != null);
  const cheapest = withTotal.reduce((b, a) => (a.total! < b.total! ? a : b), j);
  if (mode === 'prioritised') {
    const ties = withTotal.filter((a) => a !== j && a.total === j.total).map(name);
    const tie = ties.length ? ` ${ties.join(', ')} ${ties.length > 1 ? 'are' : 'is'} as short; the search completed ${name(j)} first.` : '';
    const proved = alts.some((a) => a.status === 'not-cheaper') ? ' The search proved that no other L_k gives a shorter plan.' : '';
    return `Prioritised: the search minimises prefix + demonstration left, so it joined ${name(j)} with the least total, ${j.total} (${j.prefix} new + ${j.suffix} demonstrated).${tie}${proved}`;
  }
  const first = `Paper: all L_k have equal priority; the search stops at the first state satisfying any of them — the cheapest prefix (${j.prefix}) — and joins the one there with the least demonstration left.`;
  if (cheapest !== j && cheapest.total! < j.total!) {
    return `${first} Prioritised mode would join ${name(cheapest)}: total ${cheapest.total} instead of ${j.total}.`;
  }
  const unreached = alts.some((a) => a.status === 'unreached');
  return unreached ? `${first} L_k the search did not reach may still be cheaper in total; prioritised mode would search for them.` : first;
}

/** The panel: the table of candidates (searched ones first by total) and the sentence. */
export function whyJoinPanel(r: Replan, mode: Mode): HTMLElement {
  const rows = [...r.alternatives].sort((a, b) => (a.total ?? Infinity) - (b.total ?? Infinity) || (a.k ?? 1e9) - (b.k ?? 1e9));
  const cell = (v: number | undefined) => el('td', { class: 'num' }, v == null ? '–' : String(v));
  const table = el(
    'table',
    { class: 'why-table' },
    el('thead', {}, el('tr', {}, ...['state', 'prefix', 'demo left', 'total', ''].map((h) => el('th', {}, h)))),
    el(
      'tbody',
      {},
      ...rows.map((a) =>
        el('tr', { class: `alt ${a.status}` }, el('td', {}, a.k == null ? 'G' : lk(a.k)), cell(a.prefix), cell(a.suffix), cell(a.total), el('td', { class: 'muted' }, STATUS[a.status])),
      ),
    ),
  );
  return el(
    'div',
    { class: 'why-join', role: 'region', 'aria-label': `why ${r.k == null ? 'G' : `L${r.k}`}` },
    el('p', { class: 'why-sentence' }, whySentence(r, mode)),
    table,
    el('p', { class: 'muted small' }, 'Costs are sums of action costs: prefix = the new plan from S_C to the state, as found by this replan\u2019s search; demo left = c_k.'),
  );
}
