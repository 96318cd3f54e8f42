/**
 * The page's DOM: the top bar (scenario, playback, disturbances, scene and link, help), the stage
 * that holds the 3-D view with its status line, clock and notices, and the side with its tabs (Run,
 * Teach, Charts, PDDL). Builds the elements, mounts them in #app and hands back the ones the panels
 * use; no behaviour lives here.
 */
import { robotDirInput, robotSelect } from './robot-choice';
import type { Benchmark, Catalogue } from 'logic-lfd';
import { items } from './catalogue';
import { button, el, select } from './dom';
import { HelpOverlay } from './help';
import { SPEEDS, blockItems, blockRange, type PageState, type Scenario, type TabId } from './state';

/** The top bar's controls. */
export interface Controls {
  benchSel: HTMLSelectElement;
  /** Blocks of the generated tower task ('': the benchmark's template task). */
  blocksSel: HTMLSelectElement;
  /** The robot in the arms' place (robot-choice.ts). */
  robotSel: HTMLSelectElement;
  /** The directory picker behind the robot select's "Open robot folder…". */
  robotDirIn: HTMLInputElement;
  methodSel: HTMLSelectElement;
  modeSel: HTMLSelectElement;
  seedIn: HTMLInputElement;
  resetBtn: HTMLButtonElement;
  playBtn: HTMLButtonElement;
  stepBtn: HTMLButtonElement;
  speedSel: HTMLSelectElement;
  /** The disturbance buttons' group, and the buttons (made when the catalogue arrives). */
  levelGroup: HTMLElement;
  levelBtns: HTMLButtonElement[];
  saveBtn: HTMLButtonElement;
  loadBtn: HTMLButtonElement;
  fileIn: HTMLInputElement;
  /** The directory picker behind the benchmark select's "Open folder…". */
  dirIn: HTMLInputElement;
  linkBtn: HTMLButtonElement;
  helpBtn: HTMLButtonElement;
}

/** The stage over the 3-D view: status line (with Cancel), clock, notices. */
export interface Stage {
  root: HTMLElement;
  status: HTMLElement;
  statusText: HTMLElement;
  cancelBtn: HTMLButtonElement;
  hud: HTMLElement;
  notice: HTMLElement;
}

/** The Run tab's lists. */
export interface RunLists {
  /** The task's goal in words. */
  goal: HTMLElement;
  planCount: HTMLElement;
  plan: HTMLOListElement;
  replanInfo: HTMLElement;
  matched: HTMLElement;
  demo: HTMLOListElement;
  factsDiff: HTMLElement;
  facts: HTMLUListElement;
}

/** A side tab: its button and its panel. */
export interface Tab {
  id: TabId;
  button: HTMLButtonElement;
  panel: HTMLElement;
}

export interface Layout {
  app: HTMLElement;
  version: HTMLElement;
  /** Says the Run runs a taught task (hidden otherwise). */
  taskTag: HTMLElement;
  controls: Controls;
  stage: Stage;
  run: RunLists;
  tabs: Tab[];
  /** Panels filled by their own modules: charts, the PDDL editor, Teach mode. */
  chartsPanel: HTMLElement;
  editorHost: HTMLElement;
  teachSlot: HTMLElement;
  compareSlot: HTMLElement;
  help: HelpOverlay;
}

const BLOCKS_TITLE = "Blocks: the benchmark's task as in the paper, or a generated tower of N blocks";

/** Fills the block select with benchmark `b`'s choices, set to `blocks` (undefined: template);
 * disabled, saying why, for a benchmark without an N-block task, and until the worker has sent
 * the block counts (showing the count asked for meanwhile). */
export function setBlockChoices(sel: HTMLSelectElement, b: Benchmark, blocks: number | null | undefined): void {
  const r = blockRange(b);
  const items = blockItems(b);
  if (r === 'unknown' && blocks != null) items.push([String(blocks), `${blocks} blocks`]);
  sel.replaceChildren(...items.map(([v, t]) => el('option', { value: v }, t)));
  sel.value = blocks == null ? '' : String(blocks);
  sel.disabled = r === null || r === 'unknown';
  sel.title =
    r === 'unknown'
      ? `${BLOCKS_TITLE} (loading)`
      : r
        ? `${BLOCKS_TITLE} (${b.toUpperCase()}: ${r[0]} to ${r[1]})`
        : `${b.toUpperCase()} has no N-block variant: it runs its task as in the paper`;
}

function blockSelect(b: Benchmark, blocks: number | null | undefined): HTMLSelectElement {
  const sel = el('select', { id: 'blocks', 'aria-label': 'Blocks' });
  setBlockChoices(sel, b, blocks);
  return sel;
}

/** A select that shows `value` alone, disabled, until the catalogue fills it. */
function pending<T extends string>(id: string, label: string, value: T): HTMLSelectElement {
  const s = select(id, label, [[value, value]], value);
  s.disabled = true;
  return s;
}

/** Sets a select's items and value, and enables it. */
function fill<T extends string>(sel: HTMLSelectElement, choices: [T, string][], value: T): void {
  sel.replaceChildren(...choices.map(([v, t]) => el('option', { value: v }, t)));
  sel.value = value;
  sel.disabled = false;
}

/** The benchmark select's item that opens a task folder, and the one of the open folder. */
export const OPEN_FOLDER = 'open-folder';
export const FOLDER = 'folder';
/** The benchmark select's item while the Run runs a taught task. */
export const TAUGHT = 'taught';
/** The gallery's task folders, served beside the page at `tasks/NAME/` (web/vite.config.ts). */
export const GALLERY: { name: string; label: string; title: string }[] = [
  { name: 'sorting', label: 'Sorting task', title: 'Sorting: cubes of two colours from a mixed pile into two trays, one stack per tray' },
  { name: 'shelf-tower', label: 'Shelf tower', title: 'Shelf tower: a tower in a given order on a shelf another block occupies' },
];
/** The select's value of gallery task `name`. */
export const galleryValue = (name: string): string => `tasks/${name}`;

/** Adds to the benchmark select the open folder (selected; null: none) and the item that opens
 * one. */
export function setFolderChoice(sel: HTMLSelectElement, folder: string | null, benchmark: Benchmark): void {
  for (const v of [FOLDER, OPEN_FOLDER, TAUGHT, ...GALLERY.map((g) => galleryValue(g.name))]) sel.querySelector(`option[value="${v}"]`)?.remove();
  if (folder !== null) {
    // The folder's last name, short: the select is as wide as its longest item.
    const name = folder.split('/').filter((p) => p && p !== '.').pop() ?? folder;
    sel.append(el('option', { value: FOLDER, title: `The task folder ${folder}` }, `folder · ${name.length > 14 ? `${name.slice(0, 13)}…` : name}`));
  }
  for (const g of GALLERY) {
    if (folder !== galleryValue(g.name)) sel.append(el('option', { value: galleryValue(g.name), title: g.title }, g.label));
  }
  sel.append(el('option', { value: OPEN_FOLDER, title: 'Open a task folder of your own: pick its directory' }, 'Open folder…'));
  sel.value = folder !== null ? FOLDER : benchmark;
}

/** Fills the benchmark, method and mode selects and makes the disturbance buttons from the catalogue
 * the worker sent, the selects set to scenario `o`. */
export function setCatalogueChoices(c: Controls, cat: Catalogue, o: Scenario): void {
  fill(c.benchSel, items(cat.benchmarks), o.benchmark);
  setFolderChoice(c.benchSel, null, o.benchmark);
  fill(c.methodSel, items(cat.methods), o.method);
  fill(c.modeSel, items(cat.modes), o.mode);
  const buttons = cat.levels.map(({ id, label, description }, i) => {
    const b = button(`inject-${id}`, `${label}, the paper’s ${id.toUpperCase()} (key ${i + 1}): ${description}`, label, 'level');
    b.dataset.level = id;
    return b;
  });
  c.levelBtns.splice(0, c.levelBtns.length, ...buttons);
  c.levelGroup.append(...buttons);
}

function buildControls(s: PageState): Controls {
  const o = s.options;
  return {
    benchSel: pending('benchmark', 'Benchmark', o.benchmark),
    blocksSel: blockSelect(o.benchmark, o.blocks),
    robotSel: robotSelect(s.robot),
    robotDirIn: robotDirInput(),
    methodSel: pending('method', 'Method', o.method),
    modeSel: pending('mode', 'Multi-goal mode', o.mode),
    seedIn: el('input', { id: 'seed', type: 'number', min: '0', step: '1', 'aria-label': 'Random seed', title: 'Random seed', value: String(o.seed) }),
    resetBtn: button('reset', 'Reset the episode with this seed (R)', '↺ Reset'),
    playBtn: button('play', 'Play (Space)', '▶ Play', 'primary'),
    stepBtn: button('step', 'Advance 0.1 s of simulated time (N)', 'Step'),
    speedSel: select('speed', 'Playback speed', SPEEDS, String(s.speed)),
    levelGroup: el('div', { class: 'group', role: 'group', 'aria-label': 'Disturb the task' }),
    levelBtns: [],
    saveBtn: button('save-scene', 'Save the current scene as JSON', 'Save'),
    loadBtn: button('load-scene', 'Load a scene or a saved run (JSON), or a task folder’s files or .zip', 'Load'),
    fileIn: el('input', {
      id: 'load-file',
      type: 'file',
      multiple: '',
      accept: 'application/json,.json,.zip,application/zip,.pddl,.plan,.md',
      hidden: '',
      'aria-label': 'Scene or saved run (JSON), or a task folder’s files or .zip',
    }),
    dirIn: el('input', { id: 'folder-dir', type: 'file', webkitdirectory: '', multiple: '', hidden: '', 'aria-label': 'Task folder' }),
    linkBtn: button('permalink', 'Copy a link to this benchmark, block count, method, mode and seed', 'Link'),
    helpBtn: button('help', 'Keyboard shortcuts and help (?)', '?'),
  };
}

function buildStage(c: Controls): Stage {
  const statusText = el('span', { id: 'status-text', class: 'status-text' }, 'Loading the planner…');
  const statusDot = el('span', { class: 'status-dot', 'aria-hidden': 'true' });
  const cancelBtn = button('cancel', 'Cancel the current plan: the robot stops and replans (C)', 'Cancel');
  cancelBtn.hidden = true;
  const status = el('div', { id: 'status', class: 'status idle', role: 'status', 'aria-live': 'polite' }, statusDot, statusText, cancelBtn);
  const hud = el('div', { id: 'hud', class: 'hud', 'aria-label': 'Simulation clock and timings' });
  const notice = el('div', { id: 'notice', class: 'notice', role: 'alert', hidden: '' });
  // The robot select sits on the view it changes (bottom right, over the Capsules / Meshes switch).
  const robot = el('label', { class: 'robot-choice' }, 'robot', c.robotSel, c.robotDirIn);
  const root = el('section', { class: 'stage', 'aria-label': 'Workcell' }, status, hud, notice, robot);
  return { root, status, statusText, cancelBtn, hud, notice };
}

function buildRunPanel(): { panel: HTMLElement; lists: RunLists } {
  const lists: RunLists = {
    goal: el('p', { id: 'goal', class: 'goal' }),
    planCount: el('span', { class: 'muted', id: 'plan-count' }),
    plan: el('ol', { id: 'plan', class: 'plan-list', 'aria-label': 'Current plan' }),
    replanInfo: el('div', { id: 'replan-info', class: 'replan-info' }),
    matched: el('span', { class: 'muted', id: 'matched' }),
    demo: el('ol', { id: 'demo', class: 'demo-list', 'aria-label': 'Demonstration states and actions' }),
    factsDiff: el('div', { id: 'facts-diff', class: 'facts-diff', 'aria-live': 'polite' }),
    facts: el('ul', { id: 'facts', class: 'facts', 'aria-label': 'Current facts' }),
  };
  const panel = el(
    'div',
    { class: 'panel', id: 'panel-run', role: 'tabpanel' },
    el('h2', {}, 'Goal ', el('span', { class: 'muted' }, 'G')),
    lists.goal,
    el('h2', {}, 'Plan ', lists.planCount),
    lists.plan,
    lists.replanInfo,
    el('h2', {}, 'Demonstration ', lists.matched),
    lists.demo,
    el('h2', {}, 'Facts ', el('span', { class: 'muted' }, 'S', el('sub', {}, 'C'))),
    lists.factsDiff,
    lists.facts,
  );
  return { panel, lists };
}

function buildTopBar(c: Controls, version: HTMLElement, taskTag: HTMLElement): HTMLElement {
  return el(
    'header',
    { class: 'topbar' },
    el('div', { class: 'brand' }, el('strong', {}, 'logic-lfd'), version, taskTag),
    el('div', { class: 'group', role: 'group', 'aria-label': 'Scenario' }, c.benchSel, c.blocksSel, c.methodSel, c.modeSel, el('label', { class: 'seed' }, 'seed', c.seedIn), c.resetBtn),
    el('div', { class: 'group', role: 'group', 'aria-label': 'Playback' }, c.playBtn, c.stepBtn, c.speedSel),
    c.levelGroup,
    el('div', { class: 'group right', role: 'group', 'aria-label': 'Scene and link' }, c.saveBtn, c.loadBtn, c.fileIn, c.dirIn, c.linkBtn, c.helpBtn),
  );
}

/** Builds the page for state `s` and mounts it in #app (replacing the boot message). */
export function buildLayout(s: PageState): Layout {
  const controls = buildControls(s);
  const stage = buildStage(controls);
  const run = buildRunPanel();
  const chartsPanel = el('div', { class: 'panel', id: 'panel-charts', role: 'tabpanel', hidden: '' });
  const editorHost = el('div', { class: 'panel panel-editor', id: 'panel-pddl', role: 'tabpanel', hidden: '' });
  const teachSlot = el('div', { class: 'panel', id: 'panel-teach', role: 'tabpanel', hidden: '' });
  const compareSlot = el('div', { class: 'panel', id: 'panel-compare', role: 'tabpanel', hidden: '' });
  const tabDefs: [TabId, string, HTMLElement][] = [
    ['run', 'Run', run.panel],
    ['teach', 'Teach', teachSlot],
    ['charts', 'Charts', chartsPanel],
    ['pddl', 'PDDL', editorHost],
    ['compare', 'Compare', compareSlot],
  ];
  const tabs: Tab[] = tabDefs.map(([id, text, panel]) => ({
    id,
    panel,
    button: el('button', { id: `tab-${id}`, role: 'tab', class: 'tab', 'aria-controls': `panel-${id}`, 'aria-selected': 'false', type: 'button' }, text),
  }));
  const side = el(
    'aside',
    { class: 'side', 'aria-label': 'Plan, demonstration, facts, charts and PDDL' },
    el('div', { class: 'side-tabs', role: 'tablist' }, ...tabs.map((t) => t.button)),
    ...tabs.map((t) => t.panel),
  );
  const help = new HelpOverlay(controls.helpBtn);
  const version = el('span', { id: 'version', class: 'muted' });
  const taskTag = el('span', { id: 'task-tag', class: 'task-tag', hidden: '' });
  const app = document.getElementById('app')!;
  app.replaceChildren(buildTopBar(controls, version, taskTag), el('main', { class: 'layout' }, stage.root, side), help.root);
  return { app, version, taskTag, controls, stage, run: run.lists, tabs, chartsPanel, editorHost, teachSlot, compareSlot, help };
}
