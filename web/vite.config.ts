import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const pkg = fileURLToPath(new URL('../pkg/web/logic_lfd.js', import.meta.url));
const repo = fileURLToPath(new URL('..', import.meta.url));

export default defineConfig({
  base: './',
  resolve: { alias: { 'logic-lfd': pkg } },
  worker: { format: 'es' },
  server: { fs: { allow: [repo] } },
  build: {
    target: 'es2022',
    outDir: 'dist',
    emptyOutDir: true,
    chunkSizeWarningLimit: 1200,
  },
});
