/**
 * `window.lfd`: read-only views of the page's state for the browser tests and the benchmark script
 * (the current frame, where a body is on screen, step and render timings, replans, the last
 * cancel, memory, the move onto the full-speed module), and a way to put PDDL into the editor.
 */
import type { Frame } from 'logic-lfd';
import type { Charts } from './charts';
import type { WorkerClient } from './client';
import type { History, Mark } from './history';
import type { SpeedUpState } from './speed-up';
import type { CancelTiming, PageState } from './state';
import type { Tabs } from './tabs';
import type { View } from './view';
import type { ArmMeshInfo, ArmStyle } from './view-arms';

declare global {
  interface Window {
    lfd: {
      frame: () => Frame | null;
      screenPosition: (body: string) => { x: number; y: number } | null;
      project: (p: [number, number, number]) => { x: number; y: number };
      stepTimes: () => number[];
      replans: () => [number, number][];
      setPddl: (domain: string, problem: string, demo?: string) => Promise<void>;
      renderMs: () => number;
      lastCancel: () => CancelTiming | null;
      memory: () => Promise<{ wasmBytes: number; freshBytes: number; geometries: number; textures: number }>;
      loadedAt: number;
      /** Bodies whose disturbance move is marked in the view now. */
      moveMarks: () => string[];
      /** The disturbance and replan markers of the episode (the timeline's and the charts'). */
      marks: () => Mark[];
      /** The markers each chart drew last: [replanning chart, trajectory chart]. */
      chartMarks: () => [Mark[], Mark[]];
      /** The simulated time the view shows when scrubbed back (null: live), and the latest. */
      viewing: () => { t: number | null; end: number };
      /** Where the 3-D view draws `body` now (world coordinates). */
      bodyPosition: (body: string) => [number, number, number] | null;
      /** Whether the worker's session runs on the full-speed module yet (speed-up.ts). */
      speedUp: () => Promise<SpeedUpState>;
      /** What the rewound panels' record holds (rewind.ts, once loaded): Moments, those with a
       * record, the distinct snapshots and plan lists they share, replans kept with their plans. */
      rewind?: () => { moments: number; recorded: number; snapshots: number; plans: number; replans: number };
      /** How the arms are drawn, whether the robot's meshes are loaded, and where they are drawn. */
      armMeshes: () => { style: ArmStyle; loaded: boolean; arms: (ArmMeshInfo | null)[] };
    };
  }
}

export function installTestHooks(p: { state: PageState; view: View; charts: Charts; history: History; tabs: Tabs; client: WorkerClient }): void {
  const { state, view, charts, history, tabs, client } = p;
  window.lfd = {
    frame: () => state.frame,
    screenPosition: (b) => view.screenPosition(b),
    project: (pt) => view.project(pt),
    stepTimes: () => [...state.stepTimes],
    replans: () => charts.replans(),
    setPddl: (domain, problem, demo) => tabs.setPddl(domain, problem, demo),
    renderMs: () => view.renderMs,
    lastCancel: () => state.lastCancel,
    memory: async () => ({ ...(await client.call('memory', {})), ...view.renderer.info.memory }),
    loadedAt: 0,
    moveMarks: () => view.moveMarks(),
    marks: () => history.marks.map((m) => ({ ...m })),
    chartMarks: () => charts.drawnMarks(),
    viewing: () => ({ t: history.viewing, end: history.end }),
    bodyPosition: (b) => view.bodyPosition(b),
    speedUp: () => client.call('speedUpState', {}),
    armMeshes: () => view.armMeshes(),
  };
}
