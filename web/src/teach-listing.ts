/**
 * What the Teach tab lists, built from the worker's data: the recording's demo states and
 * recognised actions (each with its arm, time span and fact change), a taught demo's states and
 * actions, the goal checklist (L_N's facts) and a refused edit's explanation.
 */
import type { TaughtInfo, TeachError, TeachState } from 'logic-lfd';
import { button, demoStateItem, el, factChips } from './dom';

const ERROR_TITLES: Record<TeachError['kind'], string> = {
  input: 'Bad input',
  model: 'Model',
  unexplained: 'Not explained by the domain',
  physics: 'Physically implausible',
  refused: 'Refused',
};

/** The recording's L0, a1, L1, …; the actions in `fresh` are highlighted (just recognised). */
export function recordingItems(s: TeachState, fresh: ReadonlySet<number>): HTMLElement[] {
  const items: HTMLElement[] = [];
  s.states.forEach((st, i) => {
    items.push(demoStateItem(i, st));
    const seg = s.segments[i];
    if (seg) {
      const change = [...seg.added.map((f) => `+${f}`), ...seg.removed.map((f) => `−${f}`)].join(' ');
      items.push(
        el(
          'li',
          { class: `teach-seg${fresh.has(i) ? ' new' : ''}`, title: change },
          el('span', { class: 'seg-name' }, `a${i + 1} ${seg.action}`),
          el('span', { class: 'muted small' }, ` ${seg.arm} · ${seg.tStart.toFixed(2)}–${seg.tEnd.toFixed(2)} s`),
        ),
      );
    }
  });
  return items;
}

/** A taught demo's L0, a1, L1, … with the arm of each action; the first action of each of the
 * `moves` (`[first, end)` ranges) carries a button deleting that move. */
export function taughtItems(info: TaughtInfo, moves: [number, number][], onDelete: (k: number) => void): HTMLElement[] {
  const items: HTMLElement[] = [];
  info.states.forEach((st, i) => {
    items.push(demoStateItem(i, st));
    if (i >= info.actions.length) return;
    const k = moves.findIndex(([first]) => first === i);
    const row = el('li', { class: 'teach-seg teach-move' }, el('span', { class: 'seg-name' }, `a${i + 1} ${info.actions[i]}`), el('span', { class: 'muted small' }, ` ${info.arms[i]}`));
    if (k >= 0) {
      const [first, end] = moves[k];
      const span = end - first > 1 ? `a${first + 1}–a${end}` : `a${first + 1}`;
      const del = button(`teach-delete-move-${k + 1}`, `Delete move ${k + 1} (${span}) from the demonstration`, `✕ move ${k + 1}`);
      del.onclick = () => onDelete(k);
      row.append(del);
    }
    items.push(row);
  });
  return items;
}

/** The goal checklist: every fact of the last demo state, ticked when it is in the goal. */
export function goalItems(info: TaughtInfo, onChange: () => void): HTMLElement[] {
  const last = info.states[info.states.length - 1];
  const goal = new Set(info.goal);
  return last.map((f) => {
    const box = el('input', { type: 'checkbox', 'aria-label': `goal fact ${f}` });
    box.checked = goal.has(f);
    box.onchange = onChange;
    return el('li', {}, el('label', {}, box, ` ${f}`));
  });
}

/** The facts ticked in a goal checklist. */
export function checkedGoal(list: HTMLElement): string[] {
  return [...list.querySelectorAll('input')].filter((b) => b.checked).map((b) => (b.getAttribute('aria-label') ?? '').replace(/^goal fact /, ''));
}

/** A refused edit (or load): what kind of refusal and when, the message, the fact change it
 * would make, and what was kept. */
export function errorContent(e: TeachError, kept = 'Nothing was recorded from this edit.'): HTMLElement[] {
  return [
    el('strong', {}, `${ERROR_TITLES[e.kind]}${e.t != null ? ` at t = ${e.t.toFixed(2)} s` : ''}`),
    el('div', { class: 'teach-error-msg' }, e.message),
    el('div', { class: 'facts-diff' }, ...factChips(e.added, e.removed)),
    el('div', { class: 'muted small' }, kept),
  ];
}
