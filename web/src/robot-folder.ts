/**
 * A robot folder picked from this computer, read for the robot select (robot-choice.ts): a chunk
 * of its own, fetched when a folder is picked, so the page's first load does not carry it.
 */
import type { RobotPick } from './robot-choice';

/** What a robot folder's files may be: the robot file, the URDF and collision meshes. */
const ROBOT_FILE = /\.(json|urdf|stl|obj|dae)$/i;

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
