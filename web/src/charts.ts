/**
 * Two small uPlot charts: the time of each replan (ms) and the end-effector trajectory (m).
 * The data is recorded from the first frame; uPlot itself (and its CSS) is loaded on the first
 * draw, i.e. when the Charts tab is opened, so it is not part of the page's first load.
 */
import type uPlot from 'uplot';
import type { Frame } from 'logic-lfd';

type UPlot = typeof uPlot;
let uPlotModule: Promise<UPlot> | null = null;
function loadUPlot(): Promise<UPlot> {
  uPlotModule ??= Promise.all([import('uplot'), import('uplot/dist/uPlot.min.css')]).then(([m]) => m.default);
  return uPlotModule;
}

/** Replans kept for the chart (oldest dropped first). */
const MAX_REPLANS = 2000;
/** The charts redraw at most this often (ms): drawing 3 000 points per series on a 2-D canvas at
 * 60 Hz costs more than the whole 3-D view on a machine without a GPU. */
const REDRAW_MS = 100;

const axis = { stroke: '#8b949e', grid: { stroke: '#21262d', width: 1 }, ticks: { stroke: '#30363d', width: 1 } };

/** `xRange`: both charts share one time axis, from 0 to the latest data (a margin keeps the last
 * point inside). */
function chart(UPlot: UPlot, host: HTMLElement, title: string, xLabel: string, yLabel: string, series: uPlot.Series[], xRange: () => [number, number]): uPlot {
  const data = [[], ...series.slice(1).map(() => [])] as unknown as uPlot.AlignedData;
  return new UPlot(
    {
      title,
      width: Math.max(200, host.clientWidth),
      height: 170,
      cursor: { drag: { x: false, y: false } },
      // Hovering shows the values under the cursor.
      legend: { live: true },
      scales: { x: { time: false, range: xRange } },
      axes: [
        { ...axis, label: xLabel, size: 36 },
        { ...axis, label: yLabel, size: 48 },
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
  private replanX: number[] = [];
  private replanY: number[] = [];
  /** Why each replan happened (the hover shows it). */
  private replanWhy: string[] = [];
  private lastReplanKey = '';
  private ee: number[][] = [[], [], [], [], [], [], []];
  private lastT = -1;
  private dirty = false;
  private lastDraw = -Infinity;
  private redrawTimer = 0;

  constructor(root: HTMLElement) {
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
  }

  /** Loads uPlot and makes the two charts (once). */
  private async create(): Promise<void> {
    const UPlot = await loadUPlot();
    const [a, b] = this.hosts;
    const range = (): [number, number] => {
      const end = Math.max(this.lastT, this.replanX[this.replanX.length - 1] ?? 0, 1);
      return [0, end * 1.03];
    };
    this.replanChart = chart(UPlot, a, 'Replanning time', 'simulated time (s)', 'ms', [
      {},
      {
        label: 'replan (ms)',
        stroke: '#ffb224',
        width: 0,
        paths: () => null,
        points: { show: true, size: 7, fill: '#ffb224' },
        value: (_u, v, _s, i) => (v == null || i == null ? '–' : `${v.toFixed(2)} ms: ${this.replanWhy[i] ?? ''}`),
      },
    ], range);
    this.eeChart = chart(UPlot, b, 'End-effector trajectory (arm 1)', 'simulated time (s)', 'm', [
      {},
      { label: 'x', stroke: '#e5484d', width: 1.5 },
      { label: 'y', stroke: '#46a758', width: 1.5 },
      { label: 'z', stroke: '#3e63dd', width: 1.5 },
      { label: 'x*', stroke: '#ff8a8d', width: 1.5, dash: [5, 4] },
      { label: 'y*', stroke: '#8fd99c', width: 1.5, dash: [5, 4] },
      { label: 'z*', stroke: '#8fa8ff', width: 1.5, dash: [5, 4] },
    ], range);
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
    this.replanX = [];
    this.replanY = [];
    this.replanWhy = [];
    this.lastReplanKey = '';
    this.ee = [[], [], [], [], [], [], []];
    this.lastT = -1;
    this.replanChart?.setData([[], []]);
    this.eeChart?.setData(this.ee as uPlot.AlignedData);
  }

  push(f: Frame): void {
    if (f.t < this.lastT) this.reset();
    const r = f.lastReplan;
    if (r) {
      const key = `${r.tick}:${r.reason}`;
      if (key !== this.lastReplanKey) {
        this.lastReplanKey = key;
        this.replanX.push(r.tick * (f.world.dt || 0.01));
        this.replanY.push(r.timeMs);
        this.replanWhy.push(r.reason);
        if (this.replanX.length > MAX_REPLANS) {
          this.replanX.shift();
          this.replanY.shift();
          this.replanWhy.shift();
        }
        this.dirty = true;
      }
    }
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
    this.replanChart.setData([this.replanX, this.replanY]);
    this.eeChart.setData(this.ee as uPlot.AlignedData);
  }

  /** Replans recorded so far, [time (s), ms]. */
  replans(): [number, number][] {
    return this.replanX.map((x, i) => [x, this.replanY[i]]);
  }
}
