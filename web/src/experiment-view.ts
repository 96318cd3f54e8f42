/**
 * The Compare experiment's results, drawn from what the wasm module's `table1Report` returns:
 * success per method × level with its 95 % Wilson interval, a box plot of first-plan times per
 * method (plain SVG), failures grouped logic / motion / budget, the episodes (one row per task and
 * method, a click replays one) and the CSV export. Nothing here recomputes Table I: every count
 * comes from the report's cells; only the box plot's quartiles and the medians are drawn here.
 */
import { catalogue, entryOf, levelName } from './catalogue';
import { el } from './dom';

/** A cell of `logic-lfd bench table1 --json`. */
export interface Table1Cell {
  benchmark: string;
  method: string;
  mode: string;
  successes: number;
  tasks: number;
  plan_ms: number[];
  search_ms: number[];
  bind_ms: number[];
  fallbacks: number;
  replans: number[];
  actions: number[];
  failures: [string, number][];
}

/** `logic-lfd bench table1 --json`. */
export interface Table1 {
  tasks: number;
  seed: number;
  cells: Table1Cell[];
  redrawn: { benchmark: string; task: number; draws: number }[];
  tamp_fallback: boolean;
  robots?: string[];
}

export type Interval = [number, number];
export type Group = 'logic' | 'motion' | 'budget';

/** `table1Report`'s answer. */
export interface Report {
  table: Table1;
  intervals: Interval[];
  levels: { level: string; items: number[]; table: Table1; intervals: Interval[] }[];
  groups: Record<string, Group>;
}

/** One method's run from one task (`Table1Run`). */
export interface Run {
  plan_ms: number | null;
  bind_ms: number | null;
  fallbacks: number;
  replans: number;
  success_actions: number | null;
  failure: string | null;
}

/** One item of the sweep (`Table1Task`). */
export interface Task {
  benchmark: string;
  task: number;
  draw: number;
  runs: Run[];
}

/** What the results show: the levels and the Table I rows (`method_label`s) chosen. */
export interface Filter {
  levels: Set<string>;
  methods: Set<string>;
}

/** Table I's row name of a cell, as `Table1Cell::method_label` writes it. */
export const labelOf = (c: Pick<Table1Cell, 'method' | 'mode'>): string => (c.method === 'logic-lfd' ? `logic-lfd (${c.mode})` : c.method);

/** A Table I row name as the page's selects write it: `logic-lfd (paper)` → "Logic-LfD (paper)". */
export function shownMethod(label: string): string {
  const [, method, mode] = /^(\S+)(?: \((\S+)\))?$/.exec(label) ?? [];
  const c = catalogue();
  const m = entryOf(c?.methods ?? [], method)?.label ?? method ?? label;
  return mode ? `${m} (${entryOf(c?.modes ?? [], mode)?.label ?? mode})` : m;
}

/** A level's cell: the page's name of the disturbance, the paper's in the tooltip. */
const levelCell = (level: string) => el('td', { title: `the paper’s ${level.toUpperCase()}` }, levelName(level));

const GROUPS: Group[] = ['logic', 'motion', 'budget'];

function quantile(sorted: number[], q: number): number {
  const at = (sorted.length - 1) * q;
  const lo = Math.floor(at);
  const hi = Math.ceil(at);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * (at - lo);
}

const median = (v: number[]): number | null => (v.length ? quantile([...v].sort((a, b) => a - b), 0.5) : null);
const ms = (v: number | null): string => (v === null ? '—' : v < 10 ? v.toFixed(2) : v.toFixed(1));
const pct = (x: number): string => `${Math.round(100 * x)} %`;
const mean = (v: number[]): number | null => (v.length ? v.reduce((a, b) => a + b, 0) / v.length : null);

/** The failures of a cell per group. */
function grouped(c: Table1Cell, groups: Record<string, Group>): Record<Group, number> {
  const out: Record<Group, number> = { logic: 0, motion: 0, budget: 0 };
  for (const [kind, n] of c.failures) out[groups[kind] ?? 'logic'] += n;
  return out;
}

/** A row of the success table and of the CSV: one benchmark, method and level (or all levels). */
interface Row {
  benchmark: string;
  method: string;
  level: string;
  cell: Table1Cell;
  ci: Interval;
}

function rows(r: Report, f: Filter, withAll: boolean): Row[] {
  const out: Row[] = [];
  r.table.cells.forEach((cell, i) => {
    const method = labelOf(cell);
    if (!f.methods.has(method)) return;
    for (const l of r.levels) {
      if (!f.levels.has(l.level)) continue;
      const c = l.table.cells[i];
      if (c.tasks > 0) out.push({ benchmark: cell.benchmark, method, level: l.level, cell: c, ci: l.intervals[i] });
    }
    if (withAll) out.push({ benchmark: cell.benchmark, method, level: 'all', cell, ci: r.intervals[i] });
  });
  return out;
}

/** The success table: rows benchmark × method × level, then each method over all levels. */
export function successTable(r: Report, f: Filter): HTMLTableElement {
  const head = ['Bench\u00admark', 'Method', 'Level', 'Success', '95 % interval (Wilson)', 'First plan ms, median (search / binding)', 'Re-plans after the first (mean)', 'Failures logic / motion / budget'];
  const body = rows(r, f, true).map(({ benchmark, method, level, cell: c, ci }) => {
    const g = grouped(c, r.groups);
    const kinds = c.failures.map(([k, n]) => `${k} ×${n} (${r.groups[k] ?? 'logic'})`).join(', ');
    return el(
      'tr',
      { class: level === 'all' ? 'all' : '', 'data-method': method, 'data-level': level },
      el('td', {}, benchmark.toUpperCase()),
      el('th', {}, shownMethod(method)),
      level === 'all' ? el('td', {}, 'all') : levelCell(level),
      el('td', { class: 'num' }, `${pct(c.successes / Math.max(1, c.tasks))} (${c.successes}/${c.tasks})`),
      el('td', { class: 'num' }, `${pct(ci[0])} – ${pct(ci[1])}`),
      el('td', { class: 'num' }, c.plan_ms.length ? `${ms(median(c.plan_ms))} (${ms(median(c.search_ms))} / ${ms(median(c.bind_ms))})` : '—'),
      el('td', { class: 'num' }, mean(c.replans)?.toFixed(2) ?? '—'),
      el('td', { class: 'num', title: kinds || 'none' }, GROUPS.map((k) => g[k]).join(' / ')),
    );
  });
  return el(
    'table',
    { id: 'experiment-success', class: 'experiment-table' },
    el('thead', {}, el('tr', {}, ...head.map((h) => el('th', {}, h)))),
    el('tbody', {}, ...body),
  );
}

const csvField = (v: string | number): string => (typeof v === 'number' ? String(v) : /[",\n]/.test(v) ? `"${v.replace(/"/g, '""')}"` : v);

/** The CSV: one row per benchmark, method and level shown. */
export function csv(r: Report, f: Filter): string {
  const head = ['benchmark', 'method', 'level', 'successes', 'tasks', 'success_rate', 'ci95_low', 'ci95_high', 'first_plan_ms_median', 'search_ms_median', 'bind_ms_median', 'replans_after_first_mean', 'failures_logic', 'failures_motion', 'failures_budget'];
  const lines = rows(r, f, false).map(({ benchmark, method, level, cell: c, ci }) => {
    const g = grouped(c, r.groups);
    const num = (v: number | null) => (v === null ? '' : Number(v.toFixed(4)));
    return [benchmark, method, level, c.successes, c.tasks, num(c.successes / Math.max(1, c.tasks)), num(ci[0]), num(ci[1]), num(median(c.plan_ms)), num(median(c.search_ms)), num(median(c.bind_ms)), num(mean(c.replans)), g.logic, g.motion, g.budget]
      .map(csvField)
      .join(',');
  });
  return [head.join(','), ...lines].join('\n') + '\n';
}

const SVG = 'http://www.w3.org/2000/svg';
function svg(tag: string, attrs: Record<string, string | number>, text?: string): SVGElement {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

/** A horizontal box plot of the first-plan times per method (all benchmarks and levels shown):
 * whiskers at the extremes, the box from the first to the third quartile, the median marked. */
export function boxPlot(r: Report, f: Filter): HTMLElement {
  const byMethod = new Map<string, number[]>();
  r.table.cells.forEach((_, i) => {
    const method = labelOf(r.table.cells[i]);
    if (!f.methods.has(method)) return;
    const times = r.levels.filter((l) => f.levels.has(l.level)).flatMap((l) => l.table.cells[i].plan_ms);
    byMethod.set(method, [...(byMethod.get(method) ?? []), ...times]);
  });
  const series = [...byMethod].filter(([, v]) => v.length > 0);
  const max = Math.max(1e-3, ...series.flatMap(([, v]) => v));
  const [W, left, right, rowH, top] = [640, 170, 16, 30, 8];
  const H = top + rowH * Math.max(1, series.length) + 34;
  const x = (v: number) => left + ((W - left - right) * v) / max;
  const root = svg('svg', { viewBox: `0 0 ${W} ${H}`, class: 'experiment-box', role: 'img', 'aria-label': 'First-plan time per method (ms)' });
  for (let k = 0; k <= 4; k++) {
    const v = (max * k) / 4;
    root.append(svg('line', { x1: x(v), x2: x(v), y1: top, y2: H - 28, class: 'grid' }), svg('text', { x: x(v), y: H - 14, 'text-anchor': 'middle' }, ms(v)));
  }
  root.append(svg('text', { x: (left + W - right) / 2, y: H - 1, 'text-anchor': 'middle' }, 'first-plan time (ms, wall clock)'));
  series.forEach(([method, v], i) => {
    const s = [...v].sort((a, b) => a - b);
    const [q1, q2, q3] = [quantile(s, 0.25), quantile(s, 0.5), quantile(s, 0.75)];
    const y = top + rowH * i + rowH / 2;
    const g = svg('g', { 'data-method': method });
    g.append(
      svg('title', {}, `${method}: ${s.length} plans; min ${ms(s[0])}, quartiles ${ms(q1)} / ${ms(q2)} / ${ms(q3)}, max ${ms(s[s.length - 1])} ms`),
      svg('text', { x: left - 8, y: y + 4, 'text-anchor': 'end' }, shownMethod(method)),
      svg('line', { x1: x(s[0]), x2: x(s[s.length - 1]), y1: y, y2: y, class: 'whisker' }),
      svg('rect', { x: x(q1), y: y - 9, width: Math.max(1, x(q3) - x(q1)), height: 18, class: 'box' }),
      svg('line', { x1: x(q2), x2: x(q2), y1: y - 9, y2: y + 9, class: 'median' }),
    );
    root.append(g);
  });
  const wrap = el('figure', { id: 'experiment-boxplot', class: 'experiment-figure' });
  wrap.append(root);
  if (!series.length) wrap.append(el('figcaption', { class: 'muted small' }, 'No method shown planned.'));
  return wrap;
}

/** One episode row: item `index`, method `run` (Table I's order). */
export interface EpisodeRef {
  index: number;
  run: number;
  name: string;
}

/** The episodes: one row per task and method shown; `onPick` hears a click (or Enter). */
export function episodesTable(r: Report, tasks: Task[], levelOf: (index: number) => string, f: Filter, onPick: (e: EpisodeRef, row: HTMLElement) => void): HTMLTableElement {
  const perBench = r.table.cells.length / Math.max(1, new Set(r.table.cells.map((c) => c.benchmark)).size);
  const body: HTMLElement[] = [];
  tasks.forEach((t, index) => {
    const level = levelOf(index);
    if (!f.levels.has(level)) return;
    t.runs.forEach((run, k) => {
      const cell = r.table.cells[Math.floor(index / r.table.tasks) * perBench + k];
      const method = labelOf(cell);
      if (!f.methods.has(method)) return;
      const ok = run.success_actions !== null;
      const group = run.failure ? (r.groups[run.failure] ?? 'logic') : '';
      const name = `${t.benchmark} task ${t.task} ${method}`;
      const tr = el(
        'tr',
        { class: ok ? 'ok' : 'fail', tabindex: '0', title: `Replay ${name} on the Run tab`, 'data-index': String(index), 'data-run': String(k) },
        el('td', {}, t.benchmark.toUpperCase()),
        el('td', { class: 'num' }, String(t.task)),
        levelCell(level),
        el('th', {}, shownMethod(method)),
        el('td', {}, ok ? `✓ ${run.success_actions} actions` : '✗ failed'),
        el('td', { class: 'num' }, run.plan_ms === null ? '—' : `${ms(run.plan_ms)} (${ms(run.plan_ms - (run.bind_ms ?? 0))} / ${ms(run.bind_ms)})`),
        el('td', { class: 'num' }, String(run.replans)),
        el('td', { class: 'reason' }, run.failure ? `${run.failure} (${group})` : ''),
      );
      const pick = () => onPick({ index, run: k, name }, tr);
      tr.onclick = pick;
      tr.onkeydown = (e) => {
        if (e.key === 'Enter') pick();
      };
      body.push(tr);
    });
  });
  const head = ['Bench\u00admark', 'Task', 'Level', 'Method', 'Result', 'First plan, ms (search / binding)', 'Re-plans after the first', 'Failure (group)'];
  return el(
    'table',
    { id: 'experiment-episodes', class: 'experiment-table episodes' },
    el('thead', {}, el('tr', {}, ...head.map((h) => el('th', {}, h)))),
    el('tbody', {}, ...body),
  );
}
