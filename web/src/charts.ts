/**
 * Two small uPlot charts: the time of each replan (ms) and the end-effector trajectory (m), both
 * with the history's disturbance and replan markers as vertical lines (the timeline's colours).
 * The data is recorded from the first frame; uPlot itself (and its CSS) is loaded on the first
 * draw, i.e. when the Charts tab is opened, so it is not part of the page's first load.
 */
import type uPlot from 'uplot';
import type { Frame } from 'logic-lfd';
import { MARK_COLOURS, type History, type Mark } from './history';

type UPlot = typeof uPlot;
let uPlotModule: Promise<UPlot> | null = null;
function loadUPlot(): Promise<UPlot> {
  uPlotModule ??= Promise.all([import('uplot'), import('uplot/dist/uPlot.min.css')]).then(([m]) => m.default);
  return uPlotModule;
}

/** The charts redraw at most this often (ms): drawing 3 000 points per series on a 2-D canvas at
 * 60 Hz costs more than the whole 3-D view on a machine without a GPU. */
const REDRAW_MS = 100;

const axis = { stroke: '#8b949e', grid: { stroke: '#21262d', width: 1 }, ticks: { stroke: '#30363d', width: 1 } };

/** A y range with room above and below, so the highest and lowest points are drawn whole. */
function padded(_u: uPlot, min: number, max: number): [number, number] {
  // A single value (one replan) still gets a readable scale around it.
  const pad = Math.max((max - min) * 0.08, Math.abs(max) * 0.05, 1e-3);
  return [min - pad, max + pad];
}

/** Draws the markers as vertical lines: disturbances solid, replans dashed and fainter. */
function drawMarks(u: uPlot, marks: readonly Mark[], drawn: Mark[]): void {
  const { ctx, bbox } = u;
  ctx.save();
  ctx.beginPath();
  ctx.rect(bbox.left, bbox.top, bbox.width, bbox.height);
  ctx.clip();
  for (const m of marks) {
    const x = u.valToPos(m.t, 'x', true);
    if (!Number.isFinite(x) || x < bbox.left || x > bbox.left + bbox.width) continue;
    const replan = m.kind === 'replan';
    ctx.strokeStyle = MARK_COLOURS[m.kind];
    ctx.globalAlpha = replan ? 0.55 : 0.95;
    ctx.lineWidth = (replan ? 1 : 2) * devicePixelRatio;
    ctx.setLineDash(replan ? [4 * devicePixelRatio, 4 * devicePixelRatio] : []);
    ctx.beginPath();
    ctx.moveTo(x, bbox.top);
    ctx.lineTo(x, bbox.top + bbox.height);
    ctx.stroke();
    drawn.push(m);
  }
  ctx.restore();
}

/** `xRange`: both charts share one time axis, from 0 to the latest data (a margin keeps the last
 * point inside). */
function chart(
  UPlot: UPlot,
  host: HTMLElement,
  title: string,
  labels: [string, string],
  series: uPlot.Series[],
  xRange: () => [number, number],
  marks: () => readonly Mark[],
  drawn: Mark[],
): uPlot {
  const data = [[], ...series.slice(1).map(() => [])] as unknown as uPlot.AlignedData;
  return new UPlot(
    {
      title,
      width: Math.max(200, host.clientWidth),
      height: 170,
      cursor: { drag: { x: false, y: false }, points: { size: 8 } },
      // Hovering shows the values under the cursor.
      legend: { live: true },
      scales: { x: { time: false, range: xRange }, y: { range: padded } },
      hooks: {
        draw: [
          (u) => {
            drawn.length = 0;
            drawMarks(u, marks(), drawn);
          },
        ],
      },
      axes: [
        { ...axis, label: labels[0], size: 36 },
        { ...axis, label: labels[1], size: 48 },
      ],
      series,
    },
    data,
    host,
  );
}

export class Charts {
  readonly root: HTMLElement;
  private replanChart: uPlot | null = null;
  private eeChart: uPlot | null = null;
  private loading = false;
  private readonly hosts: [HTMLElement, HTMLElement];
  private ee: number[][] = [[], [], [], [], [], [], []];
  private lastT = -1;
  private marksSeen = 0;
  private dirty = false;
  private lastDraw = -Infinity;
  private redrawTimer = 0;
  /** The markers each chart drew last (for the tests). */
  private readonly drawn: [Mark[], Mark[]] = [[], []];

  constructor(
    root: HTMLElement,
    private readonly history: History,
  ) {
    this.root = root;
    const a = document.createElement('div');
    const b = document.createElement('div');
    a.className = b.className = 'chart';
    a.id = 'chart-replan';
    b.id = 'chart-ee';
    a.setAttribute('aria-label', 'Replanning time per replan, milliseconds');
    b.setAttribute('aria-label', 'End-effector position and target of the first arm over time');
    root.append(a, b);
    this.hosts = [a, b];
    history.listen(() => {
      const n = history.marks.length;
      if (n !== this.marksSeen) {
        this.marksSeen = n;
        this.dirty = true;
      }
    });
  }

  private get replanMarks(): Mark[] {
    return this.history.marks.filter((m) => m.kind === 'replan');
  }

  /** Loads uPlot and makes the two charts (once). */
  private async create(): Promise<void> {
    const UPlot = await loadUPlot();
    const [a, b] = this.hosts;
    // Both charts run to the latest time seen, markers and replans included.
    const range = (): [number, number] => {
      const marks = this.history.marks;
      const end = Math.max(this.lastT, this.history.end, marks[marks.length - 1]?.t ?? 0, 1);
      // A margin at both ends: the first and the last point are drawn whole.
      return [-end * 0.015, end * 1.03];
    };
    const marks = () => this.history.marks;
    this.replanChart = chart(
      UPlot,
      a,
      'Replanning time',
      ['simulated time (s)', 'ms'],
      [
        {},
        {
          label: 'replan (ms)',
          stroke: MARK_COLOURS.replan,
          width: 0,
          paths: () => null,
          points: { show: true, size: 8, fill: MARK_COLOURS.replan },
          value: (_u, v, _s, i) => (v == null || i == null ? '–' : `${v.toFixed(2)} ms: ${this.replanMarks[i]?.text ?? ''}`),
        },
      ],
      range,
      marks,
      this.drawn[0],
    );
    // The targets (dashed) in lighter tints of the position colours, as wide as the positions.
    this.eeChart = chart(
      UPlot,
      b,
      'End-effector trajectory (arm 1)',
      ['simulated time (s)', 'm'],
      [
        {},
        { label: 'x', stroke: '#e5484d', width: 1.5 },
        { label: 'y', stroke: '#46a758', width: 1.5 },
        { label: 'z', stroke: '#3e63dd', width: 1.5 },
        { label: 'x*', stroke: '#ffb3b5', width: 2, dash: [7, 4] },
        { label: 'y*', stroke: '#b4f0bf', width: 2, dash: [7, 4] },
        { label: 'z*', stroke: '#b8c8ff', width: 2, dash: [7, 4] },
      ],
      range,
      marks,
      this.drawn[1],
    );
    new ResizeObserver(() => this.resize()).observe(this.root);
    this.dirty = true;
    this.draw();
  }

  private resize(): void {
    const w = Math.max(200, this.root.clientWidth - 8);
    this.replanChart?.setSize({ width: w, height: 170 });
    this.eeChart?.setSize({ width: w, height: 190 });
  }

  reset(): void {
    this.ee = [[], [], [], [], [], [], []];
    this.lastT = -1;
    this.marksSeen = 0;
    this.replanChart?.setData([[], []]);
    this.eeChart?.setData(this.ee as uPlot.AlignedData);
  }

  push(f: Frame): void {
    if (f.t < this.lastT) this.reset();
    const p = f.ee.find((e) => e.arm === 0);
    if (p && f.t > this.lastT + 0.02) {
      this.lastT = f.t;
      const cols = [f.t, ...p.pos, ...p.target];
      cols.forEach((v, i) => this.ee[i].push(v));
      if (this.ee[0].length > 3000) for (const c of this.ee) c.shift();
      this.dirty = true;
    }
  }

  /** Redraws when new data arrived (called at most once per animation frame by the page). */
  draw(): void {
    if (!this.replanChart || !this.eeChart) {
      if (!this.loading) {
        this.loading = true;
        this.create().catch((e: unknown) => {
          this.loading = false;
          this.root.append(`Could not load the charts: ${e instanceof Error ? e.message : String(e)}`);
        });
      }
      return;
    }
    if (!this.dirty) return;
    const wait = this.lastDraw + REDRAW_MS - performance.now();
    if (wait > 0) {
      // Draw the latest data when the interval is over, even if no frame comes by then.
      this.redrawTimer ||= window.setTimeout(() => {
        this.redrawTimer = 0;
        if (!this.root.hidden) this.draw();
      }, wait);
      return;
    }
    this.lastDraw = performance.now();
    this.dirty = false;
    const r = this.replanMarks;
    this.replanChart.setData([r.map((m) => m.t), r.map((m) => m.ms ?? 0)]);
    this.eeChart.setData(this.ee as uPlot.AlignedData);
  }

  /** Replans recorded so far, [time (s), ms]. */
  replans(): [number, number][] {
    return this.replanMarks.map((m) => [m.t, m.ms ?? 0]);
  }

  /** The markers each chart drew last, [replanning chart, trajectory chart]. */
  drawnMarks(): [Mark[], Mark[]] {
    return [[...this.drawn[0]], [...this.drawn[1]]];
  }
}
