// The page: controls, the 3-D view, the run panels (plan, demo, facts), charts and the PDDL editor.
// All computation happens in the worker (client.ts ↔ worker.ts through protocol.ts).
import './style.css';
import type { Frame, SessionOptions } from 'logic-lfd';
import { SearchRunner, WorkerClient } from './client';
import { View } from './view';
import type { EditorPanel } from './editor';
import { Charts } from './charts';
import { el } from './dom';
import type { FromWorker, Level } from './protocol';
import type { TeachPanel } from './teach';

type Benchmark = SessionOptions['benchmark'];
type Method = SessionOptions['method'];
type Mode = SessionOptions['mode'];

const BENCHMARKS: [Benchmark, string][] = [
  ['b1', 'B1 · tower'],
  ['b2', 'B2 · reach (hook)'],
  ['b3', 'B3 · two arms'],
];
const METHODS: [Method, string][] = [
  ['logic-lfd', 'Logic-LfD'],
  ['linear', 'Linear'],
  ['rlds', 'RLDS'],
  ['tamp', 'TAMP'],
];
const MODES: [Mode, string][] = [
  ['paper', 'paper'],
  ['prioritised', 'prioritised'],
];
const LEVELS: [Level, string, string][] = [
  ['l1', 'L1', 'Motion-level: move a block a little; the facts stay the same'],
  ['l2', 'L2', 'Facts change to a state seen in the demonstration'],
  ['l3', 'L3', 'Facts change to a state the demonstration never saw'],
  ['l4', 'L4', 'A new block appears in the way'],
];

// ---------- state ----------
const params = new URLSearchParams(location.search);
const pick = <T extends string>(v: string | null, all: [T, ...unknown[]][], d: T): T =>
  all.some(([k]) => k === v) ? (v as T) : d;
const options: SessionOptions = {
  benchmark: pick(params.get('benchmark'), BENCHMARKS, 'b1'),
  method: pick(params.get('method'), METHODS, 'logic-lfd'),
  mode: pick(params.get('mode'), MODES, 'paper'),
  seed: Math.max(0, Math.floor(Number(params.get('seed') ?? '1')) || 0),
};
let speed = Number(params.get('speed') ?? '1') || 1;
let playing = false;
let frame: Frame | null = null;
let lastStepMs = 0;
const stepTimes: number[] = [];

// ---------- layout ----------
function select<T extends string>(id: string, label: string, items: [T, string, ...unknown[]][], value: T): HTMLSelectElement {
  const s = el('select', { id, 'aria-label': label, title: label }, ...items.map(([v, t]) => el('option', { value: v }, t)));
  s.value = value;
  return s;
}
function button(id: string, label: string, text: string, cls = ''): HTMLButtonElement {
  return el('button', { id, 'aria-label': label, title: label, class: cls, type: 'button' }, text);
}

const benchSel = select('benchmark', 'Benchmark', BENCHMARKS, options.benchmark);
const methodSel = select('method', 'Method', METHODS, options.method);
const modeSel = select('mode', 'Multi-goal mode', MODES, options.mode);
const seedIn = el('input', { id: 'seed', type: 'number', min: '0', step: '1', 'aria-label': 'Random seed', title: 'Random seed', value: String(options.seed) });
const resetBtn = button('reset', 'Reset the episode with this seed (R)', '↺ Reset');
const playBtn = button('play', 'Play (Space)', '▶ Play', 'primary');
const stepBtn = button('step', 'Advance 0.1 s of simulated time (N)', 'Step');
const speedSel = select(
  'speed',
  'Playback speed',
  [['0.25', '¼×'], ['0.5', '½×'], ['1', '1×'], ['2', '2×'], ['4', '4×'], ['8', '8×']],
  String(speed) as string,
);
const levelBtns = LEVELS.map(([lvl, text, what]) => {
  const b = button(`inject-${lvl}`, `Inject ${text}: ${what} (${lvl[1]})`, text, 'level');
  b.dataset.level = lvl;
  return b;
});
const saveBtn = button('save-scene', 'Save the current scene as JSON', 'Save');
const loadBtn = button('load-scene', 'Load a scene JSON file', 'Load');
const fileIn = el('input', { type: 'file', accept: 'application/json,.json', hidden: '', 'aria-label': 'Scene JSON file' });
const linkBtn = button('permalink', 'Copy a link to this benchmark, method, mode and seed', 'Link');
const helpBtn = button('help', 'Keyboard shortcuts and help (?)', '?');

const statusText = el('span', { id: 'status-text', class: 'status-text' }, 'Loading the planner…');
const statusDot = el('span', { class: 'status-dot', 'aria-hidden': 'true' });
const cancelBtn = button('cancel', 'Cancel the current plan: the robot stops and replans (C)', 'Cancel');
const status = el('div', { id: 'status', class: 'status idle', role: 'status', 'aria-live': 'polite' }, statusDot, statusText, cancelBtn);
const hud = el('div', { id: 'hud', class: 'hud', 'aria-label': 'Simulation clock and timings' });
const notice = el('div', { id: 'notice', class: 'notice', role: 'alert', hidden: '' });
const stage = el('section', { class: 'stage', 'aria-label': 'Workcell' }, status, hud, notice);

const planList = el('ol', { id: 'plan', class: 'plan-list', 'aria-label': 'Current plan' });
const demoList = el('ol', { id: 'demo', class: 'demo-list', 'aria-label': 'Demonstration states and actions' });
const factsList = el('ul', { id: 'facts', class: 'facts', 'aria-label': 'Current facts' });
const factsDiff = el('div', { id: 'facts-diff', class: 'facts-diff', 'aria-live': 'polite' });
const replanInfo = el('div', { id: 'replan-info', class: 'replan-info' });
const runPanel = el(
  'div',
  { class: 'panel', id: 'panel-run', role: 'tabpanel' },
  el('h2', {}, 'Plan ', el('span', { class: 'muted', id: 'plan-count' })),
  planList,
  replanInfo,
  el('h2', {}, 'Demonstration ', el('span', { class: 'muted', id: 'matched' })),
  demoList,
  el('h2', {}, 'Facts ', el('span', { class: 'muted' }, 'S', el('sub', {}, 'C'))),
  factsDiff,
  factsList,
);
const chartsPanel = el('div', { class: 'panel', id: 'panel-charts', role: 'tabpanel', hidden: '' });
const editorHost = el('div', { class: 'panel panel-editor', id: 'panel-pddl', role: 'tabpanel', hidden: '' });
const teachSlot = el('div', { class: 'panel', id: 'panel-teach', role: 'tabpanel', hidden: '' });
const tabDefs: [string, string, HTMLElement][] = [
  ['run', 'Run', runPanel],
  ['teach', 'Teach', teachSlot],
  ['charts', 'Charts', chartsPanel],
  ['pddl', 'PDDL', editorHost],
];
const tabBtns = tabDefs.map(([id, text]) =>
  el('button', { id: `tab-${id}`, role: 'tab', class: 'tab', 'aria-controls': `panel-${id}`, 'aria-selected': 'false', type: 'button' }, text),
);
const side = el('aside', { class: 'side', 'aria-label': 'Plan, demonstration, facts, charts and PDDL' }, el('div', { class: 'side-tabs', role: 'tablist' }, ...tabBtns), ...tabDefs.map(([, , p]) => p));

const help = el(
  'div',
  { id: 'help-overlay', class: 'overlay', role: 'dialog', 'aria-modal': 'true', 'aria-label': 'Help', hidden: '' },
  el(
    'div',
    { class: 'dialog' },
    el('h2', {}, 'logic-lfd — learning a task from one demonstration'),
    el(
      'p',
      {},
      'The robot was shown the task once. It plans with PDDL to reach ',
      el('em', {}, 'any'),
      ' state seen in that demonstration, then follows the rest of it. Drag a block with the mouse while it works: it notices the change, replans in milliseconds and still finishes.',
    ),
    el(
      'table',
      { class: 'keys' },
      ...(
        [
          ['Space', 'play / pause'],
          ['N', 'step 0.1 s'],
          ['R', 'reset (same seed)'],
          ['C', 'cancel the current plan'],
          ['1 – 4', 'inject disturbance L1 – L4'],
          ['B', 'next benchmark'],
          ['+ / −', 'faster / slower'],
          ['P', 'open the PDDL editor'],
          ['?', 'this help; Esc closes it'],
          ['mouse', 'left-drag a block to move it; drag elsewhere to orbit; wheel to zoom'],
          ['G', 'Teach tab, gripper mode: close / open the gripper'],
        ] as [string, string][]
      ).map(([k, v]) => el('tr', {}, el('th', {}, el('kbd', {}, k)), el('td', {}, v))),
    ),
    el('button', { id: 'help-close', class: 'primary', type: 'button', 'aria-label': 'Close help' }, 'Close'),
  ),
);

const header = el(
  'header',
  { class: 'topbar' },
  el('div', { class: 'brand' }, el('strong', {}, 'logic-lfd'), el('span', { id: 'version', class: 'muted' })),
  el('div', { class: 'group', role: 'group', 'aria-label': 'Scenario' }, benchSel, methodSel, modeSel, el('label', { class: 'seed' }, 'seed', seedIn), resetBtn),
  el('div', { class: 'group', role: 'group', 'aria-label': 'Playback' }, playBtn, stepBtn, speedSel),
  el('div', { class: 'group', role: 'group', 'aria-label': 'Inject a disturbance' }, el('span', { class: 'muted small' }, 'inject'), ...levelBtns),
  el('div', { class: 'group right', role: 'group', 'aria-label': 'Scene and link' }, saveBtn, loadBtn, fileIn, linkBtn, helpBtn),
);

const app = document.getElementById('app')!;
app.replaceChildren(header, el('main', { class: 'layout' }, stage, side), help);

// ---------- worker, view, panels ----------
const client = new WorkerClient(onPush);
const view = new View(stage, {
  onDrop: async ({ body, position }) => {
    if (teach?.active) return teach.drop({ body, position });
    const r = await client.call('perturb', { body, position });
    if (!r.ok) return r.reason;
    showNotice(r.message || `Moved ${body}`, 'info');
    render(r.frame);
    if (!playing && autoResume) await play();
    return null;
  },
  onDragStart: () => {
    autoResume = playing;
  },
  onNotice: (t, k) => showNotice(t, k),
});
let autoResume = false;
// Teach mode (its panel, and the wasm module with the recorder in the worker) is loaded when its
// tab first opens, like the PDDL editor: the page becomes interactive sooner.
let teach: TeachPanel | null = null;
let teachPromise: Promise<TeachPanel> | null = null;
function getTeach(): Promise<TeachPanel> {
  teachPromise ??= Promise.all([import('./teach'), client.call('teachLoad', {})]).then(
    ([{ TeachPanel }]) => (teach = newTeachPanel(TeachPanel)),
    (e: unknown) => {
      teachPromise = null;
      throw e;
    },
  );
  return teachPromise;
}
const newTeachPanel = (Panel: typeof TeachPanel): TeachPanel => new Panel(teachSlot, {
  client,
  view,
  stage,
  benchmark: () => options.benchmark,
  options: () => options,
  notice: (t, k) => showNotice(t, k),
  status: (kind, text) => {
    status.className = `status ${kind}`;
    status.dataset.kind = kind;
    statusText.textContent = text;
  },
  pauseRun: async () => {
    if (playing) await pause();
  },
  runTaught: async (f, autoplay) => {
    setPlaying(false);
    charts.reset();
    view.clearTrail();
    selectTab('run');
    lastPanelKey = '';
    render(f);
    if (autoplay) await play();
  },
});
const charts = new Charts(chartsPanel);
// The PDDL editor (CodeMirror) is loaded on first use: the page becomes interactive sooner.
let editorPromise: Promise<EditorPanel> | null = null;
const search = new SearchRunner();
function getEditor(): Promise<EditorPanel> {
  editorPromise ??= import('./editor').then(({ EditorPanel, PLAN_TIME_LIMIT_MS }) => {
    // The editor's searches run in a worker of their own (terminated on cancel or timeout): a
    // pathological problem never stops the robot's worker nor freezes the page.
    const e = new EditorPanel({
      plan: (domain, problem, o) => search.call('plan', { domain, problem, options: o }, PLAN_TIME_LIMIT_MS + 5000),
      check: (domain, problem) => search.call('check', { domain, problem }, 10_000),
      cancel: () => search.cancel('cancelled'),
    });
    editorHost.append(e.root);
    return e;
  });
  return editorPromise;
}
let editorBenchmark: Benchmark | null = null;

let currentTab = 'run';
function selectTab(id: string): void {
  tabDefs.forEach(([tid, , panel], i) => {
    const on = tid === id;
    panel.hidden = !on;
    tabBtns[i].classList.toggle('active', on);
    tabBtns[i].setAttribute('aria-selected', String(on));
  });
  currentTab = id;
  if (id === 'teach') {
    getTeach().then(
      (t) => t.setVisible(currentTab === 'teach'),
      (e: unknown) => showNotice(`could not load Teach mode: ${(e as Error).message}`, 'error'),
    );
  } else teach?.setVisible(false);
  if (id !== 'teach' && frame && !pendingFrame) {
    lastPanelKey = '';
    render(frame);
  }
  if (id === 'pddl') void loadEditor();
  if (id === 'charts') charts.draw();
}
tabBtns.forEach((b, i) => (b.onclick = () => selectTab(tabDefs[i][0])));
selectTab('run');

async function loadEditor(): Promise<void> {
  if (editorBenchmark === options.benchmark) return;
  editorBenchmark = options.benchmark;
  const [editor, b] = await Promise.all([getEditor(), client.call('benchmark', { id: options.benchmark })]);
  editor.setTexts(b.domain, b.problem);
}

let noticeTimer = 0;
function showNotice(text: string, kind: 'info' | 'error'): void {
  notice.textContent = text;
  notice.className = `notice ${kind}`;
  notice.hidden = false;
  clearTimeout(noticeTimer);
  noticeTimer = window.setTimeout(() => (notice.hidden = true), kind === 'error' ? 6000 : 3500);
}

function onPush(m: FromWorker): void {
  if (m.type === 'fatal') {
    setPlaying(false);
    status.className = 'status failed';
    statusText.textContent = m.message;
    return;
  }
  if (m.type !== 'frame' || teach?.active) return;
  lastStepMs = m.timing.stepMs;
  stepTimes.push(m.timing.stepMs);
  if (stepTimes.length > 600) stepTimes.shift();
  render(m.frame);
  if (!m.playing && playing) setPlaying(false);
}

// ---------- rendering a frame ----------
let pendingFrame: Frame | null = null;
function render(f: Frame): void {
  frame = f;
  charts.push(f);
  if (pendingFrame === null) requestAnimationFrame(flush);
  pendingFrame = f;
}

function flush(): void {
  const f = pendingFrame;
  pendingFrame = null;
  if (!f) return;
  view.update(f.world, f.ee);
  if (!chartsPanel.hidden) charts.draw();
  renderStatus(f);
  renderPanels(f);
}

let lastPanelKey = '';
function renderStatus(f: Frame): void {
  const k = f.status.kind;
  status.className = `status ${k}`;
  status.dataset.kind = k;
  statusText.textContent = f.status.message || k;
  cancelBtn.disabled = !(k === 'planning' || k === 'executing' || k === 'replanning');
  const mean = stepTimes.length ? stepTimes.reduce((a, b) => a + b, 0) / stepTimes.length : 0;
  hud.textContent = `t = ${f.t.toFixed(2)} s · tick ${f.tick} · step ${lastStepMs.toFixed(2)} ms (mean ${mean.toFixed(2)}) · ${f.replans} replans`;
}

function renderPanels(f: Frame): void {
  const key = JSON.stringify([f.plan, f.executing, f.demo.length, f.matched_k, f.facts, f.last_replan?.tick]);
  if (key === lastPanelKey) return;
  lastPanelKey = key;
  document.getElementById('plan-count')!.textContent = f.plan.length ? `${f.plan.length} actions` : '';
  planList.replaceChildren(
    ...f.plan.map((a, i) => {
      const cls = f.executing === i ? 'current' : f.executing != null && i < f.executing ? 'done' : '';
      return el('li', { class: cls, 'aria-current': f.executing === i ? 'step' : 'false' }, a);
    }),
  );
  if (!f.plan.length) planList.append(el('li', { class: 'muted empty' }, 'no plan yet'));
  planList.querySelector('.current')?.scrollIntoView({ block: 'nearest' });

  const k = f.matched_k ?? null;
  document.getElementById('matched')!.textContent = k == null ? '' : `joined at L${k}`;
  const demoItems: HTMLElement[] = [];
  f.demo_states.forEach((_, i) => {
    demoItems.push(el('li', { class: `demo-state${k === i ? ' matched' : ''}`, title: f.demo_states[i].join(' ') }, `L${i}`, el('span', { class: 'muted' }, ` · ${f.demo_states[i].length} facts`)));
    if (i < f.demo.length) demoItems.push(el('li', { class: `demo-action${k != null && i >= k ? ' ahead' : ''}` }, `a${i + 1} ${f.demo[i]}`));
  });
  demoList.replaceChildren(...demoItems);

  const added = new Set(f.facts_added);
  factsList.replaceChildren(...f.facts.map((x) => el('li', { class: added.has(x) ? 'added' : '' }, x)));
  factsDiff.replaceChildren(
    ...f.facts_added.map((x) => el('span', { class: 'chip added' }, `+ ${x}`)),
    ...f.facts_removed.map((x) => el('span', { class: 'chip removed' }, `− ${x}`)),
  );
  const r = f.last_replan;
  replanInfo.textContent = r
    ? `Last replan at tick ${r.tick}: ${r.reason} — ${r.time_ms.toFixed(2)} ms${r.k != null ? `, joined the demo at L${r.k}` : ''}`
    : '';
}

// ---------- actions ----------
/** Runs an action; a rejected call (no session, a refused request) becomes a notice, not an error. */
function guard(f: () => unknown): void {
  Promise.resolve()
    .then(f)
    .catch((e: unknown) => showNotice(e instanceof Error ? e.message : String(e), 'error'));
}

function setPlaying(p: boolean): void {
  playing = p;
  playBtn.textContent = p ? '❚❚ Pause' : '▶ Play';
  playBtn.setAttribute('aria-label', p ? 'Pause (Space)' : 'Play (Space)');
  playBtn.setAttribute('aria-pressed', String(p));
}

async function play(): Promise<void> {
  if (frame && (frame.status.kind === 'done' || frame.status.kind === 'failed')) return;
  setPlaying(true);
  await client.call('play', { speed });
}

async function pause(): Promise<void> {
  setPlaying(false);
  const f = await client.call('pause', {});
  if (f) render(f);
}

function updateUrl(): void {
  const p = new URLSearchParams();
  p.set('benchmark', options.benchmark);
  p.set('method', options.method);
  p.set('mode', options.mode);
  p.set('seed', String(options.seed));
  if (speed !== 1) p.set('speed', String(speed));
  history.replaceState(null, '', `${location.pathname}?${p}`);
}

async function open(scene?: string): Promise<void> {
  setPlaying(false);
  updateUrl();
  statusText.textContent = 'Loading the benchmark…';
  try {
    const f = await client.call('open', { options: { ...options }, scene });
    charts.reset();
    view.clearTrail();
    lastPanelKey = '';
    render(f);
    if (editorBenchmark !== options.benchmark && !editorHost.hidden) void loadEditor();
    if (params.get('autoplay') !== '0') await play();
  } catch (e) {
    // Still show the benchmark's scene, and say why nothing moves.
    try {
      view.update((await client.call('benchmark', { id: options.benchmark })).scene);
    } catch {
      /* the message below says enough */
    }
    status.className = 'status failed';
    statusText.textContent = `Could not start the session: ${(e as Error).message}`;
  }
}

async function reset(): Promise<void> {
  setPlaying(false);
  charts.reset();
  view.clearTrail();
  render(await client.call('reset', { seed: options.seed }));
  if (params.get('autoplay') !== '0') await play();
}

const withoutLevel = (level: Level, m: string) => m.replace(new RegExp(`^${level}:\\s*`, 'i'), '');
const withLevel = (level: Level, m: string) => `${level.toUpperCase()}: ${withoutLevel(level, m)}`;

async function inject(level: Level): Promise<void> {
  try {
    const r = await client.call('inject', { level });
    showNotice(withLevel(level, r.message), 'info');
    render(r.frame);
    if (!playing) await play();
  } catch (e) {
    showNotice(`${level.toUpperCase()} refused: ${withoutLevel(level, (e as Error).message)}`, 'error');
  }
}

benchSel.onchange = () => {
  options.benchmark = benchSel.value as Benchmark;
  teach?.reset();
  void open();
};
methodSel.onchange = () => {
  options.method = methodSel.value as Method;
  void open();
};
modeSel.onchange = () => {
  options.mode = modeSel.value as Mode;
  void open();
};
seedIn.onchange = () => {
  options.seed = Math.max(0, Math.floor(Number(seedIn.value)) || 0);
  seedIn.value = String(options.seed);
  updateUrl();
  guard(reset);
};
resetBtn.onclick = () => guard(reset);
playBtn.onclick = () => guard(() => (playing ? pause() : play()));
stepBtn.onclick = () =>
  guard(async () => {
    setPlaying(false);
    render(await client.call('step', { dt: 0.1 }));
  });
speedSel.onchange = () => {
  speed = Number(speedSel.value);
  updateUrl();
  guard(() => client.call('speed', { speed }));
};
levelBtns.forEach((b) => (b.onclick = () => void inject(b.dataset.level as Level)));
/** Times of the last cancel (ms since the epoch, `performance.timeOrigin` based), for the tests. */
let lastCancel: { clickedAt: number; appliedAt: number; repliedAt: number } | null = null;
cancelBtn.onclick = () =>
  guard(async () => {
    const clickedAt = performance.timeOrigin + performance.now();
    const r = await client.call('cancel', {});
    render(r.frame);
    lastCancel = { clickedAt, appliedAt: r.appliedAt, repliedAt: performance.timeOrigin + performance.now() };
  });
saveBtn.onclick = () => guard(save);
async function save(): Promise<void> {
  const json = await client.call('scene', {});
  const a = el('a', { href: URL.createObjectURL(new Blob([json], { type: 'application/json' })), download: `${options.benchmark}-scene.json` });
  a.click();
  URL.revokeObjectURL(a.href);
}
loadBtn.onclick = () => fileIn.click();
fileIn.onchange = () =>
  guard(async () => {
    const file = fileIn.files?.[0];
    if (!file) return;
    await open(await file.text());
    fileIn.value = '';
  });
linkBtn.onclick = async () => {
  updateUrl();
  try {
    await navigator.clipboard.writeText(location.href);
    showNotice('Link copied: it restores this benchmark, method, mode and seed', 'info');
  } catch {
    showNotice(location.href, 'info');
  }
};
const openHelp = () => {
  help.hidden = false;
  (document.getElementById('help-close') as HTMLButtonElement).focus();
};
const closeHelp = () => {
  help.hidden = true;
  helpBtn.focus();
};
helpBtn.onclick = openHelp;
document.getElementById('help-close')!.onclick = closeHelp;
help.onclick = (e) => {
  if (e.target === help) closeHelp();
};

document.addEventListener('keydown', (e) => {
  const t = e.target as HTMLElement;
  if (t.closest('.cm-editor') || t instanceof HTMLInputElement || t instanceof HTMLSelectElement) return;
  if (e.ctrlKey || e.metaKey || e.altKey) return;
  if (e.key === 'Escape' && !help.hidden) return closeHelp();
  if (!help.hidden) return;
  const k = e.key.toLowerCase();
  // While Teach mode owns the view, the run's keys would act on the hidden episode.
  if (teach?.active && ' nrc1234'.includes(k)) return;
  const act: Record<string, () => void> = {
    ' ': () => guard(() => (playing ? pause() : play())),
    n: () => stepBtn.click(),
    r: () => guard(reset),
    c: () => cancelBtn.click(),
    '1': () => void inject('l1'),
    '2': () => void inject('l2'),
    '3': () => void inject('l3'),
    '4': () => void inject('l4'),
    b: () => {
      const i = BENCHMARKS.findIndex(([b]) => b === options.benchmark);
      benchSel.value = BENCHMARKS[(i + 1) % BENCHMARKS.length][0];
      benchSel.dispatchEvent(new Event('change'));
    },
    '+': () => stepSpeed(1),
    '=': () => stepSpeed(1),
    '-': () => stepSpeed(-1),
    p: () => selectTab('pddl'),
    '?': openHelp,
  };
  const f = act[k];
  if (f) {
    e.preventDefault();
    f();
  }
});

function stepSpeed(d: number): void {
  const opts = [...speedSel.options].map((o) => o.value);
  const i = Math.max(0, Math.min(opts.length - 1, opts.indexOf(speedSel.value) + d));
  speedSel.value = opts[i];
  speedSel.dispatchEvent(new Event('change'));
}

// Hooks for the browser tests and the benchmark script (read-only views of the page's state).
declare global {
  interface Window {
    lfd: {
      frame: () => Frame | null;
      screenPosition: (body: string) => { x: number; y: number } | null;
      project: (p: [number, number, number]) => { x: number; y: number };
      stepTimes: () => number[];
      replans: () => [number, number][];
      setPddl: (domain: string, problem: string) => Promise<void>;
      renderMs: () => number;
      lastCancel: () => { clickedAt: number; appliedAt: number; repliedAt: number } | null;
      memory: () => Promise<{ wasmBytes: number; geometries: number; textures: number }>;
      loadedAt: number;
    };
  }
}
window.lfd = {
  frame: () => frame,
  screenPosition: (b) => view.screenPosition(b),
  project: (p) => view.project(p),
  stepTimes: () => [...stepTimes],
  replans: () => charts.replans(),
  setPddl: async (domain, problem) => {
    editorBenchmark = options.benchmark;
    selectTab('pddl');
    (await getEditor()).setTexts(domain, problem);
  },
  renderMs: () => view.renderMs,
  lastCancel: () => lastCancel,
  memory: async () => ({ ...(await client.call('memory', {})), ...view.renderer.info.memory }),
  loadedAt: 0,
};

client.ready.then(
  async (v) => {
    document.getElementById('version')!.textContent = `v${v}`;
    view.start();
    await open();
    window.lfd.loadedAt = performance.now();
    app.dataset.ready = 'true';
  },
  (e: Error) => {
    status.className = 'status failed';
    statusText.textContent = e.message;
  },
);
