/**
 * Shows the session's frames: every frame becomes the page's current one and feeds the charts;
 * at most once per animation frame the latest is drawn in the 3-D view, the charts (when shown),
 * the status line and the Run tab.
 */
import type { Frame } from 'logic-lfd';
import type { Charts } from './charts';
import type { History } from './history';
import type { RunPanel } from './run-panel';
import type { PageState } from './state';
import type { StatusBar } from './status-bar';
import type { View } from './view';

export class FrameRenderer {
  private pendingFrame: Frame | null = null;

  constructor(
    private readonly state: PageState,
    private readonly parts: { view: View; charts: Charts; history: History; chartsPanel: HTMLElement; status: StatusBar; run: RunPanel },
  ) {}

  /** Whether a frame waits to be drawn. */
  get pending(): boolean {
    return this.pendingFrame !== null;
  }

  /** Called with every frame (the L1–L4 buttons follow it). */
  onFrame: (f: Frame) => void = () => {};

  render(f: Frame): void {
    this.state.frame = f;
    this.onFrame(f);
    this.parts.history.push(f);
    this.parts.charts.push(f);
    this.parts.run.record(f);
    if (this.pendingFrame === null) requestAnimationFrame(() => this.flush());
    this.pendingFrame = f;
  }

  /** Empties the charts, the end-effector trail and the step timings (a new episode begins). */
  clearHistory(): void {
    // The step timings are the episode's too: a long search in the last one must not skew the mean.
    this.state.stepTimes = [];
    this.state.lastStepMs = 0;
    this.parts.history.reset();
    this.parts.charts.reset();
    this.parts.view.clearTrail();
  }

  /** Renders `f` as the first frame of a new episode: empty charts and trail, lists redrawn. */
  restart(f: Frame): void {
    this.clearHistory();
    this.parts.run.restart();
    this.render(f);
  }

  /** Draws the current frame again in full (the Run tab was hidden meanwhile). */
  redraw(): void {
    if (!this.state.frame || this.pendingFrame) return;
    this.parts.run.invalidate();
    this.render(this.state.frame);
  }

  private flush(): void {
    const f = this.pendingFrame;
    this.pendingFrame = null;
    if (!f) return;
    const { view, charts, chartsPanel, status, run, history } = this.parts;
    if (!chartsPanel.hidden) charts.draw();
    // Scrubbed back: the view and the panels keep the past moment until Play returns to live.
    if (history.viewing !== null) return;
    view.update(f.world, f.ee);
    status.showFrame(f, this.state);
    run.show(f);
  }
}
