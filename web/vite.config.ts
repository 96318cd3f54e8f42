/**
 * Builds the page: the wasm package's aliases (pkg/, made by scripts/build-wasm.sh), ES-module
 * workers, and the project documentation (the repository's docs/*.md) served and copied beside the
 * page as docs/, where the help overlay links to it.
 */
import { defineConfig, type Plugin } from 'vite';
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const pkg = (file: string) => fileURLToPath(new URL(`../pkg/${file}`, import.meta.url));
const repo = fileURLToPath(new URL('..', import.meta.url));

/** The repository's docs/*.md (none when the folder is missing). */
function docFiles(dir: string): string[] {
  return existsSync(dir) ? readdirSync(dir).filter((f) => f.endsWith('.md')) : [];
}

/** A UTF-8 byte order mark: static servers send .md as text/markdown without a charset, and a
 * browser would then read the files as Latin-1; the mark makes it read UTF-8. */
const UTF8_BOM = Buffer.from([0xef, 0xbb, 0xbf]);

/** A doc file as copied into the build: with the byte order mark, once. */
function withBom(file: string): Buffer {
  const text = readFileSync(file);
  return text.subarray(0, 3).equals(UTF8_BOM) ? text : Buffer.concat([UTF8_BOM, text]);
}

/**
 * docs/*.md of the repository at `docs/` of the page: copied into the build, served by the dev
 * server. Without the folder the build still succeeds (the help's links then find nothing).
 */
function projectDocs(): Plugin {
  const dir = join(repo, 'docs');
  return {
    name: 'logic-lfd-docs',
    configureServer(server) {
      server.middlewares.use('/docs', (req, res, next) => {
        const name = decodeURIComponent((req.url ?? '').split('?')[0]).replace(/^\//, '');
        if (!docFiles(dir).includes(name)) return next();
        res.setHeader('content-type', 'text/markdown; charset=utf-8');
        res.end(readFileSync(join(dir, name)));
      });
    },
    generateBundle() {
      const files = docFiles(dir);
      if (!files.length) this.warn(`no ${dir}/*.md: the help's documentation links will find nothing`);
      for (const f of files) this.emitFile({ type: 'asset', fileName: `docs/${f}`, source: withBom(join(dir, f)) });
    },
  };
}

/** The gallery's task folders (`domains/NAME`), served and copied beside the page as
 * `tasks/NAME/`, where the benchmark select opens them (`?folder=tasks/NAME`). */
export const GALLERY = ['sorting', 'shelf-tower'];
const TASK_FILES = ['domain.pddl', 'problem.pddl', 'motions.json', 'scene.json', 'demo.json', 'expert.json', 'demo.plan', 'README.md'];

function galleryTasks(): Plugin {
  const dir = join(repo, 'domains');
  return {
    name: 'logic-lfd-gallery',
    configureServer(server) {
      server.middlewares.use('/tasks', (req, res, next) => {
        const [task, file] = decodeURIComponent((req.url ?? '').split('?')[0]).replace(/^\//, '').split('/');
        if (!GALLERY.includes(task) || !TASK_FILES.includes(file) || !existsSync(join(dir, task, file))) return next();
        res.setHeader('content-type', 'text/plain; charset=utf-8');
        res.end(readFileSync(join(dir, task, file)));
      });
    },
    generateBundle() {
      for (const task of GALLERY) {
        for (const f of TASK_FILES) {
          const file = join(dir, task, f);
          if (existsSync(file)) this.emitFile({ type: 'asset', fileName: `tasks/${task}/${f}`, source: readFileSync(file) });
        }
      }
    },
  };
}

export default defineConfig({
  base: './',
  plugins: [projectDocs(), galleryTasks()],
  resolve: {
    alias: {
      // The npm package's full API (the page imports only its types).
      'logic-lfd': pkg('web/logic_lfd.js'),
      // The worker's first-load module: the API without Teach mode (scripts/build-wasm.sh).
      'logic-lfd-page': pkg('page/logic_lfd.js'),
      // The full module, fetched by the worker when Teach mode opens.
      'logic-lfd-teach': pkg('page/logic_lfd_teach.js'),
    },
  },
  worker: { format: 'es' },
  server: { fs: { allow: [repo] } },
  build: {
    target: 'es2022',
    outDir: 'dist',
    emptyOutDir: true,
    chunkSizeWarningLimit: 1200,
  },
});
