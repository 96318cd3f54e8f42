// Node tests of the built npm package in pkg/ (run scripts/build-wasm.sh first).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const pkgDir = fileURLToPath(new URL('../../pkg/', import.meta.url));
const lfd = await import(new URL('../../pkg/node/index.mjs', import.meta.url).href);

test('version matches the crate', () => {
  const cargo = readFileSync(fileURLToPath(new URL('../../crate/Cargo.toml', import.meta.url)), 'utf8');
  const want = /^version = "([^"]+)"/m.exec(cargo)[1];
  assert.equal(lfd.version(), want);
});

test('the package resolves by name from node, as ESM and as CommonJS', () => {
  const esm = execFileSync(
    process.execPath,
    ['--input-type=module', '-e', "import init, { version } from 'logic-lfd'; await init(); console.log(version())"],
    { cwd: pkgDir, encoding: 'utf8' },
  );
  const cjs = execFileSync(process.execPath, ['-e', "console.log(require('logic-lfd').version())"], {
    cwd: pkgDir,
    encoding: 'utf8',
  });
  assert.equal(esm.trim(), lfd.version());
  assert.equal(cjs.trim(), lfd.version());
});
