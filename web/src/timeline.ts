/**
 * The timeline under the 3-D view: a scrubber over the episode's simulated time with a marker per
 * disturbance (drags, L1–L4, coloured by kind) and per replan (its reason on hover). Dragging the
 * scrubber pauses the run and shows the recorded moment in the view (and the panels: rewind.ts);
 * Play returns to live.
 * Loaded once the page is interactive: it is not part of the first frame.
 */
import { levelName } from './catalogue';
import { MARK_COLOURS, type History, type Mark } from './history';

export interface TimelineParts {
  history: History;
  /** Pauses the run (scrubbing begins). */
  pause: () => void;
  /** Play / pause, as the Play button (Space on the scrubber). */
  togglePlay: () => void;
}

/** Markers drawn at most (the newest): hundreds of replans stay one light row. */
const MAX_SHOWN = 300;

/** A marker's name: a disturbance's word (the catalogue's label), else what it marks. */
const nameOf = (kind: Mark['kind']): string => (kind === 'drag' ? 'Drag' : kind === 'replan' ? 'Replan' : levelName(kind));

/** The scale's end: the latest time rounded up, so markers move only when it steps. */
function scaleEnd(t: number): number {
  const step = t < 30 ? 5 : t < 120 ? 15 : 60;
  return Math.max(step, Math.ceil((t + 1e-6) / step) * step);
}

export class Timeline {
  readonly root: HTMLElement;
  private readonly range: HTMLInputElement;
  private readonly marksEl: HTMLElement;
  private readonly label: HTMLElement;
  private max = 0;
  private marksShown = -1;

  constructor(
    stage: HTMLElement,
    private readonly p: TimelineParts,
  ) {
    this.root = document.createElement('div');
    this.root.className = 'timeline';
    this.root.id = 'timeline';
    this.marksEl = document.createElement('div');
    this.marksEl.className = 'tl-marks';
    this.range = document.createElement('input');
    this.range.type = 'range';
    this.range.id = 'timeline-range';
    this.range.min = '0';
    this.range.step = '0.01';
    this.range.setAttribute('aria-label', 'Episode time: drag to view an earlier moment');
    this.label = document.createElement('span');
    this.label.className = 'tl-label';
    this.label.id = 'timeline-label';
    this.label.setAttribute('aria-live', 'polite');
    const track = document.createElement('div');
    track.className = 'tl-track';
    track.append(this.marksEl, this.range);
    this.root.append(track, this.label);
    stage.append(this.root);
    stage.classList.add('has-timeline');

    this.range.addEventListener('input', () => this.scrub(Number(this.range.value)));
    this.range.addEventListener('keydown', (e) => {
      if (e.key !== ' ') return;
      // Space keeps its page-wide meaning (play / pause) on the scrubber.
      e.preventDefault();
      e.stopPropagation();
      p.togglePlay();
    });
    p.history.listen(() => this.update());
    this.update();
  }

  /** Shows the moment at `t` and pauses the run. */
  private scrub(t: number): void {
    const h = this.p.history;
    if (h.viewing === null) this.p.pause();
    h.view(Math.min(t, h.end));
  }

  private update(): void {
    const h = this.p.history;
    const max = scaleEnd(h.end);
    const rebuild = max !== this.max || h.marks.length !== this.marksShown;
    if (max !== this.max) {
      this.max = max;
      this.range.max = String(max);
    }
    if (rebuild) this.drawMarks();
    const t = h.viewing ?? h.end;
    this.range.value = String(t);
    // The played part of the track, up to the latest time.
    this.range.style.setProperty('--live', `${(h.end / max) * 100}%`);
    const past = h.viewing !== null;
    this.root.classList.toggle('past', past);
    const text = past ? `viewing t = ${t.toFixed(1)} s — Play returns to live` : `live · t = ${t.toFixed(1)} s`;
    if (this.label.textContent !== text) this.label.textContent = text;
  }

  private drawMarks(): void {
    const h = this.p.history;
    this.marksShown = h.marks.length;
    const items = h.marks.slice(-MAX_SHOWN).map((m) => {
      const s = document.createElement('span');
      s.className = `tl-mark ${m.kind === 'replan' ? 'replan' : 'disturbance'}`;
      s.dataset.kind = m.kind;
      s.dataset.t = m.t.toFixed(2);
      s.style.left = `${(m.t / this.max) * 100}%`;
      s.style.background = MARK_COLOURS[m.kind];
      s.title = `${nameOf(m.kind)} at t = ${m.t.toFixed(2)} s: ${m.text}`;
      return s;
    });
    this.marksEl.replaceChildren(...items);
  }
}
