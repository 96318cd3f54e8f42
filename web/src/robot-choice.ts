/**
 * The robot in the arms' place: the top bar's robot select (the Panda, the UR5, a robot folder of
 * the user's own), the folder read from a picked directory, and the `robot` option a session takes.
 * The wasm module checks the folder (errors name the file at fault); this module only gathers it.
 */
import type { RobotChoice } from 'logic-lfd';
import { el } from './dom';

/** The robots shipped with the page (their URDFs compiled into the wasm module, their meshes
 * under `robots/<name>/`), the first the default. */
export const SHIPPED_ROBOTS: [string, string, string][] = [
  ['panda', 'Panda', 'The Franka Emika Panda, from its own URDF (7 joints)'],
  ['ur5', 'UR5', 'The Universal Robots UR5, from its own URDF (6 joints, a two-finger gripper added)'],
];

/** The robot select's item that opens a robot folder, and the one of the open folder. */
export const OPEN_ROBOT = 'open-robot';
export const ROBOT_FOLDER = 'robot-folder';

/** The robot the arms are: a shipped one by name, or a robot folder's files (path → bytes). */
export interface RobotPick {
  name: string;
  files?: Record<string, Uint8Array>;
}

/** What a robot folder's files may be: the robot file, the URDF and collision meshes. */
const ROBOT_FILE = /\.(json|urdf|stl|obj|dae)$/i;

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
  const sel = el('select', { id: 'robot', 'aria-label': 'Robot', title: 'The robot in the arms’ place' });
  setRobotChoice(sel, pick);
  return sel;
}

/** Sets the robot select's items (a robot folder's own item while one is open) and value. */
export function setRobotChoice(sel: HTMLSelectElement, pick: RobotPick | null): void {
  const items = SHIPPED_ROBOTS.map(([v, text, title]) => el('option', { value: v, title }, text));
  if (pick?.files) items.push(el('option', { value: ROBOT_FOLDER, title: 'The robot folder opened from this computer' }, `${pick.name} (folder)`));
  items.push(el('option', { value: OPEN_ROBOT, title: 'Put a robot of your own in the arms’ place: pick its folder (robot.json, URDF, meshes)' }, 'Open robot folder…'));
  sel.replaceChildren(...items);
  sel.value = pick?.files ? ROBOT_FOLDER : (pick?.name ?? SHIPPED_ROBOTS[0][0]);
}

/** The hidden directory input behind "Open robot folder…". */
export function robotDirInput(): HTMLInputElement {
  return el('input', { id: 'robot-dir', type: 'file', webkitdirectory: '', multiple: '', hidden: '', 'aria-label': 'Robot folder' });
}

/**
 * The robot folder the user picked (`webkitdirectory`: each path starts with the directory's
 * name): its robot file, URDF and meshes by path, as bytes. Rejects a folder without a `.json`
 * or `.urdf` file.
 */
export async function robotFromFiles(list: File[]): Promise<RobotPick> {
  const path = (f: File) => f.webkitRelativePath || f.name;
  const kept = list.filter((f) => ROBOT_FILE.test(f.name));
  if (!kept.some((f) => /\.json$/i.test(f.name)) || !kept.some((f) => /\.urdf$/i.test(f.name))) {
    throw new Error('a robot folder holds its robot.json, its URDF and the meshes the URDF names');
  }
  const files: Record<string, Uint8Array> = {};
  await Promise.all(kept.map(async (f) => (files[path(f)] = new Uint8Array(await f.arrayBuffer()))));
  const top = path(kept[0]).split('/')[0];
  const name = kept.every((f) => path(f).startsWith(`${top}/`)) ? top : 'robot';
  return { name, files };
}
