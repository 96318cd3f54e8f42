/**
 * The robot in the arms' place: the top bar's robot select (the Panda, the UR5, a robot folder of
 * the user's own), the folder read from a picked directory, and the `robot` option a session takes.
 * The wasm module checks the folder (errors name the file at fault); this module only gathers it.
 */
import type { RobotChoice } from 'logic-lfd';
import { el } from './dom';

/** The robots shipped with the page (their URDFs compiled into the wasm module, their meshes
 * under `robots/<name>/`), the first the default. */
export const SHIPPED_ROBOTS: [string, string][] = [
  ['panda', 'Panda'],
  ['ur5', 'UR5'],
];

/** The robot select's item that opens a robot folder, and the one of the open folder. */
export const OPEN_ROBOT = 'open-robot';
export const ROBOT_FOLDER = 'robot-folder';

/** The robot the arms are: a shipped one by name, or a robot folder's files (path → bytes). */
export interface RobotPick {
  name: string;
  files?: Record<string, Uint8Array>;
}

/** The session option for `pick` (none: the default Panda). */
export function robotOption(pick: RobotPick | null): { robot?: RobotChoice } {
  if (!pick || pick.name === SHIPPED_ROBOTS[0][0]) return {};
  return { robot: pick.files ?? pick.name };
}

/** The robot a page opened with `?robot=NAME` takes (a shipped robot's name; else the default). */
export function robotFromUrl(name: string | null): RobotPick | null {
  return name && SHIPPED_ROBOTS.some(([n]) => n === name) && name !== SHIPPED_ROBOTS[0][0] ? { name } : null;
}

/** A robot's name as the page shows it: a shipped robot's label (`UR5`), else its folder's name. */
export function robotName(pick: RobotPick | null): string {
  const shipped = SHIPPED_ROBOTS.find(([n]) => n === (pick?.name ?? SHIPPED_ROBOTS[0][0]));
  return shipped && !pick?.files ? shipped[1] : (pick?.name ?? '');
}

/** How a robot is named in messages (`capital`: at a sentence's start). */
export function robotLabel(pick: RobotPick | null, capital = false): string {
  const label = pick?.files ? `the robot ${pick.name}` : `the ${robotName(pick)}`;
  return capital ? label[0].toUpperCase() + label.slice(1) : label;
}

/** The robot select, set to `pick`. */
export function robotSelect(pick: RobotPick | null): HTMLSelectElement {
  const sel = el('select', { id: 'robot', 'aria-label': 'Robot', title: 'The robot in the arms’ place: the Panda or the UR5 from its URDF, or a folder of your own (robot.json, URDF, meshes)' });
  setRobotChoice(sel, pick);
  return sel;
}

/** Sets the robot select's items (a robot folder's own item while one is open) and value. */
export function setRobotChoice(sel: HTMLSelectElement, pick: RobotPick | null): void {
  const items = SHIPPED_ROBOTS.map(([v, text]) => el('option', { value: v }, text));
  if (pick?.files) items.push(el('option', { value: ROBOT_FOLDER }, `${pick.name} (folder)`));
  items.push(el('option', { value: OPEN_ROBOT }, 'Open robot folder…'));
  sel.replaceChildren(...items);
  sel.value = pick?.files ? ROBOT_FOLDER : (pick?.name ?? SHIPPED_ROBOTS[0][0]);
}

/** The hidden directory input behind "Open robot folder…". */
export function robotDirInput(): HTMLInputElement {
  return el('input', { id: 'robot-dir', type: 'file', webkitdirectory: '', multiple: '', hidden: '', 'aria-label': 'Robot folder' });
}
