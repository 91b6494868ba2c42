// meshq (WebAssembly) against three-mesh-bvh in headless Chromium: the Node benchmark's
// workloads run by the page web/bench/ in the browser's own engine, on the mesh the Node
// benchmark loads (the bundled bunny, or the OBJ file MESHQ_BENCH_MESH names). Prints the
// ratios (three-mesh-bvh's time / meshq's) and the browser's version; --json prints them as
// JSON. Build the demo first: scripts/build-web.sh. Environment: MESHQ_BENCH_RAYS (default
// 1,000,000), MESHQ_BENCH_POINTS (default 100,000), MESHQ_BENCH_ROUNDS (default 5),
// CHROMIUM (the browser binary, default /usr/bin/chromium).
import { fileURLToPath } from 'node:url';
import { launchChromium, startServer } from '../../web/tests/browser.mjs';
import { fail, loadMesh, positiveInteger } from './args.mjs';

const json = process.argv.includes('--json');
const { env } = process;
const options = {
  rays: positiveInteger('MESHQ_BENCH_RAYS', env.MESHQ_BENCH_RAYS, 1_000_000),
  points: positiveInteger('MESHQ_BENCH_POINTS', env.MESHQ_BENCH_POINTS, 100_000),
  rounds: positiveInteger('MESHQ_BENCH_ROUNDS', env.MESHQ_BENCH_ROUNDS, 5),
};
const { index, positions } = await loadMesh();

const web = fileURLToPath(new URL('../../web/', import.meta.url));
const { url, server } = await startServer(web, 'bench');
const browser = await launchChromium();
let failure = null;
try {
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e));
  // Served cross-origin isolated: the worker pool shares memory with its workers.
  await page.goto(new URL('bench/?driven&isolated', url).href);
  await page.waitForFunction(() => window.meshqBench !== undefined, null, { timeout: 60_000 });
  if (errors.length) throw errors[0];
  // The mesh crosses as plain arrays (structured cloning) and becomes typed arrays again there.
  const result = await page.evaluate(
    ([p, i, o]) => window.meshqBench.run(new Float32Array(p), new Uint32Array(i), o),
    [Array.from(positions), Array.from(index), options],
  ).catch((e) => {
    // The page's own message (an invalid mesh, say), on one line.
    failure = `the benchmark page failed: ${e.message.replace(/^page\.evaluate: /, '').split('\n')[0]}`;
    return null;
  });
  if (result !== null) {
    result.browser = browser.version();
    result.mesh = process.env.MESHQ_BENCH_MESH ?? 'bunny';
    if (json) {
      console.log(JSON.stringify(result, null, 2));
    } else {
      console.log(`${result.mesh}: ${result.triangles} triangles; Chromium ${result.browser}`);
      for (const row of result.rows) {
        if (row.workload === 'agreement') {
          console.log(`agreement on ${row.rays} random rays: ${row.identical} the same answer`);
        } else if (row.ratio === undefined) {
          console.log(`${row.workload}: ${row.meshq_ms.toFixed(1)} ms`);
        } else {
          const rate = row.meshq_per_s === undefined ? ''
            : `  (${(row.meshq_per_s / 1e6).toFixed(2)} vs ${(row.three_mesh_bvh_per_s / 1e6).toFixed(2)} M/s)`;
          console.log(`${row.workload.padEnd(52)} ${row.ratio.toFixed(2)}×${rate}`);
        }
      }
    }
  }
} finally {
  await browser.close();
  server.kill();
}
if (failure) fail(failure);
