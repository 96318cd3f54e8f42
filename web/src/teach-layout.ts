/**
 * The Teach tab's DOM: Record / Stop / Undo, the ways to demonstrate (with the gripper's arm and
 * grip, and B2's hook pulls), the refusal box, the listing of recognised actions and demo states,
 * save and load, the goal checklist and the run box. Builds the elements into the tab's panel and
 * hands them back; no behaviour lives here.
 */
import { button, el } from './dom';

export type TeachMode = 'quick' | 'gripper' | 'hand';

/** The ways to demonstrate: mode, button text, what it does (tooltip and hint). */
export const TEACH_MODES: [TeachMode, string, string][] = [
  ['quick', 'Quick', 'Drag a block onto a block or a place: the robot carries it (the arm motion is synthesised)'],
  ['gripper', 'Gripper', 'Drag the gripper handle (ball: move, blue arrow: up/down, green ring: turn); G or the button closes/opens it'],
  ['hand', 'By hand', 'Move a block by hand, without the robot (only a nudge that changes no fact is accepted)'],
];

export interface TeachUi {
  recordBtn: HTMLButtonElement;
  stopBtn: HTMLButtonElement;
  undoBtn: HTMLButtonElement;
  saveBtn: HTMLButtonElement;
  loadBtn: HTMLButtonElement;
  recBtn: HTMLButtonElement;
  fileIn: HTMLInputElement;
  modeBtns: HTMLButtonElement[];
  gripBtn: HTMLButtonElement;
  armSel: HTMLSelectElement;
  pullRow: HTMLElement;
  gripRow: HTMLElement;
  hint: HTMLElement;
  errorBox: HTMLElement;
  clock: HTMLElement;
  count: HTMLElement;
  list: HTMLOListElement;
  summary: HTMLElement;
  goalList: HTMLUListElement;
  goalBox: HTMLElement;
  startSel: HTMLSelectElement;
  seedIn: HTMLInputElement;
  runBtn: HTMLButtonElement;
  runBox: HTMLElement;
}

function buildElements(): TeachUi {
  return {
    recordBtn: button('teach-record', 'Start a new recording in this workcell', '● Record', 'primary'),
    stopBtn: button('teach-stop', 'Stop recording: segment, learn the skills, edit the goal', '■ Stop'),
    undoBtn: button('teach-undo', 'Undo the last move: its pick and its place together (the world goes back to before the move)', '↶ Undo'),
    saveBtn: button('teach-save', 'Save the taught demonstration (demo.json)', 'Save demo'),
    loadBtn: button('teach-load', 'Load a taught demonstration (demo.json)', 'Load demo'),
    recBtn: button('teach-save-recording', 'Save the raw recording (for logic-lfd demo segment)', 'Save recording'),
    fileIn: el('input', { type: 'file', accept: 'application/json,.json', hidden: '', 'aria-label': 'Taught demo JSON file' }),
    modeBtns: TEACH_MODES.map(([m, text, what]) => {
      const b = button(`teach-mode-${m}`, what, text, 'tab');
      b.setAttribute('aria-pressed', 'false');
      return b;
    }),
    gripBtn: button('teach-grip', 'Close or open the gripper (G)', 'Close gripper'),
    armSel: el('select', { id: 'teach-arm', 'aria-label': 'Arm to move', title: 'Arm to move' }),
    pullRow: el('div', { class: 'teach-row', id: 'teach-pull' }),
    gripRow: el('div', { class: 'teach-row', hidden: '' }),
    hint: el('p', { class: 'muted small teach-hint', id: 'teach-hint' }),
    errorBox: el('div', { id: 'teach-error', class: 'teach-error', role: 'alert', hidden: '' }),
    clock: el('span', { class: 'muted', id: 'teach-clock' }),
    count: el('span', { class: 'muted', id: 'teach-count' }),
    list: el('ol', { id: 'teach-list', class: 'teach-list', 'aria-label': 'Recognised actions and demo states' }),
    summary: el('div', { id: 'teach-summary', class: 'teach-summary' }),
    goalList: el('ul', { id: 'teach-goal', class: 'teach-goal', 'aria-label': 'Goal facts' }),
    goalBox: el('div', { hidden: '', id: 'teach-goal-box' }),
    startSel: el(
      'select',
      { id: 'teach-start', 'aria-label': 'Initial world of the run', title: 'Initial world of the run' },
      el('option', { value: 'random' }, 'random initial world (seed)'),
      el('option', { value: 'taught' }, 'the taught initial world'),
      el('option', { value: 'arrange' }, 'arrange it myself, then Play'),
    ),
    seedIn: el('input', { id: 'teach-seed', type: 'number', min: '0', step: '1', value: '1', 'aria-label': 'Seed of the random initial world', title: 'Seed of the random initial world' }),
    runBtn: button('teach-run', 'Run the taught task with Logic-LfD', '▶ Run taught task', 'primary'),
    runBox: el('div', { hidden: '', id: 'teach-run-box' }),
  };
}

/** Builds the Teach tab into `root`. */
export function buildTeachUi(root: HTMLElement): TeachUi {
  const u = buildElements();
  root.append(
    el('h2', {}, 'Teach a task ', u.clock),
    el('div', { class: 'teach-row' }, u.recordBtn, u.stopBtn, u.undoBtn),
    el('div', { class: 'teach-row', role: 'group', 'aria-label': 'How to demonstrate' }, el('span', { class: 'muted small' }, 'demonstrate'), ...u.modeBtns),
    u.gripRow,
    u.pullRow,
    u.hint,
    u.errorBox,
    el('h2', {}, 'Demonstration ', u.count),
    u.list,
    u.summary,
    el('div', { class: 'teach-row' }, u.saveBtn, u.loadBtn, u.recBtn, u.fileIn),
    u.goalBox,
    u.runBox,
  );
  u.gripRow.append(el('label', { class: 'muted small' }, 'arm ', u.armSel), u.gripBtn);
  u.goalBox.append(
    el('h2', {}, 'Goal ', el('span', { class: 'muted' }, 'facts the run must reach (default: every fact of L', el('sub', {}, 'N'), ')')),
    u.goalList,
  );
  u.runBox.append(
    el('h2', {}, 'Run the taught task'),
    el('div', { class: 'teach-row' }, u.startSel, el('label', { class: 'seed' }, 'seed', u.seedIn)),
    el('div', { class: 'teach-row' }, u.runBtn),
    el('p', { class: 'muted small' }, 'Logic-LfD plans to the nearest demo state and follows the taught actions; drag blocks or use the disturbance buttons while it works.'),
  );
  return u;
}
