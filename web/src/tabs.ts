/**
 * The side tabs (Run, Teach, Charts, PDDL): switching between them, and loading Teach mode and the
 * PDDL editor on first use (each is a chunk of its own, and Teach mode a wasm module of its own in
 * the worker), so the page becomes interactive sooner.
 */
import type { Frame } from 'logic-lfd';
import { catalogueReady } from './catalogue';
import type { Charts } from './charts';
import { SearchRunner, type WorkerClient } from './client';
import type { ComparePanel } from './compare';
import type { EditorPanel } from './editor';
import type { FrameRenderer } from './frame-renderer';
import type { Layout } from './layout';
import { robotName, robotOption } from './robot-choice';
import { taskKey, type PageState, type TabId } from './state';
import type { StatusBar } from './status-bar';
import type { TeachPanel } from './teach';
import type { View } from './view';

/** What Teach mode needs of the Run's playback. */
export interface Playback {
  play(): Promise<void>;
  pause(): Promise<void>;
  setPlaying(p: boolean): void;
  /** Opens files as Load does (a saved run is replayed). */
  loadFiles(files: File[]): Promise<void>;
  /** The Run now runs a taught task (not the benchmark's), with goal facts `goal`: the selects say so. */
  taught(f: Frame, inFolder: boolean, goal: string[]): Promise<void>;
}

export interface TabsParts {
  state: PageState;
  ui: Layout;
  client: WorkerClient;
  view: View;
  charts: Charts;
  renderer: FrameRenderer;
  status: StatusBar;
  playback: Playback;
}

export class Tabs {
  /** Teach mode, once its tab has been opened. */
  teach: TeachPanel | null = null;
  private teachPromise: Promise<TeachPanel> | null = null;
  private editorPromise: Promise<EditorPanel> | null = null;
  private comparePromise: Promise<ComparePanel> | null = null;
  /** The PDDL tab's texts per benchmark (domain, problem, demonstration). */
  private readonly edits = new Map<string, [string, string, string]>();
  private readonly search = new SearchRunner();

  constructor(private readonly p: TabsParts) {
    p.ui.tabs.forEach((t) => (t.button.onclick = () => this.select(t.id)));
    this.select('run');
  }

  select(id: TabId): void {
    const { state, ui, status, renderer, charts } = this.p;
    for (const t of ui.tabs) {
      const on = t.id === id;
      t.panel.hidden = !on;
      t.button.classList.toggle('active', on);
      t.button.setAttribute('aria-selected', String(on));
    }
    state.currentTab = id;
    if (id === 'teach') {
      this.getTeach().then(
        (t) => t.setVisible(state.currentTab === 'teach'),
        (e: unknown) => status.notice(`could not load Teach mode: ${(e as Error).message}`, 'error'),
      );
    } else this.teach?.setVisible(false);
    if (id !== 'teach') {
      this.runControls(true);
      renderer.redraw();
    }
    if (id === 'pddl') void this.loadEditor();
    if (id === 'charts') charts.draw();
    if (id === 'compare') void this.loadCompare().then((c) => c.refresh());
  }

  /** Loads the PDDL of the task the Run runs into the editor, unless it holds it already: a
   * benchmark's template files, a generated N-block task's own problem, a task folder's files. */
  async loadEditor(): Promise<void> {
    const { state, client } = this.p;
    const key = taskKey(state);
    if (state.editorTask === key) return;
    const left = state.editorTask;
    state.editorTask = key;
    const editor = await this.getEditor();
    // The user's edits of the task left behind come back when it is chosen again.
    if (left) this.edits.set(left, [editor.text('domain'), editor.text('problem'), editor.text('demo')]);
    const kept = this.edits.get(key);
    if (kept) return editor.setTexts(...kept);
    if (state.folder || state.options.blocks != null) {
      const t = await client.call('task', {});
      editor.setTexts(t.domain, t.problem, t.demoPlan);
    } else {
      const b = await client.call('benchmark', { id: state.options.benchmark });
      editor.setTexts(b.domain, b.problem, b.demoPlan);
    }
  }

  /** Opens the PDDL tab holding `domain`, `problem` and, when given, the demonstration `demo`
   * (the benchmark's texts are not loaded over them). */
  async setPddl(domain: string, problem: string, demo?: string): Promise<void> {
    this.p.state.editorTask = taskKey(this.p.state);
    this.select('pddl');
    (await this.getEditor()).setTexts(domain, problem, demo);
  }

  /** Loads the Compare view's chunk and mounts it (once). */
  private loadCompare(): Promise<ComparePanel> {
    this.comparePromise ??= Promise.all([import('./compare'), catalogueReady]).then(([{ ComparePanel }, catalogue]) => {
      const c = new ComparePanel(
        {
          scenario: () => {
            const o = this.p.state.options;
            return { benchmark: o.benchmark, seed: o.seed, ...(o.blocks != null && !this.p.state.folder ? { blocks: o.blocks } : {}) };
          },
          folder: () => this.p.state.folder,
          robot: () => {
            const { robot } = robotOption(this.p.state.robot);
            return robot === undefined ? null : { choice: robot, name: robotName(this.p.state.robot) };
          },
          episode: () => this.p.client.call('episode', {}),
          replay: async (name, log) => {
            await this.p.playback.loadFiles([new File([log], name)]);
            this.select('run');
          },
        },
        catalogue,
      );
      this.p.ui.compareSlot.append(c.root);
      return c;
    });
    return this.comparePromise;
  }

  private getEditor(): Promise<EditorPanel> {
    this.editorPromise ??= import('./editor').then(({ EditorPanel, PLAN_TIME_LIMIT_MS }) => {
      // The editor's searches run in a worker of their own (terminated on cancel or timeout): a
      // pathological problem never stops the robot's worker nor freezes the page.
      const search = this.search;
      const e = new EditorPanel({
        plan: (domain, problem, o) => search.call('plan', { domain, problem, options: o }, PLAN_TIME_LIMIT_MS + 5000),
        check: (domain, problem) => search.call('check', { domain, problem }, 10_000),
        logicLfd: (input, timeoutMs) => search.call('logicLfd', { input }, timeoutMs),
        logicLfdPerturb: (input) => search.call('logicLfdPerturb', { input }, 20_000),
        cancel: () => search.cancel('cancelled'),
      });
      this.p.ui.editorHost.append(e.root);
      return e;
    });
    return this.editorPromise;
  }

  /** Enables the Run's controls, or disables them while Teach mode records (it owns the view). */
  private runControls(on: boolean): void {
    const c = this.p.ui.controls;
    for (const b of [c.playBtn, c.stepBtn, c.resetBtn, c.speedSel, ...c.levelBtns]) b.disabled = !on;
  }

  private getTeach(): Promise<TeachPanel> {
    this.teachPromise ??= Promise.all([import('./teach'), this.p.client.call('teachLoad', {})]).then(
      ([{ TeachPanel }]) => (this.teach = this.newTeachPanel(TeachPanel)),
      (e: unknown) => {
        this.teachPromise = null;
        throw e;
      },
    );
    return this.teachPromise;
  }

  private newTeachPanel(Panel: typeof TeachPanel): TeachPanel {
    const { state, ui, client, view, status, renderer, playback } = this.p;
    return new Panel(ui.teachSlot, {
      client,
      view,
      stage: ui.stage.root,
      benchmark: () => state.options.benchmark,
      folder: () => state.folder,
      options: () => state.options,
      notice: (t, k) => status.notice(t, k),
      status: (kind, text) => {
        // Teach mode's own status: no run to cancel, no run clock.
        status.show(kind, text);
        this.runControls(!this.teach?.active);
        ui.stage.cancelBtn.disabled = true;
        ui.stage.hud.textContent = '';
      },
      pauseRun: async () => {
        if (state.playing) await playback.pause();
      },
      runTaught: async (f: Frame, autoplay: boolean, inFolder: boolean, goal: string[]) => {
        playback.setPlaying(false);
        await playback.taught(f, inFolder, goal);
        this.select('run');
        renderer.restart(f);
        if (autoplay) await playback.play();
      },
    });
  }
}
