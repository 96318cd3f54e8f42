/**
 * Moves of a demonstration: a move is the run of actions from a free hand to a free hand again (a
 * pick and its place; a hook's pick, pull and put-back), the unit Undo, the toast and deletion work
 * on. While recording the arms' `holding` tells where a move ends; in a taught demo.json the
 * gripper commands do (an action whose last command opens the gripper ends a move).
 */
import type { Segment, TeachState } from 'logic-lfd';

/** Whether no arm holds anything: a move is complete. */
export const atRest = (s: TeachState): boolean => s.handles.every((h) => h.holding === null);

/** The net fact change of consecutive actions (a fact made true then false again is left out). */
export function netChange(segs: readonly Pick<Segment, 'added' | 'removed'>[]): { added: string[]; removed: string[] } {
  const added = new Set<string>();
  const removed = new Set<string>();
  for (const s of segs) {
    for (const f of s.removed) if (!added.delete(f)) removed.add(f);
    for (const f of s.added) if (!removed.delete(f)) added.add(f);
  }
  return { added: [...added].sort(), removed: [...removed].sort() };
}

interface DemoAction {
  action: string;
  gripper?: { step: number; command: string }[];
}
interface DemoFile {
  actions: DemoAction[];
  goal: string[];
}

/** The moves of a taught demo.json as `[first, end)` action ranges (a last, unfinished run of
 * actions is a move of its own). */
export function demoMoves(demoJson: string): [number, number][] {
  const { actions } = JSON.parse(demoJson) as DemoFile;
  const moves: [number, number][] = [];
  let start = 0;
  actions.forEach((a, i) => {
    const last = a.gripper?.[a.gripper.length - 1]?.command;
    if (last === 'open' || i === actions.length - 1) {
      moves.push([start, i + 1]);
      start = i + 1;
    }
  });
  return moves;
}

/** The demo.json without the actions `[first, end)` (to be checked again before use). */
export function withoutMove(demoJson: string, [first, end]: [number, number]): string {
  const demo = JSON.parse(demoJson) as DemoFile;
  demo.actions.splice(first, end - first);
  return JSON.stringify(demo);
}

/** The demo.json with goal `goal`. */
export function withGoal(demoJson: string, goal: string[]): string {
  const demo = JSON.parse(demoJson) as DemoFile;
  demo.goal = goal;
  return JSON.stringify(demo);
}
