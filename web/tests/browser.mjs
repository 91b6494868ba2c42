// What the browser tests share: the demo server on a port the OS picks (checked to be ours by
// a token), and headless Chromium (Debian's, through playwright-core) with a fresh profile.
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

/**
 * Starts `serve.mjs` from `dir` on a free port and resolves to `{ url, server }` once the
 * server that answers is this one (a taken port would silently test another server's page).
 */
export async function startServer(dir, label) {
  const token = `${label}-${process.pid}-${Date.now()}`;
  const server = spawn(process.execPath, [join(dir, 'serve.mjs')], {
    cwd: dir,
    env: { ...process.env, MESHQ_PORT: '0', MESHQ_SERVER_TOKEN: token },
    stdio: ['ignore', 'pipe', 'inherit'],
  });
  process.on('exit', () => server.kill());
  const url = await new Promise((resolve, reject) => {
    let text = '';
    server.stdout.on('data', (chunk) => {
      text += chunk;
      const m = text.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve(m[0]);
    });
    server.on('exit', (code) => reject(new Error(`server exited with ${code}`)));
  });
  const identity = await (await fetch(new URL('__meshq-demo', url))).text();
  assert.equal(identity, `meshq-demo ${token}`, 'another server answers on our port');
  return { url, server };
}

const launchOptions = () => ({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  timeout: 60000,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});

/** Headless Chromium with a fresh temporary profile and no background networking. */
export function launchChromium() {
  return chromium.launch(launchOptions());
}

/**
 * Headless Chromium with its profile (its HTTP cache and V8's code cache among it) in `dir`,
 * which outlives the returned browser context: a later launch on the same `dir` finds what
 * this one kept, as a returning visitor's browser does.
 */
export function launchChromiumWithProfile(dir) {
  return chromium.launchPersistentContext(dir, { ...launchOptions(), headless: true });
}
