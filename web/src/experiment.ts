/**
 * The Compare tab's experiment: Table I (`logic-lfd bench table1`) run on the page. Its tasks are
 * the CLI's (same benchmarks, task count and seed: the same initial states, draws and episodes),
 * run in a pool of workers (experiment-pool.ts) and joined by the wasm module's `table1Report`,
 * so the exported JSON is what `bench table1 --json` prints but for the wall-clock times. Levels
 * follow the task number as in the CLI (task i at L(i mod 4 + 1)); the level and method boxes
 * choose what the results and the CSV show. A click on an episode replays it on the Run tab.
 */
import type { Catalogue } from 'logic-lfd';
import { button, downloadJson, el } from './dom';
import { ExperimentWorker, Pool, PoolCancelled, poolSize } from './experiment-pool';
import { boxPlot, csv, episodesTable, type EpisodeRef, type Filter, labelOf, type Report, type Task, shownMethod, successTable } from './experiment-view';
import './experiment.css';

/** Table I's rows (`TABLE1_METHODS`, in order): the report's cells are checked against them. */
const TABLE1_ROWS = ['linear', 'tamp', 'logic-lfd (paper)', 'logic-lfd (prioritised)'];

/** What the experiment needs of the page. */
export interface ExperimentHost {
  /** The task folder the Run has open, if any (Table I cannot run one). */
  folderName(): string | null;
  /** Replays an episode log on the Run tab (`name`: the run's name in the notice). */
  replay(name: string, log: string): Promise<void>;
}

/** The sweep `table1Task` runs (the CLI's flags, and the optional budgets). */
interface SweepOptions {
  benchmarks: string[];
  tasks: number;
  seed: number;
  tampFallback: boolean;
  maxNodes?: number;
  maxTimeS?: number;
}

function check(name: string, label: string, checked: boolean, title = label): [HTMLLabelElement, HTMLInputElement] {
  const box = el('input', { type: 'checkbox', name, value: label.toLowerCase(), title });
  box.checked = checked;
  return [el('label', { class: 'check', title }, box, ` ${label}`), box];
}

function num(id: string, label: string, value: string, attrs: Record<string, string> = {}): HTMLInputElement {
  return el('input', { id, type: 'number', 'aria-label': label, title: label, value, ...attrs });
}

export class ExperimentPanel {
  readonly root: HTMLElement;
  private readonly benchBoxes: HTMLInputElement[];
  private readonly levelBoxes: HTMLInputElement[];
  private readonly methodBoxes: HTMLInputElement[];
  private readonly tasksIn = num('experiment-tasks', 'Tasks per benchmark (tasks 0 to N − 1, as bench table1 --tasks N numbers them)', '20', { min: '1', max: '1000', step: '1' });
  private readonly seedIn = num('experiment-seed', 'Seed of the task generator and the episodes (bench table1 --seed)', '1', { min: '0', step: '1' });
  private readonly nodesIn = num('experiment-nodes', 'States a search may expand per plan (empty: the default, as the CLI)', '', { min: '1', step: '1000', placeholder: 'default' });
  private readonly timeIn = num('experiment-time', 'Simulated seconds an episode may take (empty: the default, 240 s, as the CLI)', '', { min: '1', step: '10', placeholder: '240' });
  private readonly fallbackBox: HTMLInputElement;
  private readonly runBtn = button('experiment-run', 'Run Table I on these tasks in a pool of workers', '▶ Run experiment', 'primary');
  private readonly cancelBtn = button('experiment-cancel', 'Stop every worker of the pool', '■ Cancel');
  private readonly progress = el('progress', { id: 'experiment-progress', max: '1', value: '0' });
  private readonly progressText = el('span', { id: 'experiment-progress-text', class: 'muted small', 'aria-live': 'polite' });
  private readonly note = el('p', { id: 'experiment-note', class: 'muted small' });
  private readonly results = el('div', { id: 'experiment-results', class: 'experiment-results' });
  private readonly csvBtn = button('experiment-csv', 'Export the success table as CSV (one row per benchmark, method and level shown)', 'CSV');
  private readonly jsonBtn = button('experiment-json', 'Export Table I as JSON, in the form of bench table1 --json', 'JSON');
  private pool: Pool | null = null;
  private last: { options: SweepOptions; report: Report; tasks: Task[] } | null = null;

  constructor(
    private readonly host: ExperimentHost,
    catalogue: Catalogue,
  ) {
    const benches = catalogue.benchmarks.map((b) => check('experiment-benchmark', b.label, b.id === 'b1', b.description));
    this.benchBoxes = benches.map(([, box], i) => ((box.value = catalogue.benchmarks[i].id), box));
    const levels = catalogue.levels.map((l) => check('experiment-level', l.label, true, l.description));
    this.levelBoxes = levels.map(([, box], i) => ((box.value = catalogue.levels[i].id), box));
    const methods = TABLE1_ROWS.map((m) => check('experiment-method', shownMethod(m), true));
    this.methodBoxes = methods.map(([, box], i) => ((box.value = TABLE1_ROWS[i]), box));
    const [fallbackLabel, fallbackBox] = check('experiment-fallback', 'TAMP fallback', false, 'Let Logic-LfD plan to G from scratch when none of its skeletons binds (bench table1 --tamp-fallback)');
    this.fallbackBox = fallbackBox;
    const group = (legend: string, ...kids: Node[]) => el('fieldset', { class: 'experiment-group' }, el('legend', {}, legend), ...kids);
    this.root = el(
      'section',
      { id: 'experiment', class: 'experiment' },
      el('h2', {}, 'Experiment ', el('span', { class: 'muted' }, '— Table I on the page, as logic-lfd bench table1')),
      el(
        'div',
        { class: 'experiment-form' },
        group('Benchmarks', ...benches.map(([l]) => l)),
        group('Tasks', el('label', {}, 'N ', this.tasksIn), el('label', {}, 'seed ', this.seedIn)),
        group('Levels shown', ...levels.map(([l]) => l)),
        group('Methods shown', ...methods.map(([l]) => l)),
        group('Budget per episode', el('label', {}, 'nodes ', this.nodesIn), el('label', {}, 'sim s ', this.timeIn), fallbackLabel),
      ),
      el('div', { class: 'compare-row' }, this.runBtn, this.cancelBtn, this.progress, this.progressText, this.csvBtn, this.jsonBtn),
      this.note,
      this.results,
    );
    this.cancelBtn.disabled = true;
    this.csvBtn.disabled = this.jsonBtn.disabled = true;
    this.runBtn.onclick = () => void this.run();
    this.cancelBtn.onclick = () => this.cancel();
    this.csvBtn.onclick = () => this.last && download(csv(this.last.report, this.filter()), 'table1.csv', 'text/csv');
    this.jsonBtn.onclick = () => this.last && downloadJson(JSON.stringify(this.last.report.table), 'table1.json');
    for (const b of [...this.levelBoxes, ...this.methodBoxes]) b.onchange = () => this.show();
  }

  /** Says why the open task folder is not offered (Table I draws its tasks from the benchmarks). */
  refresh(): void {
    const folder = this.host.folderName();
    this.note.textContent = folder
      ? `The open task folder ${folder} cannot be run here: Table I draws random initial states from each benchmark's task generator, which a folder does not have.`
      : '';
  }

  private filter(): Filter {
    const on = (boxes: HTMLInputElement[]) => new Set(boxes.filter((b) => b.checked).map((b) => b.value));
    return { levels: on(this.levelBoxes), methods: on(this.methodBoxes) };
  }

  private options(): SweepOptions | string {
    const benchmarks = this.benchBoxes.filter((b) => b.checked).map((b) => b.value);
    if (!benchmarks.length) return 'Choose at least one benchmark.';
    const tasks = Math.floor(Number(this.tasksIn.value));
    if (!(tasks >= 1 && tasks <= 1000)) return 'Tasks per benchmark: a whole number from 1 to 1000.';
    const seed = Math.floor(Number(this.seedIn.value));
    if (!(seed >= 0 && Number.isSafeInteger(seed))) return 'Seed: a whole number from 0.';
    const o: SweepOptions = { benchmarks, tasks, seed, tampFallback: this.fallbackBox.checked };
    if (this.nodesIn.value !== '') o.maxNodes = Math.max(1, Math.floor(Number(this.nodesIn.value)));
    if (this.timeIn.value !== '') o.maxTimeS = Math.max(1, Number(this.timeIn.value));
    return o;
  }

  /** Runs the experiment; resolves when it ends, fails or is cancelled. */
  async run(): Promise<void> {
    const options = this.options();
    if (typeof options === 'string') {
      this.note.textContent = options;
      return;
    }
    this.pool?.cancel();
    const count = options.benchmarks.length * options.tasks;
    const pool = (this.pool = new Pool(poolSize(count)));
    const json = JSON.stringify(options);
    delete this.root.dataset.done;
    this.runBtn.disabled = true;
    this.cancelBtn.disabled = false;
    const budget = options.maxNodes !== undefined || options.maxTimeS !== undefined ? ' Budgets set: the CLI runs with the defaults, so its table may differ.' : '';
    this.note.textContent = `${options.benchmarks.map((b) => b.toUpperCase()).join(', ')} · tasks 0–${options.tasks - 1} · seed ${options.seed} · ${pool.size} worker${pool.size > 1 ? 's' : ''}.${budget}`;
    const shown = (done: number) => {
      this.progress.max = count;
      this.progress.value = done;
      this.progressText.textContent = `${done}/${count} tasks`;
      this.root.dataset.progress = `${done}/${count}`;
    };
    shown(0);
    try {
      const items = await pool.run(json, count, shown);
      const report = JSON.parse(await pool.report(json, items)) as Report;
      const rows = report.table.cells.slice(0, TABLE1_ROWS.length).map(labelOf);
      if (rows.join() !== TABLE1_ROWS.join()) throw new Error(`Table I's rows changed: ${rows.join(', ')}`);
      this.last = { options, report, tasks: items.map((t) => JSON.parse(t) as Task) };
      this.csvBtn.disabled = this.jsonBtn.disabled = false;
      this.show();
      this.root.dataset.done = 'true';
    } catch (e) {
      this.note.textContent = e instanceof PoolCancelled ? `Cancelled after ${this.progress.value}/${count} tasks: every worker was stopped.` : `The experiment stopped: ${(e as Error).message}`;
      this.root.dataset.done = e instanceof PoolCancelled ? 'cancelled' : 'failed';
    } finally {
      pool.close('done');
      if (this.pool === pool) this.pool = null;
      this.runBtn.disabled = false;
      this.cancelBtn.disabled = true;
    }
  }

  cancel(): void {
    this.pool?.cancel();
  }

  private show(): void {
    if (!this.last) return;
    const { report, tasks } = this.last;
    const f = this.filter();
    const levelOf = new Map(report.levels.flatMap((l) => l.items.map((i) => [i, l.level] as const)));
    const redrawn = report.table.redrawn.length ? `Redrawn as infeasible: ${report.table.redrawn.map((r) => `${r.benchmark.toUpperCase()} task ${r.task} (${r.draws} draws)`).join(', ')}.` : 'Every first draw was feasible.';
    this.results.replaceChildren(
      el('h2', {}, 'Success per method and level ', el('span', { class: 'muted' }, `(${report.table.tasks} tasks per benchmark, seed ${report.table.seed}; ${redrawn})`)),
      el('div', { class: 'experiment-scroll' }, successTable(report, f)),
      el('h2', {}, 'First-plan time per method ', el('span', { class: 'muted' }, '(wall clock: differs from run to run)')),
      boxPlot(report, f),
      el('h2', {}, 'Episodes ', el('span', { class: 'muted' }, '(click one to replay it on the Run tab)')),
      el('div', { class: 'experiment-scroll episodes' }, episodesTable(report, tasks, (i) => levelOf.get(i) ?? '', f, (e, row) => void this.replay(e, row))),
    );
  }

  /** Runs the episode again in a worker of its own, with its log, and replays the log on the Run. */
  private async replay(e: EpisodeRef, row: HTMLElement): Promise<void> {
    if (!this.last) return;
    row.classList.add('replaying');
    const w = new ExperimentWorker();
    try {
      const { log, end } = JSON.parse(await w.call({ kind: 'episode', options: JSON.stringify(this.last.options), index: e.index, run: e.run })) as { log: string; end: string };
      const won = this.last.tasks[e.index].runs[e.run].success_actions !== null;
      // The Run replays with its own parameters (TAMP fallback on, default budgets): a replay
      // that ends otherwise than the table's run would show another episode.
      if ((end === 'done') !== won) throw new Error(`the Run replays with its own parameters (TAMP fallback on, default budgets) and would end ${end === 'done' ? 'in success' : `as ${end}`}, unlike this run`);
      await this.host.replay(`${e.name.replace(/[^\w-]+/g, '-')}.json`, log);
    } catch (err) {
      this.note.textContent = `${e.name} could not be replayed: ${(err as Error).message}`;
    } finally {
      w.terminate('done');
      row.classList.remove('replaying');
    }
  }
}

function download(text: string, name: string, type: string): void {
  const a = el('a', { href: URL.createObjectURL(new Blob([text], { type })), download: name });
  a.click();
  URL.revokeObjectURL(a.href);
}
