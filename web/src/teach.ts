/**
 * Teach mode: record a new demonstration in the workcell and run it with Logic-LfD.
 *
 * Record → demonstrate (quick: drag a block and the robot carries it; gripper: move the 3-D
 * gripper handle, open/close it, the arm follows by IK; by hand: nudge a block without the robot)
 * → Stop. Every edit is segmented in the worker into the domain's actions as it happens; the
 * panel lists the actions a1..aN and the demo states L0..LN, and refusals (a change the PDDL model
 * cannot explain, a release in mid-air) with their time and fact change — a refused edit leaves the
 * recording as it was. After Stop: the goal (L_N's facts by default, editable), save/load of the
 * taught demo.json, and Run: a closed-loop session of the taught task from a random, the taught or
 * a user-arranged initial world, disturbed with the usual drag and L1–L4 buttons.
 */
import type { Benchmark, Frame, Segment, SessionOptions, TaughtFolder, TaughtInfo, TeachEdit, TeachError, TeachResult, TeachState } from 'logic-lfd';
import type { OpenFolder } from './folder';
import type { WorkerClient } from './client';
import type { View, DropRequest } from './view';
import { button, downloadJson, el, guard, isShortcut } from './dom';
import { parseSeed } from './state';
import { GripperHandle, type HandlePose } from './teach-gripper';
import { GripperStream } from './teach-gripper-stream';
import { buildTeachUi, TEACH_MODES, type TeachMode, type TeachUi } from './teach-layout';
import { checkedGoal, errorContent, goalItems, recordingItems, taughtItems } from './teach-listing';
import { blockUnder, DropHint, type DropHintState } from './teach-drop';
import { atRest, demoMoves, withGoal, withoutMove } from './teach-moves';
import { MoveToast } from './teach-toast';
import './teach.css';

type Start = 'random' | 'taught' | 'arrange';

export interface TeachHost {
  client: WorkerClient;
  view: View;
  stage: HTMLElement;
  benchmark: () => Benchmark;
  /** The open task folder (Teach records in its workcell), if any. */
  folder: () => OpenFolder | null;
  options: () => SessionOptions;
  notice: (text: string, kind: 'info' | 'error') => void;
  status: (kind: string, text: string) => void;
  /** Pauses the running session (Teach mode owns the view meanwhile). */
  pauseRun: () => Promise<void>;
  /** Shows a new session's first frame in the Run tab; plays it if `autoplay`. `inFolder`: the
   * task was taught in the open task folder; `goal`: its goal facts. */
  runTaught: (f: Frame, autoplay: boolean, inFolder: boolean, goal: string[]) => Promise<void>;
}

const ms = (m: number) => `${(m * 1000).toFixed(1)} mm`;
/** Where a recording or a taught demo is: `./sorting` (a task folder) or `B1`. */
const taskLabel = (t: { benchmark: Benchmark | null; folder: string | null }): string => t.folder ?? t.benchmark?.toUpperCase() ?? 'the task';
/** The open folder as the taught-task calls take it. */
const asTaught = (f: OpenFolder): TaughtFolder => ({ files: f.files, dir: f.name });
/** The world a folder's `scene.json` names (null: unreadable). */
function sceneName(json: string | undefined): string | null {
  try {
    const name = (JSON.parse(json ?? '') as { name?: unknown }).name;
    return typeof name === 'string' ? name : null;
  } catch {
    return null;
  }
}

export class TeachPanel {
  private state: TeachState | null = null;
  private demoJson: string | null = null;
  private info: TaughtInfo | null = null;
  private visible = false;
  private mode: TeachMode = 'quick';
  private busy = false;
  private readonly handle: GripperHandle;
  private readonly stream: GripperStream;
  private closed = false;
  private newSegments = new Set<number>();
  /** Whether the listed demo is a loaded file (else the recording). */
  private loaded = false;
  /** The task folder the recording or the loaded demo was taught in (null: a benchmark's). */
  private taughtIn: TaughtFolder | null = null;

  private readonly ui: TeachUi;
  private readonly hint: DropHint;
  private readonly toast: MoveToast;

  constructor(
    readonly root: HTMLElement,
    private readonly host: TeachHost,
  ) {
    this.ui = buildTeachUi(root);
    this.hint = new DropHint(host.view.scene, () => host.view.controls.dispatchEvent({ type: 'change' }));
    // Quick mode only: there the page decides stack or place (`drop`), by the rule the hint shows.
    host.view.dragHint = (body, p) => this.hint.show(this.active && this.mode === 'quick' ? this.state!.world : null, body, p);
    this.toast = new MoveToast(host.stage);
    this.ui.modeBtns.forEach((b, i) => (b.onclick = () => this.setMode(TEACH_MODES[i][0])));
    this.handle = new GripperHandle(host.view, host.stage, (p, final) => this.queueGripper(p, final));
    this.stream = new GripperStream({
      send: (pose, duration) =>
        this.push({
          edit: 'gripper',
          arm: Number(this.ui.armSel.value || 0),
          position: pose.position,
          yaw: pose.yaw,
          gripper: this.closed ? 'closed' : 'open',
          duration,
        }),
      report: (m) => this.host.notice(m, 'error'),
      // Back to where the arm really is (it may not reach the commanded pose).
      settled: () => {
        if (!this.handle.dragging) this.placeHandle();
      },
    });
    this.ui.recordBtn.onclick = () => void this.guard(() => this.record());
    this.ui.stopBtn.onclick = () => void this.guard(() => this.stop());
    this.ui.undoBtn.onclick = () => void this.guard(() => this.undo());
    this.ui.gripBtn.onclick = () => this.toggleGrip();
    this.ui.saveBtn.onclick = () => this.save();
    this.ui.recBtn.onclick = () => void this.guard(() => this.saveRecording());
    this.ui.loadBtn.onclick = () => this.ui.fileIn.click();
    this.ui.fileIn.onchange = () => void this.guard(() => this.load());
    this.ui.runBtn.onclick = () => void this.guard(() => this.run());
    this.ui.armSel.onchange = () => this.placeHandle();
    document.addEventListener('keydown', (e) => {
      if (!this.active || this.mode !== 'gripper' || !isShortcut(e)) return;
      if (e.key.toLowerCase() === 'g') {
        e.preventDefault();
        this.toggleGrip();
      }
    });
    this.setMode('quick');
    this.refresh();
    window.lfdTeach = {
      state: () => this.state,
      info: () => this.info,
      demoJson: () => this.demoJson,
      handle: (part) => this.handle.screenPosition(part),
      busy: () => this.busy || this.stream.busy,
      dropHint: () => this.hint.current(),
    };
  }

  /** Whether Teach mode owns the view (the tab is shown and a recording exists). */
  get active(): boolean {
    return this.visible && this.state !== null;
  }

  /** Called when the side tab changes. */
  setVisible(on: boolean): void {
    this.visible = on;
    if (on && this.state) this.show(this.state);
    this.handle.show(this.active && this.mode === 'gripper');
    if (on) this.host.status('idle', this.statusText());
  }

  /** Ends any recording (the workcell changed); a loaded or taught demo is kept for Run. */
  reset(): void {
    if (!this.state) return;
    this.state = null;
    if (!this.loaded) {
      this.demoJson = null;
      this.info = null;
    }
    this.newSegments.clear();
    this.stream.clear();
    this.clearError();
    this.handle.show(false);
    this.toast.hide();
    void this.host.client.call('teachClose', {}).catch(() => {});
    this.refresh();
  }

  /** A block dropped in the view while Teach mode is active; resolves to a refusal or null. */
  async drop(d: DropRequest): Promise<string | null> {
    const s = this.state;
    if (!s) return 'press Record first';
    if (this.mode === 'gripper') return 'in gripper mode the robot moves blocks: drag the gripper handle, or switch to Quick';
    if (this.mode === 'hand') {
      await this.push({ edit: 'move', body: d.body, position: d.position });
      return null;
    }
    const onto = blockUnder(s.world, d.body, d.position);
    this.host.status('planning', `Recording: the robot carries ${d.body}…`);
    await this.push(
      onto
        ? { edit: 'drag', body: d.body, onto }
        : { edit: 'drag', body: d.body, position: [d.position[0], d.position[1]] },
    );
    return null;
  }

  // ---------------------------------------------------------------- recording

  private async record(): Promise<void> {
    await this.host.pauseRun();
    const open = this.host.folder();
    const folder = open ? asTaught(open) : undefined;
    const s = await this.host.client.call('teachStart', { benchmark: this.host.benchmark(), folder });
    this.taughtIn = folder ?? null;
    // The last run's arm trail is not part of the recording.
    this.host.view.clearTrail();
    this.forgetDemo();
    this.closed = false;
    this.newSegments.clear();
    this.clearError();
    this.toast.hide();
    this.ui.armSel.replaceChildren(...s.handles.map((h, i) => el('option', { value: String(i) }, h.arm)));
    this.ui.armSel.disabled = s.handles.length < 2;
    if (s.benchmark === 'b2' && this.mode === 'gripper') this.setMode('quick');
    this.show(s);
    this.host.notice('Recording: demonstrate the task, then press Stop', 'info');
  }

  private async push(edit: TeachEdit): Promise<TeachResult> {
    this.busy = true;
    try {
      const r = await this.host.client.call('teachPush', { edit });
      this.apply(r);
      if (r.ok && r.newSegments.length) this.toast.show(r.newSegments, 'recorded');
      return r;
    } finally {
      this.busy = false;
      if (this.active) this.host.status('idle', this.statusText());
    }
  }

  private apply(r: TeachResult): void {
    if (r.ok) {
      this.clearError();
      for (const seg of r.newSegments) this.newSegments.add(seg.index);
      if (r.newSegments.length) this.forgetDemo();
    } else this.showError(r.error);
    this.show(r.state);
  }

  /** Drops the taught or loaded demo (the recording changed). */
  private forgetDemo(): void {
    this.demoJson = null;
    this.info = null;
    this.loaded = false;
  }

  private queueGripper(pose: HandlePose, final: boolean): void {
    if (this.state) this.stream.queue(pose, final);
  }

  private toggleGrip(): void {
    if (!this.state || this.mode !== 'gripper') return;
    this.closed = !this.closed;
    this.updateGripButton();
    this.queueGripper(this.handle.current, true);
  }

  private updateGripButton(): void {
    this.ui.gripBtn.textContent = this.closed ? 'Open gripper' : 'Close gripper';
    this.ui.gripBtn.setAttribute('aria-pressed', String(this.closed));
  }

  /** Undoes the last whole move: actions are undone until no arm holds a block (a pick goes with
   * its place), so the world is back where it was before the move. */
  private async undo(): Promise<void> {
    const undone: Segment[] = [];
    let r = await this.host.client.call('teachUndo', {});
    while (r.ok && r.removed) {
      undone.push(r.removed);
      if (atRest(r.state) || !r.state.segments.length) break;
      r = await this.host.client.call('teachUndo', {});
    }
    this.newSegments.clear();
    this.forgetDemo();
    this.apply(r);
    if (r.ok) {
      this.closed = false;
      const h = r.state.handles[Number(this.ui.armSel.value || 0)];
      if (h) this.closed = h.gripper === 'closed';
      this.updateGripButton();
      this.host.notice(undone.length ? `Undid ${undone.map((u) => u.action).join(' and ')}` : 'Nothing to undo', 'info');
      this.toast.show(undone, 'undone');
    }
  }

  private async stop(): Promise<void> {
    const r = await this.host.client.call('teachFinish', {});
    if (!r.ok) {
      this.showError(r.error);
      return;
    }
    this.clearError();
    this.demoJson = r.demoJson;
    this.info = r.info;
    this.loaded = false;
    const worst = r.skills.reduce((m, f) => Math.max(m, f.rmsError), 0);
    this.ui.summary.textContent = `Taught ${r.info.actions.length} actions, demo states L0..L${r.info.actions.length}; ${r.skills.length} LQT-CP skills learned from the recorded motions (fit within ${ms(worst)} RMS).`;
    this.refresh();
    if (this.active) this.host.status('done', this.statusText());
    this.host.notice('Recording segmented: edit the goal if you like, then Run', 'info');
  }

  // ---------------------------------------------------------------- goal, save, load, run

  private renderGoal(): void {
    const info = this.info;
    this.ui.goalBox.hidden = !info;
    this.ui.runBox.hidden = !info;
    if (!info) return;
    this.ui.goalList.replaceChildren(...goalItems(info, () => void this.guard(() => this.setGoal())));
  }

  /** Deletes move `k` of the taught demo; the rest is checked again (each action must still apply
   * in turn and the goal hold at the end), else the demo stays as it was and the reason is shown. */
  private async deleteMove(k: number): Promise<void> {
    if (!this.demoJson || !this.info) return;
    const move = demoMoves(this.demoJson)[k];
    if (!move) return;
    const names = this.info.actions.slice(move[0], move[1]).join(' ');
    const json = withoutMove(this.demoJson, move);
    try {
      this.info = await this.host.client.call('teachInfo', { demoJson: json, folder: this.taughtIn ?? undefined });
    } catch (e) {
      const message = `Deleting move ${k + 1}, ${names}, leaves an invalid demonstration: ${(e as Error).message}`;
      this.showError({ kind: 'refused', message, t: null, added: [], removed: [] }, 'The demonstration is unchanged.');
      return;
    }
    this.demoJson = json;
    this.clearError();
    this.ui.summary.textContent = `Deleted move ${k + 1}, ${names}: ${this.info.actions.length} actions left, checked again.`;
    this.refresh();
    if (this.active) this.host.status('done', this.statusText());
  }

  private async setGoal(): Promise<void> {
    if (!this.demoJson) return;
    const json = withGoal(this.demoJson, checkedGoal(this.ui.goalList));
    try {
      this.info = await this.host.client.call('teachInfo', { demoJson: json, folder: this.taughtIn ?? undefined });
      this.demoJson = json;
      this.clearError();
    } catch (e) {
      this.showError({ kind: 'input', message: (e as Error).message, t: null, added: [], removed: [] });
      this.renderGoal();
    }
  }

  private save(): void {
    if (!this.demoJson) {
      this.host.notice('Stop the recording first: the demo is saved once it is segmented', 'error');
      return;
    }
    downloadJson(this.demoJson, `taught-${this.fileStem()}-demo.json`);
  }

  private async saveRecording(): Promise<void> {
    downloadJson(await this.host.client.call('teachRecording', {}), `taught-${this.fileStem()}-recording.json`);
  }

  /** The task in a file name: `b1`, or the folder's last name. */
  private fileStem(): string {
    const s = this.info ?? this.state;
    if (!s) return 'demo';
    return s.folder ? (s.folder.split('/').filter(Boolean).pop() ?? 'folder') : (s.benchmark ?? 'demo');
  }

  /** The open folder if the demo `json` was taught in its world and domain (else a benchmark's:
   * a folder may reuse a benchmark's world under its own domain). */
  private folderOf(json: string): TaughtFolder | null {
    const open = this.host.folder();
    let demo: { domain?: unknown; scene?: { name?: unknown } };
    try {
      demo = JSON.parse(json) as typeof demo;
    } catch {
      return null; // teachInfo reports the JSON error
    }
    const folderDomain = /\(\s*domain\s+([^\s()]+)/i.exec(open?.files['domain.pddl'] ?? '')?.[1];
    const ours = demo.domain === folderDomain && demo.scene?.name === sceneName(open?.files['scene.json']);
    return open && ours ? asTaught(open) : null;
  }

  private async load(): Promise<void> {
    const file = this.ui.fileIn.files?.[0];
    this.ui.fileIn.value = '';
    if (!file) return;
    const text = await file.text();
    const folder = this.folderOf(text);
    try {
      this.info = await this.host.client.call('teachInfo', { demoJson: text, folder: folder ?? undefined });
    } catch (e) {
      const kept = this.info ? 'Nothing was loaded: the demonstration listed below is unchanged.' : 'Nothing was loaded.';
      this.showError({ kind: 'input', message: `${file.name}: ${(e as Error).message}`, t: null, added: [], removed: [] }, kept);
      return;
    }
    this.demoJson = text;
    this.loaded = true;
    this.taughtIn = folder;
    this.clearError();
    this.ui.summary.textContent = `Loaded ${file.name}: ${this.info.actions.length} actions in ${taskLabel(this.info)}.`;
    this.refresh();
  }

  private async run(): Promise<void> {
    if (!this.demoJson) return;
    const start = this.ui.startSel.value as Start;
    const seed = parseSeed(this.ui.seedIn.value);
    const o = this.host.options();
    const f = await this.host.client.call('teachRun', {
      demoJson: this.demoJson,
      options: { seed, random: start === 'random', method: o.method, mode: o.mode },
      folder: this.taughtIn ?? undefined,
    });
    this.handle.show(false);
    await this.host.runTaught(f, start !== 'arrange', this.taughtIn !== null, this.info?.goal ?? []);
    if (start === 'arrange') this.host.notice('Arrange the blocks by dragging them, then press Play', 'info');
  }

  // ---------------------------------------------------------------- drawing

  private setMode(m: TeachMode): void {
    if (m === 'gripper' && this.state?.benchmark === 'b2') {
      this.host.notice("B2's hook pull is taught in Quick mode only", 'error');
      m = 'quick';
    }
    this.mode = m;
    this.ui.modeBtns.forEach((b, i) => {
      const on = TEACH_MODES[i][0] === m;
      b.classList.toggle('active', on);
      b.setAttribute('aria-pressed', String(on));
    });
    this.ui.gripRow.hidden = m !== 'gripper';
    this.ui.hint.textContent = TEACH_MODES.find(([k]) => k === m)![2];
    this.handle.show(this.active && m === 'gripper');
    this.placeHandle();
  }

  private placeHandle(): void {
    const h = this.state?.handles[Number(this.ui.armSel.value || 0)];
    if (!h) return;
    this.handle.set({ position: h.position, yaw: h.yaw }, h.gripper === 'closed');
  }

  private show(s: TeachState): void {
    this.state = s;
    if (this.visible) {
      this.host.view.update(s.world);
      this.host.status(this.busy ? 'planning' : 'idle', this.statusText());
    }
    if (!this.handle.dragging && !this.stream.sending) this.placeHandle();
    this.handle.show(this.active && this.mode === 'gripper');
    this.refresh();
  }

  private statusText(): string {
    const s = this.state;
    if (!s) return 'Teach: press ● Record to demonstrate a new task in this workcell';
    // Stopped: the taught demo (its moves may have been deleted), else the recording.
    const n = this.demoJson && this.info ? this.info.actions.length : s.segments.length;
    return `Teaching ${taskLabel(s)} · t = ${s.t.toFixed(2)} s · ${n} action${n === 1 ? '' : 's'} recognised${this.demoJson ? ' · stopped' : ' · recording'}`;
  }

  private refresh(): void {
    const s = this.state;
    const recording = s !== null;
    // Stopped: the demonstration is made; Stop has nothing left to end.
    this.ui.stopBtn.disabled = !recording || this.demoJson !== null;
    this.ui.undoBtn.disabled = !recording || s.segments.length === 0;
    this.ui.recBtn.disabled = !recording;
    this.ui.saveBtn.disabled = !this.demoJson;
    this.ui.recordBtn.textContent = recording ? '● New recording' : '● Record';
    this.ui.clock.textContent = s ? `t = ${s.t.toFixed(2)} s` : '';
    this.renderPull();
    // The listing: the recording while recording; once stopped or loaded, the taught demo (whose
    // moves may be deleted).
    const items = s && !this.demoJson ? recordingItems(s, this.newSegments) : this.info && this.demoJson ? taughtItems(this.info, demoMoves(this.demoJson), (k) => void this.guard(() => this.deleteMove(k))) : [];
    if (!items.length) items.push(el('li', { class: 'muted empty' }, recording ? 'nothing yet: demonstrate the first action' : 'not recording'));
    this.ui.list.replaceChildren(...items);
    this.ui.list.lastElementChild?.scrollIntoView({ block: 'nearest' });
    const n = (this.demoJson ? this.info?.actions.length : s?.segments.length) ?? 0;
    this.ui.count.textContent = n ? `${n} actions` : '';
    if (!this.demoJson) this.ui.summary.textContent = '';
    this.renderGoal();
  }

  private renderPull(): void {
    const s = this.state;
    if (!s || s.benchmark !== 'b2') {
      this.ui.pullRow.hidden = true;
      return;
    }
    this.ui.pullRow.hidden = false;
    const blocks = s.world.bodies.filter((b) => b.kind === 'block').map((b) => b.name);
    this.ui.pullRow.replaceChildren(
      el('span', { class: 'muted small' }, 'hook'),
      ...blocks.map((b) => {
        const btn = button(`teach-pull-${b}`, `Pull ${b} into reach with the hook`, `Pull ${b}`);
        btn.onclick = () =>
          void this.guard(async () => {
            await this.push({ edit: 'pull', body: b });
          });
        return btn;
      }),
    );
  }

  private showError(e: TeachError, kept?: string): void {
    this.ui.errorBox.replaceChildren(...errorContent(e, kept));
    this.ui.errorBox.hidden = false;
  }

  private clearError(): void {
    this.ui.errorBox.hidden = true;
    this.ui.errorBox.replaceChildren();
  }

  private guard(f: () => Promise<void>): Promise<void> {
    return guard(f, (m) => this.host.notice(m, 'error'));
  }
}

declare global {
  interface Window {
    lfdTeach: {
      state: () => TeachState | null;
      info: () => TaughtInfo | null;
      demoJson: () => string | null;
      handle: (part: 'move' | 'lift' | 'turn') => { x: number; y: number };
      busy: () => boolean;
      dropHint: () => DropHintState | null;
    };
  }
}
