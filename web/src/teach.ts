// Teach mode: record a new demonstration in the workcell and run it with Logic-LfD.
//
// Record → demonstrate (quick: drag a block and the robot carries it; gripper: move the 3-D
// gripper handle, open/close it, the arm follows by IK; by hand: nudge a block without the robot)
// → Stop. Every edit is segmented in the worker into the domain's actions as it happens; the
// panel lists the actions a1..aN and the demo states L0..LN, and refusals (a change the PDDL model
// cannot explain, a release in mid-air) with their time and fact change — a refused edit leaves the
// recording as it was. After Stop: the goal (L_N's facts by default, editable), save/load of the
// taught demo.json, and Run: a closed-loop session of the taught task from a random, the taught or
// a user-arranged initial world, disturbed with the usual drag and L1–L4 buttons.
import type { Frame, SessionOptions, TaughtInfo, TeachEdit, TeachError, TeachResult, TeachState, WorldSnapshot } from 'logic-lfd';
import type { WorkerClient } from './client';
import type { View, DropRequest } from './view';
import { el } from './dom';
import { GripperHandle, type HandlePose } from './teach-gripper';

type Benchmark = SessionOptions['benchmark'];
type TeachMode = 'quick' | 'gripper' | 'hand';
type Start = 'random' | 'taught' | 'arrange';

export interface TeachHost {
  client: WorkerClient;
  view: View;
  stage: HTMLElement;
  benchmark: () => Benchmark;
  options: () => SessionOptions;
  notice: (text: string, kind: 'info' | 'error') => void;
  status: (kind: string, text: string) => void;
  /** Pauses the running session (Teach mode owns the view meanwhile). */
  pauseRun: () => Promise<void>;
  /** Shows a new session's first frame in the Run tab; plays it if `autoplay`. */
  runTaught: (f: Frame, autoplay: boolean) => Promise<void>;
}

const MODES: [TeachMode, string, string][] = [
  ['quick', 'Quick', 'Drag a block onto a block or a place: the robot carries it (the arm motion is synthesised)'],
  ['gripper', 'Gripper', 'Drag the gripper handle (ball: move, blue arrow: up/down, green ring: turn); G or the button closes/opens it'],
  ['hand', 'By hand', 'Move a block by hand, without the robot (only a nudge that changes no fact is accepted)'],
];

function button(id: string, label: string, text: string, cls = ''): HTMLButtonElement {
  return el('button', { id, 'aria-label': label, title: label, class: cls, type: 'button' }, text);
}

const ms = (m: number) => `${(m * 1000).toFixed(1)} mm`;

export class TeachPanel {
  private state: TeachState | null = null;
  private demoJson: string | null = null;
  private info: TaughtInfo | null = null;
  private visible = false;
  private mode: TeachMode = 'quick';
  private busy = false;
  private readonly handle: GripperHandle;
  private closed = false;
  private inflight = false;
  private pending: { pose: HandlePose; final: boolean } | null = null;
  private lastSend = 0;
  private newSegments = new Set<number>();
  /** Whether the listed demo is a loaded file (else the recording). */
  private loaded = false;

  private readonly recordBtn = button('teach-record', 'Start a new recording in this workcell', '● Record', 'primary');
  private readonly stopBtn = button('teach-stop', 'Stop recording: segment, learn the skills, edit the goal', '■ Stop');
  private readonly undoBtn = button('teach-undo', 'Undo the last recognised action (the world goes back to the end of the one before)', '↶ Undo');
  private readonly saveBtn = button('teach-save', 'Save the taught demonstration (demo.json)', 'Save demo');
  private readonly loadBtn = button('teach-load', 'Load a taught demonstration (demo.json)', 'Load demo');
  private readonly recBtn = button('teach-save-recording', 'Save the raw recording (for logic-lfd demo segment)', 'Save recording');
  private readonly fileIn = el('input', { type: 'file', accept: 'application/json,.json', hidden: '', 'aria-label': 'Taught demo JSON file' });
  private readonly modeBtns: HTMLButtonElement[];
  private readonly gripBtn = button('teach-grip', 'Close or open the gripper (G)', 'Close gripper');
  private readonly armSel = el('select', { id: 'teach-arm', 'aria-label': 'Arm to move', title: 'Arm to move' });
  private readonly pullRow = el('div', { class: 'teach-row', id: 'teach-pull' });
  private readonly gripRow = el('div', { class: 'teach-row', hidden: '' });
  private readonly hint = el('p', { class: 'muted small teach-hint', id: 'teach-hint' });
  private readonly errorBox = el('div', { id: 'teach-error', class: 'teach-error', role: 'alert', hidden: '' });
  private readonly list = el('ol', { id: 'teach-list', class: 'teach-list', 'aria-label': 'Recognised actions and demo states' });
  private readonly summary = el('div', { id: 'teach-summary', class: 'teach-summary' });
  private readonly goalList = el('ul', { id: 'teach-goal', class: 'teach-goal', 'aria-label': 'Goal facts' });
  private readonly goalBox = el('div', { hidden: '', id: 'teach-goal-box' });
  private readonly startSel = el(
    'select',
    { id: 'teach-start', 'aria-label': 'Initial world of the run', title: 'Initial world of the run' },
    el('option', { value: 'random' }, 'random initial world (seed)'),
    el('option', { value: 'taught' }, 'the taught initial world'),
    el('option', { value: 'arrange' }, 'arrange it myself, then Play'),
  );
  private readonly seedIn = el('input', { id: 'teach-seed', type: 'number', min: '0', step: '1', value: '1', 'aria-label': 'Seed of the random initial world', title: 'Seed of the random initial world' });
  private readonly runBtn = button('teach-run', 'Run the taught task with Logic-LfD', '▶ Run taught task', 'primary');
  private readonly runBox = el('div', { hidden: '', id: 'teach-run-box' });

  constructor(
    readonly root: HTMLElement,
    private readonly host: TeachHost,
  ) {
    this.modeBtns = MODES.map(([m, text, what]) => {
      const b = button(`teach-mode-${m}`, what, text, 'tab');
      b.setAttribute('aria-pressed', 'false');
      b.onclick = () => this.setMode(m);
      return b;
    });
    this.handle = new GripperHandle(host.view, host.stage, (p, final) => this.queueGripper(p, final));
    root.append(
      el('h2', {}, 'Teach a task ', el('span', { class: 'muted', id: 'teach-clock' })),
      el('div', { class: 'teach-row' }, this.recordBtn, this.stopBtn, this.undoBtn),
      el('div', { class: 'teach-row', role: 'group', 'aria-label': 'How to demonstrate' }, el('span', { class: 'muted small' }, 'demonstrate'), ...this.modeBtns),
      this.gripRow,
      this.pullRow,
      this.hint,
      this.errorBox,
      el('h2', {}, 'Demonstration ', el('span', { class: 'muted', id: 'teach-count' })),
      this.list,
      this.summary,
      el('div', { class: 'teach-row' }, this.saveBtn, this.loadBtn, this.recBtn, this.fileIn),
      this.goalBox,
      this.runBox,
    );
    this.gripRow.append(el('label', { class: 'muted small' }, 'arm ', this.armSel), this.gripBtn);
    this.goalBox.append(
      el('h2', {}, 'Goal ', el('span', { class: 'muted' }, 'facts the run must reach (default: every fact of L', el('sub', {}, 'N'), ')')),
      this.goalList,
    );
    this.runBox.append(
      el('h2', {}, 'Run the taught task'),
      el('div', { class: 'teach-row' }, this.startSel, el('label', { class: 'seed' }, 'seed', this.seedIn)),
      el('div', { class: 'teach-row' }, this.runBtn),
      el('p', { class: 'muted small' }, 'Logic-LfD plans to the nearest demo state and follows the taught actions; drag blocks or press L1–L4 while it works.'),
    );
    this.recordBtn.onclick = () => void this.guard(() => this.record());
    this.stopBtn.onclick = () => void this.guard(() => this.stop());
    this.undoBtn.onclick = () => void this.guard(() => this.undo());
    this.gripBtn.onclick = () => this.toggleGrip();
    this.saveBtn.onclick = () => this.save();
    this.recBtn.onclick = () => void this.guard(() => this.saveRecording());
    this.loadBtn.onclick = () => this.fileIn.click();
    this.fileIn.onchange = () => void this.guard(() => this.load());
    this.runBtn.onclick = () => void this.guard(() => this.run());
    this.armSel.onchange = () => this.placeHandle();
    document.addEventListener('keydown', (e) => {
      const t = e.target as HTMLElement;
      if (!this.active || this.mode !== 'gripper' || e.ctrlKey || e.metaKey || e.altKey) return;
      if (t instanceof HTMLInputElement || t instanceof HTMLSelectElement || t.closest('.cm-editor')) return;
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
      busy: () => this.busy || this.inflight || this.pending !== null,
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
    this.pending = null;
    this.clearError();
    this.handle.show(false);
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
    const onto = this.blockUnder(s.world, d.body, d.position);
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
    const s = await this.host.client.call('teachStart', { benchmark: this.host.benchmark() });
    this.demoJson = null;
    this.info = null;
    this.loaded = false;
    this.closed = false;
    this.newSegments.clear();
    this.clearError();
    this.armSel.replaceChildren(...s.handles.map((h, i) => el('option', { value: String(i) }, h.arm)));
    this.armSel.disabled = s.handles.length < 2;
    if (s.benchmark === 'b2' && this.mode === 'gripper') this.setMode('quick');
    this.show(s);
    this.host.notice('Recording: demonstrate the task, then press Stop', 'info');
  }

  private async push(edit: TeachEdit): Promise<TeachResult> {
    this.busy = true;
    try {
      const r = await this.host.client.call('teachPush', { edit });
      this.apply(r);
      return r;
    } finally {
      this.busy = false;
      if (this.active) this.host.status('idle', this.statusText());
    }
  }

  private apply(r: TeachResult): void {
    if (r.ok) {
      this.clearError();
      for (const seg of r.new_segments) this.newSegments.add(seg.index);
      if (r.new_segments.length) {
        this.demoJson = null;
        this.info = null;
        this.loaded = false;
      }
    } else this.showError(r.error);
    this.show(r.state);
  }

  private queueGripper(pose: HandlePose, final: boolean): void {
    if (!this.state) return;
    this.pending = { pose, final: final || (this.pending?.final ?? false) };
    void this.pump();
  }

  private async pump(): Promise<void> {
    if (this.inflight || !this.pending) return;
    const { pose, final } = this.pending;
    this.pending = null;
    this.inflight = true;
    const now = performance.now();
    // The recording advances by the wall time between samples (bounded), so a slow drag is slow.
    const duration = final ? 0.5 : Math.min(0.3, Math.max(0.05, (now - (this.lastSend || now)) / 1000));
    this.lastSend = now;
    try {
      await this.push({
        edit: 'gripper',
        arm: Number(this.armSel.value || 0),
        position: pose.position,
        yaw: pose.yaw,
        gripper: this.closed ? 'closed' : 'open',
        duration,
      });
    } catch (e) {
      this.host.notice((e as Error).message, 'error');
    } finally {
      this.inflight = false;
    }
    if (this.pending) void this.pump();
    else if (final) {
      this.lastSend = 0;
      // Back to where the arm really is (it may not reach the commanded pose).
      if (!this.handle.dragging) this.placeHandle();
    }
  }

  private toggleGrip(): void {
    if (!this.state || this.mode !== 'gripper') return;
    this.closed = !this.closed;
    this.updateGripButton();
    this.queueGripper(this.handle.current, true);
  }

  private updateGripButton(): void {
    this.gripBtn.textContent = this.closed ? 'Open gripper' : 'Close gripper';
    this.gripBtn.setAttribute('aria-pressed', String(this.closed));
  }

  private async undo(): Promise<void> {
    const r = await this.host.client.call('teachUndo', {});
    this.newSegments.clear();
    this.demoJson = null;
    this.info = null;
    this.loaded = false;
    this.apply(r);
    if (r.ok) {
      this.closed = false;
      const h = r.state.handles[Number(this.armSel.value || 0)];
      if (h) this.closed = h.gripper === 'closed';
      this.updateGripButton();
      this.host.notice(r.removed ? `Undid ${r.removed.action}` : 'Nothing to undo', 'info');
    }
  }

  private async stop(): Promise<void> {
    const r = await this.host.client.call('teachFinish', {});
    if (!r.ok) {
      this.showError(r.error);
      return;
    }
    this.clearError();
    this.demoJson = r.demo_json;
    this.info = r.info;
    this.loaded = false;
    const worst = r.skills.reduce((m, f) => Math.max(m, f.rms_error), 0);
    this.summary.textContent = `Taught ${r.info.actions.length} actions, demo states L0..L${r.info.actions.length}; ${r.skills.length} LQT-CP skills learned from the recorded motions (fit within ${ms(worst)} RMS).`;
    this.refresh();
    if (this.active) this.host.status('done', this.statusText());
    this.host.notice('Recording segmented: edit the goal if you like, then Run', 'info');
  }

  // ---------------------------------------------------------------- goal, save, load, run

  private renderGoal(): void {
    const info = this.info;
    this.goalBox.hidden = !info;
    this.runBox.hidden = !info;
    if (!info) return;
    const last = info.states[info.states.length - 1];
    const goal = new Set(info.goal);
    this.goalList.replaceChildren(
      ...last.map((f) => {
        const box = el('input', { type: 'checkbox', 'aria-label': `goal fact ${f}` });
        box.checked = goal.has(f);
        box.onchange = () => void this.guard(() => this.setGoal());
        return el('li', {}, el('label', {}, box, ` ${f}`));
      }),
    );
  }

  private async setGoal(): Promise<void> {
    if (!this.demoJson) return;
    const goal = [...this.goalList.querySelectorAll('input')].filter((b) => b.checked).map((b) => (b.getAttribute('aria-label') ?? '').replace(/^goal fact /, ''));
    const demo = JSON.parse(this.demoJson) as { goal: string[] };
    demo.goal = goal;
    const json = JSON.stringify(demo);
    try {
      this.info = await this.host.client.call('teachInfo', { demoJson: json });
      this.demoJson = json;
      this.clearError();
    } catch (e) {
      this.showError({ kind: 'input', message: (e as Error).message, added: [], removed: [] });
      this.renderGoal();
    }
  }

  private save(): void {
    if (!this.demoJson) {
      this.host.notice('Stop the recording first: the demo is saved once it is segmented', 'error');
      return;
    }
    download(this.demoJson, `taught-${this.info?.benchmark ?? 'demo'}-demo.json`);
  }

  private async saveRecording(): Promise<void> {
    download(await this.host.client.call('teachRecording', {}), `taught-${this.host.benchmark()}-recording.json`);
  }

  private async load(): Promise<void> {
    const file = this.fileIn.files?.[0];
    this.fileIn.value = '';
    if (!file) return;
    const text = await file.text();
    try {
      this.info = await this.host.client.call('teachInfo', { demoJson: text });
    } catch (e) {
      this.showError({ kind: 'input', message: `${file.name}: ${(e as Error).message}`, added: [], removed: [] });
      return;
    }
    this.demoJson = text;
    this.loaded = true;
    this.clearError();
    this.summary.textContent = `Loaded ${file.name}: ${this.info.actions.length} actions in ${this.info.benchmark.toUpperCase()}.`;
    this.refresh();
  }

  private async run(): Promise<void> {
    if (!this.demoJson) return;
    const start = this.startSel.value as Start;
    const seed = Math.max(0, Math.floor(Number(this.seedIn.value)) || 0);
    const o = this.host.options();
    const f = await this.host.client.call('teachRun', {
      demoJson: this.demoJson,
      options: { seed, random: start === 'random', method: o.method, mode: o.mode },
    });
    this.handle.show(false);
    await this.host.runTaught(f, start !== 'arrange');
    if (start === 'arrange') this.host.notice('Arrange the blocks by dragging them, then press Play', 'info');
  }

  // ---------------------------------------------------------------- drawing

  private setMode(m: TeachMode): void {
    if (m === 'gripper' && this.state?.benchmark === 'b2') {
      this.host.notice("B2's hook pull is taught in Quick mode only", 'error');
      m = 'quick';
    }
    this.mode = m;
    this.modeBtns.forEach((b, i) => {
      const on = MODES[i][0] === m;
      b.classList.toggle('active', on);
      b.setAttribute('aria-pressed', String(on));
    });
    this.gripRow.hidden = m !== 'gripper';
    this.hint.textContent = MODES.find(([k]) => k === m)![2];
    this.handle.show(this.active && m === 'gripper');
    this.placeHandle();
  }

  private placeHandle(): void {
    const h = this.state?.handles[Number(this.armSel.value || 0)];
    if (!h) return;
    this.handle.set({ position: h.position, yaw: h.yaw }, h.gripper === 'closed');
  }

  private show(s: TeachState): void {
    this.state = s;
    if (this.visible) {
      this.host.view.update(s.world);
      this.host.status(this.busy ? 'planning' : 'idle', this.statusText());
    }
    if (!this.handle.dragging && !this.inflight) this.placeHandle();
    this.handle.show(this.active && this.mode === 'gripper');
    this.refresh();
  }

  private statusText(): string {
    const s = this.state;
    if (!s) return 'Teach: press ● Record to demonstrate a new task in this workcell';
    const n = s.segments.length;
    return `Teaching ${s.benchmark.toUpperCase()} · t = ${s.t.toFixed(2)} s · ${n} action${n === 1 ? '' : 's'} recognised${this.demoJson ? ' · stopped' : ' · recording'}`;
  }

  private refresh(): void {
    const s = this.state;
    const recording = s !== null;
    this.stopBtn.disabled = !recording;
    this.undoBtn.disabled = !recording || s.segments.length === 0;
    this.recBtn.disabled = !recording;
    this.saveBtn.disabled = !this.demoJson;
    this.recordBtn.textContent = recording ? '● New recording' : '● Record';
    (this.root.querySelector('#teach-clock') as HTMLElement).textContent = s ? `t = ${s.t.toFixed(2)} s` : '';
    this.renderPull();
    // The listing: from the recording while recording, else from a loaded demo.
    const items: HTMLElement[] = [];
    if (s && !this.loaded) {
      s.states.forEach((st, i) => {
        items.push(el('li', { class: 'demo-state', title: st.join(' ') }, `L${i}`, el('span', { class: 'muted' }, ` · ${st.length} facts`)));
        const seg = s.segments[i];
        if (seg) {
          const change = [...seg.added.map((f) => `+${f}`), ...seg.removed.map((f) => `−${f}`)].join(' ');
          items.push(
            el(
              'li',
              { class: `teach-seg${this.newSegments.has(i) ? ' new' : ''}`, title: change },
              el('span', { class: 'seg-name' }, `a${i + 1} ${seg.action}`),
              el('span', { class: 'muted small' }, ` ${seg.arm} · ${seg.t_start.toFixed(2)}–${seg.t_end.toFixed(2)} s`),
            ),
          );
        }
      });
    } else if (this.info) {
      this.info.states.forEach((st, i) => {
        items.push(el('li', { class: 'demo-state', title: st.join(' ') }, `L${i}`, el('span', { class: 'muted' }, ` · ${st.length} facts`)));
        if (i < this.info!.actions.length) items.push(el('li', { class: 'teach-seg' }, el('span', { class: 'seg-name' }, `a${i + 1} ${this.info!.actions[i]}`), el('span', { class: 'muted small' }, ` ${this.info!.arms[i]}`)));
      });
    }
    if (!items.length) items.push(el('li', { class: 'muted empty' }, recording ? 'nothing yet: demonstrate the first action' : 'not recording'));
    this.list.replaceChildren(...items);
    this.list.lastElementChild?.scrollIntoView({ block: 'nearest' });
    const n = s?.segments.length ?? this.info?.actions.length ?? 0;
    (this.root.querySelector('#teach-count') as HTMLElement).textContent = n ? `${n} actions` : '';
    if (!this.demoJson) this.summary.textContent = '';
    this.renderGoal();
  }

  private renderPull(): void {
    const s = this.state;
    if (!s || s.benchmark !== 'b2') {
      this.pullRow.hidden = true;
      return;
    }
    this.pullRow.hidden = false;
    const blocks = s.world.bodies.filter((b) => b.kind === 'block').map((b) => b.name);
    this.pullRow.replaceChildren(
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

  private showError(e: TeachError): void {
    const what = { input: 'Bad input', model: 'Model', unexplained: 'Not explained by the domain', physics: 'Physically implausible', refused: 'Refused' }[e.kind];
    this.errorBox.replaceChildren(
      el('strong', {}, `${what}${e.t != null ? ` at t = ${e.t.toFixed(2)} s` : ''}`),
      el('div', { class: 'teach-error-msg' }, e.message),
      el(
        'div',
        { class: 'facts-diff' },
        ...e.added.map((x) => el('span', { class: 'chip added' }, `+ ${x}`)),
        ...e.removed.map((x) => el('span', { class: 'chip removed' }, `− ${x}`)),
      ),
      el('div', { class: 'muted small' }, 'Nothing was recorded from this edit.'),
    );
    this.errorBox.hidden = false;
  }

  private clearError(): void {
    this.errorBox.hidden = true;
    this.errorBox.replaceChildren();
  }

  /** The block under a drop point (stack onto it), if the point is above one's top face. */
  private blockUnder(w: WorldSnapshot, body: string, p: [number, number, number]): string | null {
    let best: { name: string; top: number } | null = null;
    for (const b of w.bodies) {
      if (b.kind !== 'block' || b.name === body || b.shape.type !== 'cuboid') continue;
      const [hx, hy, hz] = b.shape.half_extents;
      const [x, y, z] = b.pose.position;
      const q = b.pose.quaternion;
      const yaw = Math.atan2(2 * (q[3] * q[2] + q[0] * q[1]), 1 - 2 * (q[1] * q[1] + q[2] * q[2]));
      const dx = p[0] - x;
      const dy = p[1] - y;
      const lx = Math.cos(yaw) * dx + Math.sin(yaw) * dy;
      const ly = -Math.sin(yaw) * dx + Math.cos(yaw) * dy;
      const top = z + hz;
      if (Math.abs(lx) <= hx + 0.005 && Math.abs(ly) <= hy + 0.005 && p[2] > top - 0.005 && (!best || top > best.top)) best = { name: b.name, top };
    }
    return best?.name ?? null;
  }

  private async guard(f: () => Promise<void>): Promise<void> {
    try {
      await f();
    } catch (e) {
      this.host.notice((e as Error).message, 'error');
    }
  }
}

function download(text: string, name: string): void {
  const a = el('a', { href: URL.createObjectURL(new Blob([text], { type: 'application/json' })), download: name });
  a.click();
  URL.revokeObjectURL(a.href);
}

declare global {
  interface Window {
    lfdTeach: {
      state: () => TeachState | null;
      info: () => TaughtInfo | null;
      demoJson: () => string | null;
      handle: (part: 'move' | 'lift' | 'turn') => { x: number; y: number };
      busy: () => boolean;
    };
  }
}
