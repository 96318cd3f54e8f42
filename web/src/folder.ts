/**
 * A task folder on the page: its files read from a picked directory, several picked files, a
 * `.zip`, or fetched from a URL beside the page (`?folder=URL`), and from a saved episode log that
 * carries them. The wasm module checks the files (errors name the file at fault); this module
 * only gathers them by name.
 */

/** The file names a task folder may hold (`sim::FOLDER_FILES`, in the core's order). */
export const FOLDER_FILES = ['domain.pddl', 'problem.pddl', 'motions.json', 'scene.json', 'demo.json', 'expert.json', 'demo.plan', 'README.md'] as const;

/** An open task folder: its name in messages, its files by name, and the URL it came from (null:
 * uploaded, so no link can restore it). */
export interface OpenFolder {
  name: string;
  files: Record<string, string>;
  url: string | null;
}

const isFolderFile = (name: string): boolean => (FOLDER_FILES as readonly string[]).includes(name);

/** The last part of a path (`a/b/scene.json` → `scene.json`). */
const baseName = (path: string): string => path.slice(path.lastIndexOf('/') + 1);

/**
 * Picks the folder's files among `paths` (path → text): those with a folder file's name in the
 * shallowest directory that holds a `domain.pddl` (a zip or a picked directory may nest the folder
 * one level down, next to other files). Returns the files by name and that directory's path.
 */
function pickFolder(paths: Map<string, string>): { dir: string; files: Record<string, string> } {
  const dirOf = (p: string) => p.slice(0, Math.max(0, p.lastIndexOf('/')));
  const depth = (p: string) => p.split('/').length;
  const domains = [...paths.keys()].filter((p) => baseName(p) === 'domain.pddl').sort((a, b) => depth(a) - depth(b));
  const dir = domains.length ? dirOf(domains[0]) : [...paths.keys()].map(dirOf).sort((a, b) => depth(a) - depth(b))[0] ?? '';
  const files: Record<string, string> = {};
  for (const [p, text] of paths) if (dirOf(p) === dir && isFolderFile(baseName(p))) files[baseName(p)] = text;
  return { dir, files };
}

/** A zip's entries (path → text), folder files only; directories and other files are skipped. */
async function unzipText(name: string, data: Uint8Array): Promise<Map<string, string>> {
  const { unzipSync, strFromU8 } = await import('fflate');
  let entries: Record<string, Uint8Array>;
  try {
    entries = unzipSync(data, { filter: (f) => isFolderFile(baseName(f.name)) && !f.name.startsWith('__MACOSX/') });
  } catch (e) {
    throw new Error(`${name}: not a zip archive (${(e as Error).message})`);
  }
  return new Map(Object.entries(entries).map(([p, bytes]) => [p, strFromU8(bytes)]));
}

/**
 * The folder the user picked: a directory (`webkitdirectory`: each file's `webkitRelativePath`
 * starts with the directory's name), several files, or one `.zip`. Rejects when none of the files
 * is a folder file, naming what a folder holds.
 */
export async function folderFromFiles(list: File[]): Promise<OpenFolder> {
  const zip = list.length === 1 && /\.zip$/i.test(list[0].name);
  let paths: Map<string, string>;
  let name: string;
  if (zip) {
    name = list[0].name.replace(/\.zip$/i, '');
    paths = await unzipText(list[0].name, new Uint8Array(await list[0].arrayBuffer()));
  } else {
    const path = (f: File) => f.webkitRelativePath || f.name;
    const kept = list.filter((f) => isFolderFile(baseName(path(f))));
    paths = new Map(await Promise.all(kept.map(async (f) => [path(f), await f.text()] as [string, string])));
    const top = list.map(path).find((p) => p.includes('/'));
    name = top ? top.slice(0, top.indexOf('/')) : 'upload';
  }
  const { dir, files } = pickFolder(paths);
  if (!Object.keys(files).length) {
    const what = zip ? list[0].name : list.length === 1 ? list[0].name : `the ${list.length} files`;
    throw new Error(`${what}: no task folder files in it (a task folder holds domain.pddl, problem.pddl, motions.json, scene.json and demo.json or expert.json)`);
  }
  // A zip of a directory names the folder after that directory; a bare name reads `./NAME`, as
  // the core names it in messages.
  if (dir) name = baseName(dir);
  return { name: `./${name}`, files, url: null };
}

/**
 * The folder served at `url` (relative to the page): each known file fetched from `url/NAME`. A
 * file the server does not have (404, or the page's own HTML a single-page server answers with) is
 * absent; a failed request rejects naming the file.
 */
export async function folderFromUrl(url: string): Promise<OpenFolder> {
  const base = url.replace(/\/+$/, '');
  const files: Record<string, string> = {};
  await Promise.all(
    FOLDER_FILES.map(async (name) => {
      const at = `${base}/${name}`;
      let res: Response;
      try {
        res = await fetch(new URL(at, location.href), { cache: 'no-cache' });
      } catch (e) {
        throw new Error(`${at}: could not be fetched (${(e as Error).message})`);
      }
      if (res.status === 404 || res.status === 410) return;
      if (!res.ok) throw new Error(`${at}: the server answered ${res.status} ${res.statusText}`.trim());
      if ((res.headers.get('content-type') ?? '').startsWith('text/html')) return;
      files[name] = await res.text();
    }),
  );
  return { name: base, files, url };
}

/** The folder an episode log carries (`folder.files`), or null. */
export function folderOfLog(log: { folder?: { dir: string; files?: Record<string, string> | null } | null }): OpenFolder | null {
  const f = log.folder;
  return f?.files ? { name: f.dir, files: f.files, url: null } : null;
}

/** Whether parsed JSON is an episode log (`Session.episodeJson()`), not a scene. */
export function isEpisodeLog(v: unknown): v is { options: Record<string, unknown>; events: unknown[]; folder?: { dir: string; files?: Record<string, string> | null } | null } {
  return typeof v === 'object' && v !== null && 'events' in v && 'options' in v && Array.isArray((v as { events: unknown }).events);
}
