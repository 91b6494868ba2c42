// Interleaved A/B of meshq package builds on the batched workloads, best of five rounds, so
// machine noise hits every build alike: for choosing between implementations, not a peer
// comparison (that is bench.mjs). Arguments: directories holding copies of wasm/pkg/node,
// e.g. one built from the main branch and one from a change:
//   node bench/node/variants.mjs /tmp/pkg-main /tmp/pkg-change
import { createRequire } from 'node:module';
import { index, positions } from './bunny.mjs';

const require = createRequire(import.meta.url);
const pkgs = process.argv.slice(2).map((p) => [p, require(`${p}/meshq_wasm.js`)]);
const meshes = pkgs.map(([p, m]) => [p, m, m.MeshBvh.build(positions, index)]);
const [, first, firstBvh] = meshes[0];
const bounds = firstBvh.bounds();
const random = first.randomRays(bounds, 1, 1_000_000);
const camera = first.cameraRays(bounds, 1024, 1024);
const points = first.queryPoints(bounds, 1, 100_000);
const workloads = {
  random: (b) => { const n = random.length / 6; const d = new Float32Array(n), t = new Uint32Array(n); return () => b.raycastBatch(random, 0, Infinity, d, t); },
  camera: (b) => { const n = camera.length / 6; const d = new Float32Array(n), t = new Uint32Array(n); return () => b.raycastBatch(camera, 0, Infinity, d, t); },
  any: (b) => { const n = random.length / 6; const h = new Uint8Array(n); return () => b.raycastAnyBatch(random, 0, Infinity, h); },
  closest: (b) => { const n = points.length / 3; const c = new Float32Array(3 * n), t = new Uint32Array(n), d = new Float32Array(n); return () => b.closestPointBatch(points, Infinity, c, t, d); },
};
for (const [name, make] of Object.entries(workloads)) {
  const runs = meshes.map(([p, , b]) => [p, make(b)]);
  const best = runs.map(() => Infinity);
  for (let round = 0; round < 5; round++) {
    runs.forEach(([, f], i) => { const t0 = performance.now(); f(); best[i] = Math.min(best[i], performance.now() - t0); });
  }
  console.log(name.padEnd(8), runs.map(([p], i) => `${p.split('/').pop()} ${best[i].toFixed(0)} ms`).join('   '));
}
