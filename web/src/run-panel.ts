/**
 * The Run tab: the current plan (done / current / ahead), the demonstration's states L0..LN and
 * actions with the state the robot joined, the current facts S_C with the last change, and the
 * last replan. Redrawn only when what it shows changed.
 */
import type { Frame } from 'logic-lfd';
import { demoStateItem, el, factChips } from './dom';
import type { RunLists } from './layout';

export class RunPanel {
  private lastKey = '';

  constructor(private readonly ui: RunLists) {}

  /** Forgets what was drawn, so the next frame redraws the lists. */
  invalidate(): void {
    this.lastKey = '';
  }

  show(f: Frame): void {
    const key = JSON.stringify([f.plan, f.executing, f.demo.length, f.matchedK, f.facts, f.lastReplan?.tick]);
    if (key === this.lastKey) return;
    this.lastKey = key;
    this.showPlan(f);
    this.showDemo(f);
    this.showFacts(f);
  }

  private showPlan(f: Frame): void {
    const list = this.ui.plan;
    this.ui.planCount.textContent = f.plan.length ? `${f.plan.length} actions` : '';
    list.replaceChildren(
      ...f.plan.map((a, i) => {
        const cls = f.executing === i ? 'current' : f.executing != null && i < f.executing ? 'done' : '';
        return el('li', { class: cls, 'aria-current': f.executing === i ? 'step' : 'false' }, a);
      }),
    );
    if (!f.plan.length) list.append(el('li', { class: 'muted empty' }, 'no plan yet'));
    list.querySelector('.current')?.scrollIntoView({ block: 'nearest' });
  }

  private showDemo(f: Frame): void {
    const k = f.matchedK ?? null;
    this.ui.matched.textContent = k == null ? '' : `joined at L${k}`;
    const items: HTMLElement[] = [];
    f.demoStates.forEach((facts, i) => {
      items.push(demoStateItem(i, facts, `demo-state${k === i ? ' matched' : ''}`));
      if (i < f.demo.length) items.push(el('li', { class: `demo-action${k != null && i >= k ? ' ahead' : ''}` }, `a${i + 1} ${f.demo[i]}`));
    });
    this.ui.demo.replaceChildren(...items);
  }

  private showFacts(f: Frame): void {
    const added = new Set(f.factsAdded);
    this.ui.facts.replaceChildren(...f.facts.map((x) => el('li', { class: added.has(x) ? 'added' : '' }, x)));
    this.ui.factsDiff.replaceChildren(...factChips(f.factsAdded, f.factsRemoved));
    const r = f.lastReplan;
    this.ui.replanInfo.textContent = r
      ? `Last replan at tick ${r.tick}: ${r.reason} — ${r.timeMs.toFixed(2)} ms${r.k != null ? `, joined the demo at L${r.k}` : ''}${r.fallback ? ', no skeleton joining the demo bound: planned to G from scratch (TAMP fallback)' : ''}`
      : '';
  }
}
