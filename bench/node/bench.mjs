// meshq (WebAssembly, the Node build in wasm/pkg) against three-mesh-bvh in Node on the bundled bunny,
// with the DESIGN.md workloads and the same rays and points for both. Prints throughput
// ratios (meshq / three-mesh-bvh); --json prints them as JSON. Build the package first:
// scripts/wasm.sh. Environment: MESHQ_BENCH_RAYS (default 1,000,000), MESHQ_BENCH_SINGLE
// (rays for the one-call-per-ray runs, default 200,000), MESHQ_BENCH_POINTS (default 100,000),
// MESHQ_BENCH_MESH (an OBJ file instead of the bundled bunny).
import os from 'node:os';
import * as THREE from 'three';
import { MeshBVH, SAH } from 'three-mesh-bvh';
import meshq from '../../wasm/pkg/node/meshq_wasm.js';
import { MeshqPool } from '../../wasm/pkg/node/pool.mjs';
import { geometry, index, positions } from './bunny.mjs';
// The timing and the peer's ray loop the browser benchmark (web/bench/) uses too.
import { median as time, paired, peerFirstHits as firstHits } from '../../web/bench/timing.js';

const RAYS = Number(process.env.MESHQ_BENCH_RAYS ?? 1_000_000);
const SINGLE = Number(process.env.MESHQ_BENCH_SINGLE ?? 200_000);
const POINTS = Number(process.env.MESHQ_BENCH_POINTS ?? 100_000);
const json = process.argv.includes('--json');
const log = (...a) => { if (!json) console.log(...a); };

const results = [];
function report(workload, meshqMs, peerMs, count, unit) {
  const row = { workload, meshq_ms: meshqMs, three_mesh_bvh_ms: peerMs, ratio: peerMs / meshqMs };
  if (count) {
    row.meshq_per_s = (count / meshqMs) * 1000;
    row.three_mesh_bvh_per_s = (count / peerMs) * 1000;
  }
  results.push(row);
  const rate = count ? `  (${(row.meshq_per_s / 1e6).toFixed(2)} vs ${(row.three_mesh_bvh_per_s / 1e6).toFixed(2)} M ${unit}/s)` : '';
  log(`${workload.padEnd(44)} ${row.ratio.toFixed(2)}×${rate}`);
}

// Build: meshq's default (balanced binned SAH) against three-mesh-bvh's default options
// (CENTER splits).
let bvh = null;
const buildMeshq = time(() => { bvh?.free(); bvh = meshq.MeshBvh.build(positions, index); }, 5);
const buildPeer = time(() => new MeshBVH(geometry), 5);
const peer = new MeshBVH(geometry);
log(`${process.env.MESHQ_BENCH_MESH ?? 'bunny'}: ${index.length / 3} triangles; meshq build ${buildMeshq.toFixed(1)} ms, three-mesh-bvh ${buildPeer.toFixed(1)} ms`);
report('build (default settings)', buildMeshq, buildPeer);
// Like for like: meshq's fast preset splits at the centre, as three-mesh-bvh's default
// (CENTER) does; meshq's default is binned SAH, as three-mesh-bvh's SAH strategy is.
let fastBvh = null;
const buildFast = time(() => { fastBvh?.free(); fastBvh = meshq.MeshBvh.build(positions, index, { quality: 'fast' }); }, 5);
report('build, centre splits: fast vs default (CENTER)', buildFast, buildPeer);
// three-mesh-bvh reorders the index it builds over: give its SAH builds their own copy so the
// tree `peer` keeps matching its geometry.
const sahGeometry = geometry.clone();
const buildPeerSah = time(() => new MeshBVH(sahGeometry, { strategy: SAH }), 3);
report('build, SAH: balanced vs strategy SAH', buildMeshq, buildPeerSah);
const blob = bvh.toBlob();
// The first loads grow the module's memory (a one-time cost per page) and run while V8 still
// compiles the loading code for speed (bench/node/first.mjs times them): after 30 loads, the
// median of 21 is the steady state.
for (let i = 0; i < 30; i++) meshq.MeshBvh.fromBlob(blob).free();
const loadMeshq = time(() => meshq.MeshBvh.fromBlob(blob).free(), 21);
log(`meshq fromBlob (validated load of a ${blob.length}-byte blob): ${loadMeshq.toFixed(1)} ms`);
results.push({ workload: 'meshq fromBlob load', meshq_ms: loadMeshq });

const bounds = bvh.bounds();
const random = meshq.randomRays(bounds, 1, RAYS);
const camera = meshq.cameraRays(bounds, 1024, 1024);
const points = meshq.queryPoints(bounds, 1, POINTS);

const peerFirstHits = (rays, count) => firstHits(THREE, peer, rays, count);

function batch(rays) {
  const n = rays.length / 6;
  const distances = new Float32Array(n);
  const triangles = new Uint32Array(n);
  return () => bvh.raycastBatch(rays, 0, Infinity, distances, triangles);
}

// Agreement first: the same first triangle (or a tie) on the random rays.
{
  const n = Math.min(RAYS, 100_000);
  const ray = new THREE.Ray();
  let same = 0;
  let hits = 0;
  for (let k = 0; k < n; k++) {
    ray.origin.set(random[6 * k], random[6 * k + 1], random[6 * k + 2]);
    ray.direction.set(random[6 * k + 3], random[6 * k + 4], random[6 * k + 5]);
    const theirs = peer.raycastFirst(ray, THREE.DoubleSide);
    const ours = bvh.raycastXyz(...random.subarray(6 * k, 6 * k + 6), 0, Infinity);
    if ((theirs === null) !== (ours === null)) continue;
    if (!ours) { same++; continue; }
    hits++;
    if (theirs.faceIndex === ours.triangle || Math.abs(theirs.distance - ours.distance) < 1e-6) same++;
  }
  log(`agreement on ${n} random rays: ${same} identical answers (${hits} hits)`);
  results.push({ workload: 'agreement', rays: n, identical: same });
}

const nRandom = RAYS;
report('random rays, batched vs raycastFirst',
  ...paired(batch(random), () => peerFirstHits(random, nRandom)), nRandom, 'rays');
{
  // three-mesh-bvh's SAH tree (`strategy: SAH`) answers its rays faster than its default one.
  const peerSah = new MeshBVH(sahGeometry, { strategy: SAH });
  report('random rays, batched vs raycastFirst on an SAH tree',
    ...paired(batch(random), () => firstHits(THREE, peerSah, random, nRandom)), nRandom, 'rays');
}
{
  const n = nRandom;
  const distances = new Float32Array(n);
  const triangles = new Uint32Array(n);
  report('random rays, batched on the fast tree vs raycastFirst',
    ...paired(() => fastBvh.raycastBatch(random, 0, Infinity, distances, triangles),
      () => peerFirstHits(random, nRandom)), nRandom, 'rays');
}
{
  // A mesh loaded from a blob decodes its tree for the same fast queries as a built one.
  const n = nRandom;
  const distances = new Float32Array(n);
  const triangles = new Uint32Array(n);
  const fromBlob = meshq.MeshBvh.fromBlob(blob);
  report('random rays, batched on the blob-loaded tree vs raycastFirst',
    ...paired(() => fromBlob.raycastBatch(random, 0, Infinity, distances, triangles),
      () => peerFirstHits(random, nRandom)), nRandom, 'rays');
  fromBlob.free();
}
report('camera rays 1024², batched vs raycastFirst',
  ...paired(batch(camera), () => peerFirstHits(camera, camera.length / 6)), camera.length / 6, 'rays');
{
  // The four-wide tree (`fourWideNodes()`; a BVH walks eight-wide nodes as built or loaded):
  // the same answers, checked here.
  const four = meshq.MeshBvh.fromBlob(blob);
  four.fourWideNodes();
  for (const [name, rays] of [['random rays', random], ['camera rays 1024²', camera]]) {
    const n = rays.length / 6;
    const distances = new Float32Array(n);
    const triangles = new Uint32Array(n);
    const wantT = new Float32Array(n);
    const wantTri = new Uint32Array(n);
    bvh.raycastBatch(rays, 0, Infinity, wantT, wantTri);
    report(`${name}, batched on the four-wide tree vs raycastFirst`,
      ...paired(() => four.raycastBatch(rays, 0, Infinity, distances, triangles),
        () => peerFirstHits(rays, n)), n, 'rays');
    for (let k = 0; k < n; k++) {
      if (triangles[k] !== wantTri[k] || !Object.is(distances[k], wantT[k])) {
        throw new Error(`four-wide tree: ray ${k} differs`);
      }
    }
  }
  four.free();
}

const singleXyz = () => {
  let hits = 0;
  for (let k = 0; k < SINGLE; k++) {
    const o = 6 * k;
    if (bvh.raycastXyz(random[o], random[o + 1], random[o + 2], random[o + 3], random[o + 4], random[o + 5], 0, Infinity) !== null) hits++;
  }
  return hits;
};
const singleArrays = () => {
  let hits = 0;
  const origin = new Float32Array(3);
  const direction = new Float32Array(3);
  // Filled number by number, as the peer's loop fills its THREE.Ray: a `subarray` view per
  // ray would time the allocation of two views in JavaScript, not the call.
  for (let k = 0; k < SINGLE; k++) {
    const o = 6 * k;
    origin[0] = random[o]; origin[1] = random[o + 1]; origin[2] = random[o + 2];
    direction[0] = random[o + 3]; direction[1] = random[o + 4]; direction[2] = random[o + 5];
    if (bvh.raycast(origin, direction, 0, Infinity) !== null) hits++;
  }
  return hits;
};
report('random rays, one call each: raycastXyz',
  ...paired(singleXyz, () => peerFirstHits(random, SINGLE)), SINGLE, 'rays');
report('random rays, one call each: raycast(arrays)',
  ...paired(singleArrays, () => peerFirstHits(random, SINGLE)), SINGLE, 'rays');

const anyBatch = (() => {
  const out = new Uint8Array(RAYS);
  return () => bvh.raycastAnyBatch(random, 0, Infinity, out);
})();
report('random rays, any hit batched vs raycastFirst',
  ...paired(anyBatch, () => peerFirstHits(random, nRandom)), nRandom, 'rays');

const closestBatch = (() => {
  const c = new Float32Array(3 * POINTS);
  const t = new Uint32Array(POINTS);
  const d = new Float32Array(POINTS);
  return () => bvh.closestPointBatch(points, Infinity, c, t, d);
})();
const peerClosest = () => {
  const p = new THREE.Vector3();
  const target = {};
  for (let k = 0; k < POINTS; k++) {
    p.set(points[3 * k], points[3 * k + 1], points[3 * k + 2]);
    peer.closestPointToPoint(p, target);
  }
};
report('closest point, batched vs closestPointToPoint',
  ...paired(closestBatch, peerClosest), POINTS, 'points');

// The worker pool (meshq-wasm/pool): the same batch on 1 worker and on one per core, each
// loading the blob; the answers are checked equal to the single-thread batch first.
{
  const cores = os.availableParallelism();
  const pools = [await MeshqPool.fromBlob(blob, { workers: 1 }), await MeshqPool.fromBlob(blob, { workers: cores })];
  const want = new Uint32Array(RAYS);
  bvh.raycastBatch(random, 0, Infinity, new Float32Array(RAYS), want);
  for (const pool of pools) {
    const got = await pool.raycastBatch(random);
    if (!got.triangles.every((x, i) => x === want[i])) throw new Error(`pool of ${pool.size}: other answers`);
  }
  // Interleaved with three-mesh-bvh's pass, best of 3 rounds after a warm-up round, so
  // machine noise hits both pools and the peer alike.
  let [one, all, peer] = [Infinity, Infinity, Infinity];
  for (let round = 0; round < 4; round++) {
    for (const [k, pool] of pools.entries()) {
      const t0 = performance.now();
      await pool.raycastBatch(random);
      const ms = performance.now() - t0;
      if (round > 0) k === 0 ? (one = Math.min(one, ms)) : (all = Math.min(all, ms));
    }
    const t0 = performance.now();
    peerFirstHits(random, nRandom);
    if (round > 0) peer = Math.min(peer, performance.now() - t0);
  }
  report(`random rays, pool of ${cores} workers vs raycastFirst`, all, peer, nRandom, 'rays');
  log(`pool scaling: ${cores} workers ${(one / all).toFixed(2)}× one worker (${one.toFixed(0)} vs ${all.toFixed(0)} ms)`);
  results.push({ workload: 'pool scaling', workers: cores, one_worker_ms: one, all_workers_ms: all, ratio: one / all });
  for (const pool of pools) pool.terminate();
  // The same pool walking the four-wide tree.
  const four = await MeshqPool.fromBlob(blob, { workers: cores, eightWide: false });
  const got = await four.raycastBatch(random);
  if (!got.triangles.every((x, i) => x === want[i])) throw new Error('four-wide pool: other answers');
  let best = Infinity;
  for (let round = 0; round < 3; round++) {
    const t0 = performance.now();
    await four.raycastBatch(random);
    best = Math.min(best, performance.now() - t0);
  }
  report(`random rays, pool of ${cores} four-wide workers vs raycastFirst`, best, peer, nRandom, 'rays');
  four.terminate();
}

if (json) console.log(JSON.stringify({ triangles: index.length / 3, results }, null, 2));
bvh.free();
fastBvh.free();
