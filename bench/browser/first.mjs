// A page's first loads of a blob in headless Chromium, on a first visit and on a return visit:
// the package started (`await init()`: its module fetched, compiled and instantiated), then the
// first five `MeshBvh.fromBlob` calls (web/bench/first.html). Each sample is a browser with a
// fresh profile: visit 1 finds nothing cached; the page then stays open 3 s, as a visitor's
// would, and the browser closes. Visit 2 starts the browser again on the same profile, where
// the site (served with MESHQ_CACHE=1) let it keep the files, and V8 the module's compiled
// code with them.
// `node bench/browser/first.mjs [samples] [--json]` (default 7; --json: every sample); MESHQ_BENCH_MESH names another OBJ file
// than the bundled bunny. Build first: scripts/build-web.sh (the page's package) and
// scripts/wasm.sh (the Node package that bakes the blob here).
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import meshq from '../../wasm/pkg/node/meshq_wasm.js';
import { launchChromiumWithProfile, startServer } from '../../web/tests/browser.mjs';
import { fail, loadMesh, positiveInteger } from './args.mjs';

const samples = positiveInteger('samples', process.argv.slice(2).find((a) => !a.startsWith('--')), 7);
const { index, positions } = await loadMesh();
const STAY_MS = 3000;
const web = fileURLToPath(new URL('../../web/', import.meta.url));
// The blob goes where the demo's server serves it (web/assets/ holds build outputs only).
const blobName = `first-${process.pid}.meshq`;
const blobPath = join(web, 'assets', blobName);
let blob;
try {
  const bvh = meshq.MeshBvh.build(positions, index);
  blob = bvh.toBlob();
  bvh.free();
} catch (e) {
  fail(`cannot build the mesh: ${e.message}`);
}
writeFileSync(blobPath, blob);

process.env.MESHQ_CACHE = '1';
const { url, server } = await startServer(web, 'first');
const visits = [[], []];
try {
  for (let s = 0; s < samples; s++) {
    const profile = mkdtempSync(join(tmpdir(), 'meshq-first-profile-'));
    try {
      for (const [v, times] of visits.entries()) {
        // A browser started anew for each visit: nothing is shared between them but the
        // profile on disk.
        const context = await launchChromiumWithProfile(profile);
        try {
          const page = await context.newPage();
          const errors = [];
          page.on('pageerror', (e) => errors.push(e));
          await page.goto(new URL(`bench/first.html?blob=../assets/${blobName}`, url).href);
          await page.waitForFunction(() => window.firstLoads !== undefined, null, { timeout: 60_000 });
          if (errors.length) throw errors[0];
          times.push(await page.evaluate(() => window.firstLoads));
          if (v === 0) await page.waitForTimeout(STAY_MS);
        } finally {
          await context.close();
        }
      }
    } finally {
      rmSync(profile, { recursive: true, force: true });
    }
  }
} finally {
  server.kill();
  rmSync(blobPath, { force: true });
}

const median = (v) => v.slice().sort((a, b) => a - b)[v.length >> 1];
const mesh = process.env.MESHQ_BENCH_MESH ?? 'bunny';
if (process.argv.includes('--json')) {
  // Every sample: [start, call 1, …, call 5] in ms, per visit.
  console.log(JSON.stringify({ mesh, triangles: index.length / 3, blob_bytes: blob.length, visits }));
  process.exit(0);
}
console.log(`${mesh} (${index.length / 3} triangles, a ${blob.length}-byte blob), ${samples} fresh browser profiles;`);
console.log('medians in ms of the package\'s start (init), then of fromBlob calls 1–5:');
for (const [v, label] of ['visit 1 (nothing cached)', 'visit 2 (browser restarted)'].entries()) {
  const cols = visits[v][0].map((_, k) => median(visits[v].map((t) => t[k])).toFixed(1));
  console.log(`${label.padEnd(28)} start ${cols[0].padStart(6)} | ${cols.slice(1).map((c) => c.padStart(5)).join(' ')}`);
}
