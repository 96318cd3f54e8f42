/**
 * The Run's session, driven from the top bar and the 3-D view: open a benchmark (or a scene file),
 * play, pause, step, reset, change the speed, inject a disturbance, cancel the plan, drop a dragged
 * block, save the scene, copy the permalink; and the frames the worker pushes while it plays.
 */
import type { Benchmark, Frame, Level, Method, Mode } from 'logic-lfd';
import type { OpenFolder } from './folder';
import { goalFacts, goalWords } from './guide';
import type { DropRequest, View } from './view';
import type { WorkerClient } from './client';
import { catalogue, entryOf, levelName, withLevel, withoutLevel } from './catalogue';
import { downloadJson, el, guard } from './dom';
import type { FirstVisitHint } from './hint';
import type { FrameRenderer } from './frame-renderer';
import type { History } from './history';
import { FOLDER, GALLERY, OPEN_FOLDER, TAUGHT, galleryValue, setBlockChoices, setFolderChoice, type Layout } from './layout';
import type { FromWorker } from './protocol';
import { OPEN_ROBOT, ROBOT_FOLDER, robotFromUrl, robotLabel, robotOption, setRobotChoice, type RobotPick } from './robot-choice';
import { blocksFor, parseSeed, recordStep, taskKey, updateUrl, type PageState } from './state';
import type { StatusBar } from './status-bar';
import type { Tabs } from './tabs';

export interface SessionParts {
  state: PageState;
  ui: Layout;
  client: WorkerClient;
  view: View;
  renderer: FrameRenderer;
  /** Recorded frames and markers (the timeline scrubs through them). */
  history: History;
  status: StatusBar;
  /** The side tabs (made after the controls: they need the playback). */
  tabs: () => Tabs;
}

/** `m` as the end of a sentence: a full stop unless it has one. */
const sentence = (m: string) => (/[.!?]$/.test(m.trim()) ? m.trim() : `${m.trim()}.`);
const isFinished = (kind: string) => kind === 'done' || kind === 'failed';


export class SessionControls {
  /** The first-visit hint, once its chunk has loaded (after the first frame). */
  private hint: FirstVisitHint | null = null;
  private goal = '';
  /** Whether the session is the scenario's own (not a replay, a scene or a taught task), so a
   * fresh worker can open it again. */
  private reopenable = false;
  /** A search inside the worker's step reports progress: the worker answers nothing meanwhile. */
  private searching = false;

  constructor(private readonly p: SessionParts) {}

  /** Shows the first-visit hint (unless dismissed before) with the current goal. */
  setHint(h: FirstVisitHint): void {
    this.hint = h;
    h.setGoal(this.goal);
  }

  /** Runs a UI action; a rejected call (no session, a refused request) becomes a notice. */
  guard(f: () => unknown): Promise<void> {
    return guard(f, (m) => this.p.status.notice(m, 'error'));
  }

  setPlaying(on: boolean): void {
    this.p.state.playing = on;
    const b = this.p.ui.controls.playBtn;
    b.textContent = on ? '❚❚ Pause' : '▶ Play';
    b.setAttribute('aria-label', on ? 'Pause (Space)' : 'Play (Space)');
    b.setAttribute('aria-pressed', String(on));
  }

  async play(): Promise<void> {
    // Play first returns a view scrubbed back to the live session.
    if (this.p.history.viewing !== null) this.p.history.view(null);
    const f = this.p.state.frame;
    if (this.p.tabs().teach?.active) {
      this.p.status.notice('Teach mode owns the view: run the taught task, or open the Run tab to play.', 'info');
      return;
    }
    if (this.p.state.dragging) {
      // The world stays still under the user's hand; it plays once the block is dropped.
      this.p.state.resumeAfterDrag = true;
      return;
    }
    if (f && isFinished(f.status.kind)) {
      // Nothing changed since the end: say what reopens the episode instead of a dead button.
      this.p.status.notice(
        f.status.kind === 'done'
          ? 'The goal holds: drag a block or inject a disturbance and the robot replans.'
          : 'The run failed: move a block to fix the scene, then press Play to resume.',
        'info',
      );
      return;
    }
    this.setPlaying(true);
    await this.p.client.call('play', { speed: this.p.state.speed });
  }

  /** A drag begins: the world stops while the user holds the block (resumed on the drop). */
  async dragStart(): Promise<void> {
    const { state } = this.p;
    this.hint?.dismiss();
    state.resumeAfterDrag = state.playing;
    state.dragging = true;
    if (state.playing) await this.pause();
  }

  /** A drag ended without a drop (refused, cancelled): play on if it played before. */
  async dragEnd(): Promise<void> {
    const { state } = this.p;
    state.dragging = false;
    if (!state.playing && state.resumeAfterDrag) await this.play();
  }

  async pause(): Promise<void> {
    this.setPlaying(false);
    const f = await this.p.client.call('pause', {});
    if (f) this.p.renderer.render(f);
  }

  togglePlay(): Promise<void> {
    return this.guard(() => (this.p.state.playing ? this.pause() : this.play()));
  }

  /** The Run runs a taught task: the benchmark select names it (no permalink restores it; the URL
   * keeps the workcell it was taught in), and the goal is its own. */
  async taught(f: Frame, inFolder: boolean, goal: string[]): Promise<void> {
    const { state, ui } = this.p;
    // A task taught in a benchmark's workcell leaves the task folder; one taught in the open
    // folder keeps it (a new episode of the folder's own task reopens it).
    if (!inFolder) {
      state.folder = null;
      this.folderChoices();
    }
    updateUrl(state);
    state.taught = true;
    this.reopenable = false;
    ui.taskTag.hidden = true;
    const sel = ui.controls.benchSel;
    sel.append(el('option', { value: TAUGHT, title: `The task taught in Teach mode, in ${f.world.name}` }, 'taught task'));
    sel.value = TAUGHT;
    ui.controls.blocksSel.disabled = true;
    ui.run.goal.textContent = goalWords(goal);
    ui.run.goal.title = goal.join(' ');
  }

  /** Opens a session of the chosen scenario (or of a scene file's world), on the open task folder
   * if there is one. */
  async open(scene?: string): Promise<void> {
    const { state, client, renderer, status, view } = this.p;
    state.taught = false;
    this.showTaskTag();
    this.setPlaying(false);
    updateUrl(state);
    const { folder } = state;
    status.say(folder ? 'Loading the task folder…' : 'Loading the benchmark…');
    try {
      await this.freshWorker();
      const f = await this.openSession(scene);
      renderer.restart(f);
      void this.guard(() => this.showGoal(f));
      if (state.editorTask !== taskKey(state) && !this.p.ui.editorHost.hidden) void this.p.tabs().loadEditor();
      if (state.autoplay) await this.play();
    } catch (e) {
      if (folder) {
        // The worker keeps the session it had; the error names the folder's file at fault.
        status.fail(`Could not open the task folder: ${(e as Error).message}`);
        return;
      }
      // Still show the benchmark's scene, and say why nothing moves.
      try {
        view.update((await client.call('benchmark', { id: state.options.benchmark })).scene);
      } catch {
        /* the message below says enough */
      }
      status.fail(`Could not start the session: ${(e as Error).message}`);
    }
  }

  /** A session on the open task folder, else on the scenario's benchmark (in `scene`'s world
   * when given), with the chosen robot in the arms' place. */
  private async openSession(scene?: string): Promise<Frame> {
    const { state } = this.p;
    const f = await (state.folder
      ? this.openFolderSession(state.folder, scene)
      : this.p.client.call('open', { options: { ...state.options, ...robotOption(state.robot) }, scene }));
    this.reopenable = scene === undefined;
    return f;
  }

  /** A session on `folder` with the scenario's method, mode and seed (the worker's `openFolder`). */
  private openFolderSession(folder: OpenFolder, scene?: string): Promise<Frame> {
    const { method, mode, seed, skill } = this.p.state.options;
    const robot = robotOption(this.p.state.robot);
    return this.p.client.call('openFolder', { files: folder.files, options: { dir: folder.name, method, mode, seed, skill, scene, ...robot } });
  }

  /** The top bar's tag: the task folder the Run runs (hidden for a benchmark). */
  private showTaskTag(): void {
    const { ui, state } = this.p;
    ui.taskTag.hidden = !state.folder;
    if (state.folder) {
      ui.taskTag.textContent = `task folder · ${state.folder.name}`;
      ui.taskTag.title = state.folder.url ? `Served at ${state.folder.url}` : 'Opened from this computer: Save keeps it with the run';
    }
  }

  /**
   * Opens the task folder `folder` in the Run (`?folder=URL`, a picked directory, files or zip,
   * a saved run's files). A folder the core refuses changes nothing and says which file is at
   * fault; resolves to whether it opened.
   */
  async openFolder(folder: OpenFolder): Promise<boolean> {
    return (await this.tryFolder(folder)) === null;
  }

  /**
   * Opens the task folder served at `url` (`?folder=URL`). When it cannot be fetched or the core
   * refuses it, the benchmark opens paused beneath and the status line keeps the reason.
   */
  async openFolderAt(url: string): Promise<void> {
    let why: string | null;
    try {
      // The folder reader loads on demand: a benchmark's first frame does not need it.
      why = await this.tryFolder(await (await import('./folder')).folderFromUrl(url));
    } catch (e) {
      why = (e as Error).message;
    }
    if (why === null) return;
    const autoplay = this.p.state.autoplay;
    this.p.state.autoplay = false;
    await this.open();
    this.p.state.autoplay = autoplay;
    // After the opened frame is drawn (next animation frame), so the reason stays on the line.
    await new Promise((r) => requestAnimationFrame(r));
    this.p.status.fail(`Could not open the task folder ${url}: ${why}`);
    this.p.status.notice(`Could not open the task folder ${url}: ${sentence(why)}`, 'error', 15000);
  }

  /** Shows the first frame `f` of a newly opened task (`folder`'s, or a benchmark's): the
   * selects, the top bar's tag, the URL, the goal and the PDDL tab follow it. */
  private showOpened(f: Frame, folder: OpenFolder | null): void {
    const { state } = this.p;
    state.folder = folder;
    state.taught = false;
    this.p.tabs().teach?.reset();
    this.folderChoices();
    this.showTaskTag();
    updateUrl(state);
    this.p.renderer.restart(f);
    void this.guard(() => this.showGoal(f));
    if (!this.p.ui.editorHost.hidden) void this.p.tabs().loadEditor();
  }

  /** Opens `folder`; resolves to null, or to why it could not (the status line says so too). */
  private async tryFolder(folder: OpenFolder): Promise<string | null> {
    const { state, status } = this.p;
    const was = state.playing;
    if (was) await this.pause();
    try {
      this.showOpened(await this.openFolderSession(folder), folder);
      this.reopenable = true;
      status.notice(`Opened the task folder ${folder.name}.`, 'info');
      if (state.autoplay) await this.play();
      return null;
    } catch (e) {
      const why = (e as Error).message;
      status.fail(`Could not open the task folder: ${why}`);
      status.notice(`The task folder ${folder.name} was not opened: ${sentence(why)}`, 'error', 15000);
      if (was) await this.play();
      return why;
    }
  }

  /**
   * Puts robot `pick` in the arms' place (null: the default, the Panda) and reopens the task from
   * its start. A robot the task refuses (a block out of its reach, a folder that does not load)
   * changes nothing and says why.
   */
  async setRobot(pick: RobotPick | null): Promise<void> {
    const { state, status } = this.p;
    const was = state.robot;
    if (state.playing) await this.pause();
    state.robot = pick;
    status.say(`Loading ${robotLabel(pick)}…`);
    try {
      this.showOpened(await this.openSession(), state.folder);
      status.notice(`The arms are now ${robotLabel(pick)}.`, 'info');
      if (state.autoplay) await this.play();
    } catch (e) {
      state.robot = was;
      setRobotChoice(this.p.ui.controls.robotSel, was);
      const why = (e as Error).message;
      status.fail(`${robotLabel(pick, true)} cannot run this task: ${why}`);
      status.notice(`${robotLabel(pick, true)} was not put in the arms' place: ${sentence(why)}`, 'error', 15000);
    }
  }

  /** The benchmark select and the block select for the open folder (none: the benchmarks). */
  private folderChoices(): void {
    const { state, ui } = this.p;
    setFolderChoice(ui.controls.benchSel, state.folder?.name ?? null, state.options.benchmark);
    // A folder is its own task: no generated N-block variant.
    if (state.folder) {
      ui.controls.blocksSel.disabled = true;
      ui.controls.blocksSel.title = 'A task folder is its own task: it has no N-block variant';
    } else setBlockChoices(ui.controls.blocksSel, state.options.benchmark, state.options.blocks);
  }

  /** States the task's goal in words (a generated tower's from its demonstration's last state). */
  private async showGoal(f: Frame): Promise<void> {
    const { folder } = this.p.state;
    const problem = folder ? (folder.files['problem.pddl'] ?? '') : (await this.p.client.call('benchmark', { id: this.p.state.options.benchmark })).problem;
    let facts = goalFacts(problem);
    if (this.p.state.options.blocks != null && !folder) {
      const preds = new Set(facts.map((x) => x.slice(1).split(' ')[0]));
      facts = (f.demoStates[f.demoStates.length - 1] ?? []).filter((x) => preds.has(x.slice(1).split(/[ )]/)[0]));
    }
    const words = goalWords(facts);
    this.p.ui.run.goal.textContent = words;
    this.p.ui.run.goal.title = facts.join(' ');
    this.goal = words;
    this.hint?.setGoal(words);
  }

  /**
   * What Load opens: one JSON file is a scene or a saved run (an episode log, replayed; one that
   * carries its task folder's files opens that folder); a `.zip` or several files are a task
   * folder.
   */
  async loadFiles(files: File[]): Promise<void> {
    const { folderFromFiles, folderOfLog, isEpisodeLog } = await import('./folder');
    const one = files.length === 1 ? files[0] : null;
    // One file is a scene or a saved run unless it is a zip or one of a folder's other files.
    if (one && !/\.(zip|pddl|plan|md)$/i.test(one.name) && !/^(motions|expert|demo)\.json$/.test(one.name)) {
      const text = await one.text();
      let parsed: unknown = null;
      try {
        parsed = JSON.parse(text);
      } catch {
        /* the scene loader names the position of the error */
      }
      if (isEpisodeLog(parsed)) return this.loadEpisode(one.name, text, folderOfLog(parsed));
      return this.loadScene(one.name, text);
    }
    let folder: OpenFolder;
    try {
      folder = await folderFromFiles(files);
    } catch (e) {
      this.p.status.notice(`No task folder was opened: ${sentence((e as Error).message)}`, 'error', 15000);
      this.p.status.fail(`Could not open the task folder: ${(e as Error).message}`);
      return;
    }
    await this.openFolder(folder);
  }

  /** Replays a saved run; one that carries its folder's files opens that folder with it. */
  private async loadEpisode(name: string, text: string, folder: OpenFolder | null): Promise<void> {
    const { state, client, status } = this.p;
    if (state.playing) await this.pause();
    try {
      const f = await client.call('replay', { episode: text });
      this.reopenable = false;
      const log = JSON.parse(text) as { options: { benchmark: Benchmark; method: Method; mode: Mode; seed: number; blocks?: number | null } };
      const o = state.options;
      Object.assign(o, { benchmark: log.options.benchmark, method: log.options.method, mode: log.options.mode, seed: log.options.seed });
      if (log.options.blocks != null && !folder) o.blocks = log.options.blocks;
      else delete o.blocks;
      const c = this.p.ui.controls;
      c.methodSel.value = o.method;
      c.modeSel.value = o.mode;
      c.seedIn.value = String(o.seed);
      this.showOpened(f, folder);
      status.notice(`Loaded the run ${name}${folder ? ` on the task folder ${folder.name}` : ''}: replayed to its end.`, 'info');
    } catch (e) {
      status.notice(`${name} was not loaded: ${sentence((e as Error).message)}`, 'error');
    }
  }

  /** Opens a scene file's world; a file the core refuses changes nothing and says why. */
  async loadScene(name: string, text: string): Promise<void> {
    const { state, renderer, status } = this.p;
    const was = state.playing;
    if (was) await this.pause();
    try {
      const f = await this.openSession(text);
      renderer.restart(f);
      status.notice(`Loaded the scene ${name}.`, 'info');
      if (state.autoplay) await this.play();
    } catch (e) {
      // The worker keeps the session it had: the run goes on as before.
      status.notice(`${name} was not loaded: ${sentence((e as Error).message)}`, 'error');
      if (was) await this.play();
    }
  }

  async reset(): Promise<void> {
    this.setPlaying(false);
    const fresh = this.reopenable && (await this.freshWorker());
    this.p.renderer.restart(await (fresh ? this.openSession() : this.p.client.call('reset', { seed: this.p.state.options.seed })));
    if (this.p.state.autoplay) await this.play();
  }

  /** Replaces a worker whose wasm memory grew 16 MiB (and twice) past its fresh size: wasm memory
   * never shrinks, and one long search (TAMP on a tall tower) can leave hundreds of MB behind. Resolves
   * to whether it did (the new worker has no session yet). */
  private async freshWorker(): Promise<boolean> {
    const { client } = this.p;
    const m = await client.call('memory', {});
    if (m.wasmBytes <= Math.max(2 * m.freshBytes, m.freshBytes + (16 << 20))) return false;
    await this.restartWorker();
    return true;
  }

  /** A fresh worker, moving onto the full-speed module as the first one did. */
  private async restartWorker(): Promise<void> {
    await this.p.client.respawn();
    void this.p.client.call('speedUp', {});
  }

  step(): Promise<void> {
    return this.guard(async () => {
      this.setPlaying(false);
      this.p.renderer.render(await this.p.client.call('step', { dt: 0.1 }));
    });
  }

  async inject(level: Level): Promise<void> {
    try {
      const was = this.p.state.frame;
      const before = was?.world.bodies;
      const r = await this.p.client.call('inject', { level });
      this.p.status.notice(withLevel(level, r.message), 'info');
      this.p.history.view(null);
      this.p.history.mark(level, withLevel(level, r.message), was, r.frame);
      // Small moves (L1's few centimetres) are easy to miss: mark what the notice names — the
      // pushed hand (a body it nudged on the way is not what was disturbed), else each moved body.
      if (r.push) this.p.view.markPush(r.push.arm, r.push.from, r.push.to);
      else {
        for (const name of r.moved) {
          const from = before?.find((b) => b.name === name)?.pose.position;
          if (from) this.p.view.markMove(name, from);
        }
      }
      this.p.renderer.render(r.frame);
      if (!this.p.state.playing) await this.play();
    } catch (e) {
      this.p.status.notice(`${levelName(level)} refused: ${withoutLevel(level, (e as Error).message)}`, 'error');
    }
  }

  cancel(): Promise<void> {
    return this.guard(async () => {
      if (this.searching) return this.stopSearch();
      const clickedAt = performance.timeOrigin + performance.now();
      const r = await this.p.client.call('cancel', {});
      this.p.renderer.render(r.frame);
      this.p.state.lastCancel = { clickedAt, appliedAt: r.appliedAt, repliedAt: performance.timeOrigin + performance.now() };
    });
  }

  /** Cancel while a search holds the worker: a fresh worker (the only way to stop wasm from
   * outside) reopens the episode at its start, or says what to open when it cannot. */
  private async stopSearch(): Promise<void> {
    const { status, renderer } = this.p;
    this.searching = false;
    this.setPlaying(false);
    await this.restartWorker();
    if (!this.reopenable) return status.fail('Search stopped: the planner restarted. Open a task to go on.');
    renderer.restart(await this.openSession());
    status.notice('Search stopped: the planner restarted and the episode is back at its start.', 'info', 8000);
  }

  /** A block the user dropped in the view; resolves to a refusal or null. */
  async drop(d: DropRequest): Promise<string | null> {
    const teach = this.p.tabs().teach;
    if (teach?.active) return teach.drop(d);
    const was = this.p.state.frame;
    const ended = was?.status.kind === 'done';
    const r = await this.p.client.call('perturb', { body: d.body, position: d.position });
    if (!r.ok) return r.reason;
    this.p.status.notice(r.message || `Moved ${d.body}`, 'info');
    this.p.history.mark('drag', `drag: ${r.message || `moved ${d.body}`}`, was, r.frame);
    this.p.renderer.render(r.frame);
    // A finished run reopens on a drag and goes on at once; a failed one waits for Play.
    if (ended) this.p.state.resumeAfterDrag = true;
    return null;
  }

  private levelsKey = '';

  /** Enables the L1–L4 buttons that would apply now (the core tries each on a copy of the
   * world), asked again whenever the loop reaches another decision. */
  refreshLevels(f: Frame): void {
    const key = JSON.stringify([f.status.kind, f.executing, f.replans, f.facts, f.world.arms.map((a) => a.holding)]);
    if (key === this.levelsKey || this.p.tabs().teach?.active) return;
    this.levelsKey = key;
    this.p.client.call('levels', {}).then(
      (why) => {
        for (const b of this.p.ui.controls.levelBtns) {
          const reason = why[b.dataset.level as Level];
          // Greyed but still clickable: a press says why it cannot apply now.
          b.setAttribute('aria-disabled', String(reason !== null));
          b.classList.toggle('unavailable', reason !== null);
          b.title = reason ? `${b.getAttribute('aria-label')} — not now: ${reason}` : (b.getAttribute('aria-label') ?? '');
        }
      },
      () => {
        /* no session: the buttons stay as they are */
      },
    );
  }

  /** A message the worker sent on its own: a frame of the playing session, or a fatal error. */
  onPush(m: FromWorker): void {
    if (m.type === 'fatal') {
      this.setPlaying(false);
      this.p.status.fail(m.message);
      return;
    }
    if (m.type === 'progress') {
      this.searching = true;
      const method = entryOf(catalogue()?.methods ?? [], this.p.state.options.method)?.label ?? '';
      return this.p.status.searching(method, m.expanded, m.ms);
    }
    this.searching = false;
    if (m.type !== 'frame' || this.p.tabs().teach?.active) return;
    recordStep(this.p.state, m.timing.stepMs);
    this.p.renderer.render(m.frame);
    if (!m.playing && this.p.state.playing) this.setPlaying(false);
    if (m.frame.status.kind === 'done') this.hint?.ended(() => void this.reset());
  }

  /** Selects the next benchmark (as if chosen in its select). */
  nextBenchmark(): void {
    const sel = this.p.ui.controls.benchSel;
    if (sel.disabled) return;
    // The benchmarks only: the open folder and the item that opens one are not in the cycle.
    const ids = [...sel.options].map((o) => o.value).filter((v) => v !== FOLDER && v !== OPEN_FOLDER && v !== TAUGHT && !GALLERY.some((g) => galleryValue(g.name) === v));
    sel.value = ids[(ids.indexOf(sel.value) + 1) % ids.length];
    sel.dispatchEvent(new Event('change'));
  }

  /** Moves the speed select `d` steps up or down (as if chosen in it). */
  stepSpeed(d: number): void {
    const sel = this.p.ui.controls.speedSel;
    const opts = [...sel.options].map((o) => o.value);
    const i = Math.max(0, Math.min(opts.length - 1, opts.indexOf(sel.value) + d));
    sel.value = opts[i];
    sel.dispatchEvent(new Event('change'));
  }

  /** Saves the scene; on a task folder, the run itself with the folder's files (Load opens it
   * again, folder and all). */
  private async save(): Promise<void> {
    const { folder } = this.p.state;
    if (folder) {
      const name = folder.name.replace(/^\.\//, '').split('/').filter(Boolean).pop() || 'folder';
      downloadJson(await this.p.client.call('episode', { withFiles: true }), `${name}-run.json`);
      this.p.status.notice('Saved the run with the task folder’s files: Load opens it again.', 'info');
      return;
    }
    downloadJson(await this.p.client.call('scene', {}), `${this.p.state.options.benchmark}-scene.json`);
  }

  private async copyLink(): Promise<void> {
    if (this.p.state.taught) {
      this.p.status.notice('A taught task has no link: save its demonstration in the Teach tab to share it.', 'info');
      return;
    }
    const { folder } = this.p.state;
    if (folder && !folder.url) {
      this.p.status.notice(
        `A link cannot carry the files of ${folder.name}: they are on this computer, not on a server. Save keeps the run with its folder’s files (Load opens it again), or serve the folder beside the page and open ?folder=URL.`,
        'info',
      );
      return;
    }
    updateUrl(this.p.state);
    try {
      await navigator.clipboard.writeText(location.href);
      this.p.status.notice(folder ? `Link copied: it restores the task folder at ${folder.url}, method, mode and seed` : 'Link copied: it restores this benchmark, blocks, method, mode and seed', 'info');
    } catch {
      this.p.status.notice(location.href, 'info');
    }
  }

  /** Connects the top bar's controls and the stage's Cancel. */
  wire(): void {
    const { state, client } = this.p;
    const c = this.p.ui.controls;
    const o = state.options;
    c.benchSel.onchange = () => {
      const gallery = GALLERY.find((g) => galleryValue(g.name) === c.benchSel.value);
      if (gallery) {
        c.benchSel.value = state.folder ? FOLDER : o.benchmark;
        void this.openFolderAt(galleryValue(gallery.name));
        return;
      }
      if (c.benchSel.value === OPEN_FOLDER || c.benchSel.value === FOLDER) {
        // Picking a folder happens in the browser's dialog; the select shows the Run's task meanwhile.
        if (c.benchSel.value === OPEN_FOLDER) c.dirIn.click();
        c.benchSel.value = state.folder ? FOLDER : o.benchmark;
        return;
      }
      o.benchmark = c.benchSel.value as Benchmark;
      state.folder = null;
      // A count the new benchmark does not allow falls back to its template task.
      const blocks = blocksFor(o.benchmark, o.blocks);
      if (blocks === undefined) delete o.blocks;
      this.folderChoices();
      this.p.tabs().teach?.reset();
      void this.open();
    };
    c.blocksSel.onchange = () => {
      const blocks = blocksFor(o.benchmark, c.blocksSel.value === '' ? undefined : Number(c.blocksSel.value));
      if (blocks === undefined) delete o.blocks;
      else o.blocks = blocks;
      void this.open();
    };
    c.methodSel.onchange = () => {
      o.method = c.methodSel.value as Method;
      void this.open();
    };
    c.modeSel.onchange = () => {
      o.mode = c.modeSel.value as Mode;
      void this.open();
    };
    c.seedIn.onchange = () => {
      o.seed = parseSeed(c.seedIn.value);
      c.seedIn.value = String(o.seed);
      updateUrl(state);
      void this.guard(() => this.reset());
    };
    c.resetBtn.onclick = () => void this.guard(() => this.reset());
    c.playBtn.onclick = () => void this.togglePlay();
    c.stepBtn.onclick = () => void this.step();
    c.speedSel.onchange = () => {
      state.speed = Number(c.speedSel.value);
      updateUrl(state);
      void this.guard(() => client.call('speed', { speed: state.speed }));
    };
    // The buttons come with the catalogue: one handler on their group serves them all.
    c.levelGroup.onclick = (e) => {
      const b = (e.target as HTMLElement).closest<HTMLButtonElement>('button.level');
      if (b) void this.inject(b.dataset.level as Level);
    };
    this.p.ui.stage.cancelBtn.onclick = () => void this.cancel();
    c.saveBtn.onclick = () => void this.guard(() => this.save());
    c.loadBtn.onclick = () => c.fileIn.click();
    c.fileIn.onchange = () =>
      void this.guard(async () => {
        const files = [...(c.fileIn.files ?? [])];
        c.fileIn.value = '';
        if (files.length) await this.loadFiles(files);
      });
    c.dirIn.onchange = () =>
      void this.guard(async () => {
        const files = [...(c.dirIn.files ?? [])];
        c.dirIn.value = '';
        if (files.length) await this.loadFiles(files);
      });
    c.robotSel.onchange = () => {
      const v = c.robotSel.value;
      if (v === OPEN_ROBOT || v === ROBOT_FOLDER) {
        // Picking a folder happens in the browser's dialog; the select shows the arms' robot meanwhile.
        if (v === OPEN_ROBOT) c.robotDirIn.click();
        setRobotChoice(c.robotSel, state.robot);
        return;
      }
      void this.guard(() => this.setRobot(robotFromUrl(v)));
    };
    c.robotDirIn.onchange = () =>
      void this.guard(async () => {
        const files = [...(c.robotDirIn.files ?? [])];
        c.robotDirIn.value = '';
        if (!files.length) return;
        const { robotFromFiles } = await import('./robot-folder');
        const pick = await robotFromFiles(files);
        setRobotChoice(c.robotSel, pick);
        await this.setRobot(pick);
      });
    c.linkBtn.onclick = () => void this.copyLink();
  }
}
