import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const pkg = (file: string) => fileURLToPath(new URL(`../pkg/${file}`, import.meta.url));
const repo = fileURLToPath(new URL('..', import.meta.url));

export default defineConfig({
  base: './',
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
