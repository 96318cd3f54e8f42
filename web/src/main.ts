/**
 * The page's entry: builds the layout from the state in the URL, starts the worker that owns the
 * wasm session (client.ts ↔ worker.ts through protocol.ts), and wires the 3-D view, the panels,
 * the controls and the keyboard together; then opens the chosen benchmark.
 */
import './style.css';
import { Charts } from './charts';
import { WorkerClient } from './client';
import { FrameRenderer } from './frame-renderer';
import { History } from './history';
import { setCatalogue } from './catalogue';
import { buildLayout, setBlockChoices, setCatalogueChoices } from './layout';
import { RunPanel } from './run-panel';
import { SessionControls } from './session-controls';
import { installShortcuts } from './shortcuts';
import { blocksFor, initialState, setBlockRanges, settleChoices } from './state';
import { StatusBar } from './status-bar';
import { Tabs } from './tabs';
import { View } from './view';

const state = initialState(location.search);
const ui = buildLayout(state);
const status = new StatusBar(ui.stage);
const history = new History();

// Every part below is made before the first event can reach it; the closures only forward.
const client = new WorkerClient((m) => session.onPush(m));
const view = new View(ui.stage.root, {
  onDrop: (d) => session.drop(d),
  onDragStart: () => void session.guard(() => session.dragStart()),
  onDragEnd: () => void session.guard(() => session.dragEnd()),
  onNotice: (t, k) => status.notice(t, k),
  dragRefusal: () => (history.viewing === null ? null : 'Viewing an earlier moment: press Play to return to live, then drag the block.'),
});
const charts = new Charts(ui.chartsPanel, history);
const run = new RunPanel(ui.run, () => state.options.mode);
const renderer = new FrameRenderer(state, { view, charts, history, chartsPanel: ui.chartsPanel, status, run });
const session: SessionControls = new SessionControls({ state, ui, client, view, renderer, history, status, tabs: () => tabs });
const tabs = new Tabs({ state, ui, client, view, charts, renderer, status, playback: session });
session.wire();
renderer.onFrame = (f) => session.refreshLevels(f);
installShortcuts({ help: ui.help, session, tabs, controls: ui.controls, stage: ui.stage });
/** `window.lfd` for the tests and bench scripts: not needed for the first frame, so fetched after it. */
const testHooks = () => import('./test-hooks').then(({ installTestHooks }) => installTestHooks({ state, view, charts, history, tabs, client }));
if (location.hash.startsWith('#pddl=')) void import('./pddl-link').then((m) => m.restore((d, p, x) => tabs.setPddl(d, p, x)));

// The view follows the timeline: a recorded moment while scrubbed back, the live frame after.
let shown: number | null = null;
history.listen(() => {
  if (history.viewing === shown) return;
  shown = history.viewing;
  const m = shown === null ? state.frame : history.at(shown);
  if (m) view.update(m.world, m.ee, shown === null);
});

client.ready.then(
  async ({ version, blockRanges, catalogue }) => {
    ui.version.textContent = `v${version}`;
    ui.version.parentElement!.title = `logic-lfd v${version}`;
    // The choices and the block counts come from the wasm module: check the URL's against them.
    setCatalogue(catalogue);
    settleChoices(state, catalogue);
    setCatalogueChoices(ui.controls, catalogue, state.options);
    setBlockRanges(blockRanges);
    const blocks = blocksFor(state.options.benchmark, state.options.blocks);
    if (blocks === undefined) delete state.options.blocks;
    setBlockChoices(ui.controls.blocksSel, state.options.benchmark, blocks);
    view.start();
    if (state.folderUrl) await session.openFolderAt(state.folderUrl);
    else await session.open();
    const loadedAt = performance.now();
    await testHooks();
    window.lfd.loadedAt = loadedAt;
    ui.app.dataset.ready = 'true';
    // The first frame is drawn: the worker now fetches the full-speed module and moves onto it.
    void client.call('speedUp', {});
    // Not needed for the first frame: fetched once the page is interactive.
    void import('./explain').then(({ explainSelects }) => explainSelects(ui.controls.methodSel, ui.controls.modeSel, catalogue));
    view.loadExtras();
    void import('./rewind').then(({ Rewind }) => new Rewind({ history, state, ui, status, run }));
    void import('./timeline').then(
      ({ Timeline }) => new Timeline(ui.stage.root, { history, pause: () => void session.guard(() => session.pause()), togglePlay: () => void session.togglePlay() }),
    );
    void import('./hint').then(({ FirstVisitHint }) => session.setHint(new FirstVisitHint(ui.stage.root)));
  },
  (e: Error) => {
    status.fail(e.message);
    void testHooks();
  },
);
