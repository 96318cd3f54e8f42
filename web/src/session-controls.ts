/**
 * The Run's session, driven from the top bar and the 3-D view: open a benchmark (or a scene file),
 * play, pause, step, reset, change the speed, inject a disturbance, cancel the plan, drop a dragged
 * block, save the scene, copy the permalink; and the frames the worker pushes while it plays.
 */
import type { Benchmark, Frame, Level, Method, Mode } from 'logic-lfd';
import type { DropRequest, View } from './view';
import type { WorkerClient } from './client';
import { downloadJson, guard } from './dom';
import type { FirstVisitHint } from './guide';
import type { FrameRenderer } from './frame-renderer';
import type { History } from './history';
import { setBlockChoices, type Layout } from './layout';
import type { FromWorker } from './protocol';
import { blocksFor, parseSeed, recordStep, updateUrl, type PageState } from './state';
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
const withoutLevel = (level: Level, m: string) => m.replace(new RegExp(`^${level}:\\s*`, 'i'), '');
const withLevel = (level: Level, m: string) => `${level.toUpperCase()}: ${withoutLevel(level, m)}`;

export class SessionControls {
  /** The first-visit hint, once its chunk has loaded (after the first frame). */
  private hint: FirstVisitHint | null = null;
  private goal = '';

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

  /** The Run runs a taught task: no permalink can restore it, so the URL and the top bar say so. */
  taught(f: Frame): void {
    this.p.state.taught = true;
    history.replaceState(null, '', location.pathname);
    this.p.ui.taskTag.textContent = `taught task · ${f.world.name}`;
    this.p.ui.taskTag.hidden = false;
    this.p.ui.run.goal.textContent = 'the taught goal (Teach tab)';
  }

  /** Opens a session of the chosen scenario (or of a scene file's world). */
  async open(scene?: string): Promise<void> {
    const { state, client, renderer, status, view } = this.p;
    state.taught = false;
    this.p.ui.taskTag.hidden = true;
    this.setPlaying(false);
    updateUrl(state);
    status.say('Loading the benchmark…');
    try {
      const f = await client.call('open', { options: { ...state.options }, scene });
      renderer.restart(f);
      void this.guard(() => this.showGoal(f));
      if (state.editorBenchmark !== state.options.benchmark && !this.p.ui.editorHost.hidden) void this.p.tabs().loadEditor();
      if (state.autoplay) await this.play();
    } catch (e) {
      // Still show the benchmark's scene, and say why nothing moves.
      try {
        view.update((await client.call('benchmark', { id: state.options.benchmark })).scene);
      } catch {
        /* the message below says enough */
      }
      status.fail(`Could not start the session: ${(e as Error).message}`);
    }
  }

  /** States the task's goal in words (a generated tower's from its demonstration's last state). */
  private async showGoal(f: Frame): Promise<void> {
    const [b, { goalFacts, goalWords }] = await Promise.all([this.p.client.call('benchmark', { id: this.p.state.options.benchmark }), import('./guide')]);
    let facts = goalFacts(b.problem);
    if (this.p.state.options.blocks != null) {
      const preds = new Set(facts.map((x) => x.slice(1).split(' ')[0]));
      facts = (f.demoStates[f.demoStates.length - 1] ?? []).filter((x) => preds.has(x.slice(1).split(/[ )]/)[0]));
    }
    const words = goalWords(facts);
    this.p.ui.run.goal.textContent = words;
    this.p.ui.run.goal.title = facts.join(' ');
    this.goal = words;
    this.hint?.setGoal(words);
  }

  /** Opens a scene file's world; a file the core refuses changes nothing and says why. */
  async loadScene(name: string, text: string): Promise<void> {
    const { state, client, renderer, status } = this.p;
    const was = state.playing;
    if (was) await this.pause();
    try {
      const f = await client.call('open', { options: { ...state.options }, scene: text });
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
    this.p.renderer.restart(await this.p.client.call('reset', { seed: this.p.state.options.seed }));
    if (this.p.state.autoplay) await this.play();
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
      this.p.status.notice(`${level.toUpperCase()} refused: ${withoutLevel(level, (e as Error).message)}`, 'error');
    }
  }

  cancel(): Promise<void> {
    return this.guard(async () => {
      const clickedAt = performance.timeOrigin + performance.now();
      const r = await this.p.client.call('cancel', {});
      this.p.renderer.render(r.frame);
      this.p.state.lastCancel = { clickedAt, appliedAt: r.appliedAt, repliedAt: performance.timeOrigin + performance.now() };
    });
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
    if (m.type !== 'frame' || this.p.tabs().teach?.active) return;
    recordStep(this.p.state, m.timing.stepMs);
    this.p.renderer.render(m.frame);
    if (!m.playing && this.p.state.playing) this.setPlaying(false);
  }

  /** Selects the next benchmark (as if chosen in its select). */
  nextBenchmark(): void {
    const sel = this.p.ui.controls.benchSel;
    if (sel.disabled) return;
    sel.selectedIndex = (sel.selectedIndex + 1) % sel.options.length;
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

  private async save(): Promise<void> {
    downloadJson(await this.p.client.call('scene', {}), `${this.p.state.options.benchmark}-scene.json`);
  }

  private async copyLink(): Promise<void> {
    if (this.p.state.taught) {
      this.p.status.notice('A taught task has no link: save its demonstration in the Teach tab to share it.', 'info');
      return;
    }
    updateUrl(this.p.state);
    try {
      await navigator.clipboard.writeText(location.href);
      this.p.status.notice('Link copied: it restores this benchmark, blocks, method, mode and seed', 'info');
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
      o.benchmark = c.benchSel.value as Benchmark;
      // A count the new benchmark does not allow falls back to its template task.
      const blocks = blocksFor(o.benchmark, o.blocks);
      if (blocks === undefined) delete o.blocks;
      setBlockChoices(c.blocksSel, o.benchmark, blocks);
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
        const file = c.fileIn.files?.[0];
        c.fileIn.value = '';
        if (file) await this.loadScene(file.name, await file.text());
      });
    c.linkBtn.onclick = () => void this.copyLink();
  }
}
