/**
 * The Compare tab (a chunk of its own, loaded when the tab first opens): the experiment of
 * experiment.ts (Table I over many tasks, in a pool of workers) and, below it, one episode —
 * benchmark, blocks, seed, and one scripted disturbance (level and time) or the Run's recorded
 * drags, injections and cancels at their times — with every method of the catalogue (Logic-LfD
 * in each of its modes), one after another in a worker of its own (the Run's session is
 * untouched), and ends with a table: success, simulated execution time, replans, planning time
 * and the reason of a failure.
 */
import type { Catalogue, Frame, Level, Method, Mode, RobotChoice, SessionOptions } from 'logic-lfd';
import { descriptionOf, items, levelName } from './catalogue';
import { WorkerClient } from './client';
import { button, el, select } from './dom';
import { ExperimentPanel } from './experiment';
import { applyAll, type Disturbance, eventLabel, type Recorded, recordedDisturbances, recordedOf, scriptedDisturbance } from './compare-recorded';
import './compare.css';

/** One run of a comparison: method, mode, the row's name and tooltip. */
export interface Run {
  method: Method;
  mode: Mode;
  name: string;
  tip: string;
}

/** The runs of a comparison: every method in table order, the one the multi-goal mode steers
 * (Logic-LfD) once per mode, the others in the first (the default, paper). */
export function runsOf(c: Catalogue): Run[] {
  const [first] = c.modes;
  return c.methods.flatMap((m): Run[] =>
    m.id === 'logic-lfd'
      ? c.modes.map((mode) => ({ method: m.id, mode: mode.id, name: `${m.label} (${mode.label})`, tip: `${m.description} Mode: ${mode.description}` }))
      : [{ method: m.id, mode: first.id, name: m.label, tip: m.description }],
  );
}

/** Simulated seconds per request while an episode runs to its end. */
const CHUNK_S = 2;
/** An episode still running after this much simulated time is stopped (s; the core's own budget
 * ends episodes at 240 s). */
const MAX_SIM_S = 300;

/** One row of the results table. */
export interface CompareResult {
  name: string;
  success: boolean;
  /** Simulated seconds until done or failed. */
  timeS: number;
  replans: number;
  /** Wall time of all replans (ms). */
  planningMs: number;
  /** The status line at the end (the failure's reason). */
  message: string;
  /** What the disturbances did (or why they could not be applied). */
  disturbance: string;
}

/** The scenario a comparison runs. */
export interface CompareScript {
  options: Pick<SessionOptions, 'benchmark' | 'seed' | 'blocks' | 'skill'>;
  /** The starting world (scene JSON); the benchmark's template scene if absent. */
  scene?: string;
  /** Applied in order, each at its tick. */
  disturbances: Disturbance[];
  /** The task folder every method runs (its name and files) instead of the benchmark's task. */
  folder?: { name: string; files: Record<string, string> } | null;
  /** The robot in the arms' place, and its name (absent: the default, the Panda). */
  robot?: { choice: RobotChoice; name: string } | null;
}

/** Where a comparison's disturbances come from. */
type Source = 'scripted' | 'recorded';

const finished = (f: Frame) => f.status.kind === 'done' || f.status.kind === 'failed';

/** Runs one method on the script in `client`'s worker. */
async function runOne(client: WorkerClient, script: CompareScript, { method, mode, name }: Run): Promise<CompareResult> {
  const robot = script.robot ? { robot: script.robot.choice } : {};
  const options: SessionOptions & { robot?: RobotChoice } = { ...script.options, method, mode, ...robot };
  const { folder } = script;
  const opened = folder
    ? await client.call('openFolder', { files: folder.files, options: { dir: folder.name, method, mode, seed: options.seed, skill: options.skill, scene: script.scene, ...robot } })
    : await client.call('open', script.scene === undefined ? { options } : { options, scene: script.scene });
  const applied = await applyAll(client, opened, script.disturbances);
  let f = applied.frame;
  while (!finished(f) && f.t < MAX_SIM_S) f = await client.call('step', { dt: CHUNK_S });
  const log = JSON.parse(await client.call('episode', {})) as { replans: { time_ms: number }[] };
  return {
    name,
    success: f.status.kind === 'done',
    timeS: f.t,
    replans: f.replans,
    planningMs: log.replans.reduce((a, r) => a + r.time_ms, 0),
    message: finished(f) ? f.status.message : `stopped after ${MAX_SIM_S} s of simulated time`,
    disturbance: applied.notes.join('; '),
  };
}

/** What a comparison needs of the page: the Run's benchmark, blocks and seed, and its episode log. */
export interface CompareHost {
  scenario(): CompareScript['options'];
  /** The task folder the Run runs (null: the benchmark's task). */
  folder(): CompareScript['folder'];
  /** The robot the Run's arms are (null: the default, the Panda). */
  robot(): CompareScript['robot'];
  /** The Run's episode log (`Session.episodeJson()`). */
  episode(): Promise<string>;
  /** Replays an episode log on the Run tab, as Load does with a saved run, and shows the Run. */
  replay(name: string, log: string): Promise<void>;
}

export class ComparePanel {
  readonly root: HTMLElement;
  private readonly sourceSel = select<Source>(
    'compare-source',
    'Which disturbances every method meets',
    [
      ['scripted', 'a scripted disturbance'],
      ['recorded', 'the Run’s recorded disturbances'],
    ],
    'scripted',
  );
  private readonly levelSel: HTMLSelectElement;
  private readonly runs: Run[];
  private readonly atIn = el('input', { id: 'compare-at', type: 'number', min: '0', step: '0.1', value: '0.5', 'aria-label': 'Inject at (simulated seconds)', title: 'Inject at (simulated seconds)' });
  private readonly scripted: HTMLElement;
  /** Why the recorded disturbances cannot be chosen (shown while they cannot). */
  private readonly why = el('p', { id: 'compare-source-why', class: 'muted small', hidden: '' });
  private readonly runBtn = button('compare-run', 'Run every method on the same seed and disturbances', '▶ Compare', 'primary');
  private readonly body = el('tbody', {});
  private readonly note = el('p', { id: 'compare-note', class: 'muted small' });
  private client: WorkerClient | null = null;
  private recorded: Recorded | string = '';
  readonly experiment: ExperimentPanel;

  constructor(
    private readonly host: CompareHost,
    catalogue: Catalogue,
  ) {
    this.runs = runsOf(catalogue);
    this.levelSel = select('compare-level', 'Disturbance level', items(catalogue.levels), 'l3');
    for (const o of this.levelSel.options) o.title = descriptionOf(catalogue.levels, o.value);
    this.scripted = el('span', { class: 'compare-scripted' }, el('label', {}, 'inject ', this.levelSel), el('label', {}, 'at ', this.atIn, ' s'));
    this.experiment = new ExperimentPanel({ folderName: () => host.folder()?.name ?? null, replay: (name, log) => host.replay(name, log) }, catalogue);
    this.root = el(
      'div',
      { class: 'compare' },
      this.experiment.root,
      el('h2', { class: 'episode-head' }, 'One episode, every method'),
      el('p', { class: 'muted' }, 'The same seed and the same disturbances for every method, run one after another in the background (the Run keeps its own episode).'),
      el('div', { class: 'compare-row' }, this.sourceSel, this.scripted, this.runBtn),
      this.why,
      this.note,
      el(
        'table',
        { id: 'compare-table', class: 'compare-table' },
        // Soft hyphens: the narrow figure columns break their headers instead of overlapping.
        el('thead', {}, el('tr', {}, ...['Method', 'Result', 'Time (s)', 'Re\u00adplans', 'Plan\u00adning (ms)', 'Reason'].map((h) => el('th', {}, h)))),
        this.body,
      ),
    );
    this.runBtn.onclick = () => void this.run();
    this.sourceSel.onchange = () => this.showSource();
    // The Run may have recorded more since: look again before the list opens.
    this.sourceSel.onfocus = () => void this.refresh();
    this.showRows([]);
    this.showSource();
  }

  /** Reads the Run's episode again: the recorded disturbances, or why there are none. */
  async refresh(): Promise<void> {
    this.experiment.refresh();
    try {
      this.recorded = recordedOf(await this.host.episode());
    } catch (e) {
      this.recorded = `The Run has no episode to replay (${(e as Error).message}).`;
    }
    this.showSource();
  }

  private showSource(): void {
    const reason = typeof this.recorded === 'string' ? this.recorded || 'Reading the Run’s episode…' : null;
    const option = this.sourceSel.querySelector<HTMLOptionElement>('option[value="recorded"]')!;
    option.disabled = reason !== null;
    if (reason !== null && this.sourceSel.value === 'recorded') this.sourceSel.value = 'scripted';
    this.why.textContent = reason ?? '';
    this.why.hidden = reason === null;
    this.scripted.hidden = this.sourceSel.value === 'recorded';
  }

  /** The script of the chosen source (null: the recorded disturbances are gone). */
  private async script(): Promise<CompareScript | null> {
    if (this.sourceSel.value === 'recorded') {
      await this.refresh();
      const r = this.recorded;
      if (typeof r === 'string') return null;
      return { options: r.options, scene: r.scene, disturbances: recordedDisturbances(r), folder: this.host.folder(), robot: this.host.robot() };
    }
    const level = this.levelSel.value as Level;
    const at = Math.max(0, Number(this.atIn.value) || 0);
    return { options: this.host.scenario(), disturbances: [scriptedDisturbance(level, at)], folder: this.host.folder(), robot: this.host.robot() };
  }

  /** The comparison's one-line description: the scenario and its disturbances. */
  private describe(script: CompareScript): string {
    const o = script.options;
    const task = script.folder ? `task folder ${script.folder.name}` : `${o.benchmark.toUpperCase()}${o.blocks ? ` · ${o.blocks} blocks` : ''}`;
    const head = `${task}${script.robot ? ` · ${script.robot.name}` : ''} · seed ${o.seed}`;
    const r = this.recorded;
    if (this.sourceSel.value === 'recorded' && typeof r !== 'string') return `${head} · the Run’s recorded disturbances: ${r.events.map((e) => eventLabel(e, r.dt)).join(', ')}`;
    return `${head} · ${levelName(this.levelSel.value)} at ${Math.max(0, Number(this.atIn.value) || 0)} s`;
  }

  /** Runs the comparison with the chosen disturbances; resolves to the table's rows. */
  async run(): Promise<CompareResult[]> {
    this.runBtn.disabled = true;
    this.client?.terminate('a new comparison started');
    const results: CompareResult[] = [];
    const script = await this.script();
    if (!script) {
      this.runBtn.disabled = false;
      return results;
    }
    const client = (this.client = new WorkerClient(() => {}));
    this.note.textContent = this.describe(script);
    try {
      await client.ready;
      for (const run of this.runs) {
        this.showRows(results, run.name);
        results.push(await runOne(client, script, run));
      }
      this.showRows(results);
      this.root.dataset.done = 'true';
    } catch (e) {
      this.note.textContent = `The comparison stopped: ${(e as Error).message}`;
    } finally {
      client.terminate('done');
      if (this.client === client) this.client = null;
      this.runBtn.disabled = false;
    }
    return results;
  }

  private showRows(results: CompareResult[], running?: string): void {
    delete this.root.dataset.done;
    const rows = this.runs.map(({ name, tip }) => {
      const r = results.find((x) => x.name === name);
      const head = el('th', { title: tip }, name);
      if (!r) return el('tr', { class: 'pending' }, head, el('td', { colspan: '5', class: 'muted' }, name === running ? 'running…' : '—'));
      return el(
        'tr',
        { class: r.success ? 'ok' : 'fail', 'data-method': name },
        head,
        el('td', {}, r.success ? '✓ success' : '✗ failed'),
        el('td', {}, r.timeS.toFixed(1)),
        el('td', {}, String(r.replans)),
        el('td', {}, r.planningMs.toFixed(1)),
        el('td', { class: 'reason', title: r.disturbance }, r.success ? '' : r.message),
      );
    });
    this.body.replaceChildren(...rows);
  }
}
