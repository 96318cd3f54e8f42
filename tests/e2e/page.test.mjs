// Browser tests of the page (Debian Chromium, headless, WebGL through SwiftShader).
import { after, before, describe, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdir } from 'node:fs/promises';
import { join } from 'node:path';
import { launch, openPage, screenshots, serve } from './harness.mjs';

let server;
let browser;

before(async () => {
  server = await serve();
  browser = await launch();
  await mkdir(screenshots, { recursive: true });
});

after(async () => {
  await browser?.close();
  await server?.close();
});

describe('page', () => {
  test('loads the wasm in a worker with no console errors', async () => {
    const { page, errors } = await openPage(browser, server.url);
    await page.waitForSelector('#app[data-ready="true"]', { timeout: 20000 });
    assert.deepEqual(errors, []);
    await page.close();
  });
});
