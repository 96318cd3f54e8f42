// The page's size as the README quotes it: every file of the built page (web/dist) gzipped at
// level 9, and the part fetched only when a tab first opens (lazy), so that the first load is
// `gz - lazyGz`. Shared by tests/e2e/bench.mjs and tests/node/bench-wasm.mjs.
import { readdir, readFile } from 'node:fs/promises';
import { gzipSync } from 'node:zlib';
import { join } from 'node:path';

// The PDDL editor (CodeMirror), the charts (uPlot, its JS and CSS), Compare, Teach mode (its
// panel, and the full wasm module with the recorder) are separate chunks fetched when their tab
// first opens; the help text when help first opens; the docs when a help link is followed; the
// robot's meshes (their reader's chunk and robots/*) and the timeline's rewind (rewind-*) after
// the first frame; a gallery task's files (tasks/*) when it is chosen.
const LAZY = /\/(robot-meshes-[^/]*\.(js|css)|robots\/[^/]*\/[^/]*|tasks\/[^/]*\/[^/]*|editor-[^/]*\.(js|css)|compare-[^/]*\.(js|css)|why-join-[^/]*\.(js|css)|rewind-[^/]*\.(js|css)|help-text-[^/]*\.js|folder-[^/]*\.js|uPlot[^/]*\.(js|css)|teach-[^/]*\.(js|css)|logic_lfd_teach[^/]*\.(js|wasm)|docs\/[^/]*\.md)$/;

/** Sizes of the built page in `dist`: totals (`raw`, `gz`, `lazyGz`) and one row per file. */
export async function pageSizes(dist) {
  const files = [];
  async function walk(d) {
    for (const e of await readdir(d, { withFileTypes: true })) {
      const p = join(d, e.name);
      if (e.isDirectory()) await walk(p);
      else files.push(p);
    }
  }
  await walk(dist);
  let raw = 0;
  let gz = 0;
  let lazyGz = 0;
  const rows = [];
  for (const f of files.sort()) {
    const b = await readFile(f);
    const g = gzipSync(b, { level: 9 }).length;
    const lazy = LAZY.test(f);
    rows.push({ file: f.slice(dist.length + 1), raw: b.length, gz: g, lazy });
    raw += b.length;
    gz += g;
    if (lazy) lazyGz += g;
  }
  return { raw, gz, lazyGz, rows };
}
