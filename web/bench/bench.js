// meshq (WebAssembly) against three-mesh-bvh in the browser that opens this page, on one
// mesh, with the rays and points of the Node benchmark (bench/node/bench.mjs): the same
// workloads, the same pairing of rounds, the same ratios (three-mesh-bvh's time / meshq's).
//
// bench/browser/bench.mjs drives it in headless Chromium (`?driven`: it hands over the mesh and
// the counts through `window.meshqBench.run`). Opened by hand it loads the demo's bunny blob
// (web/assets/bunny.meshq, from scripts/build-web.sh) and prints the table (`?rays=`,
// `?points=`, `?rounds=` for other counts).
import * as THREE from 'three';
import { MeshBVH, SAH } from 'three-mesh-bvh';
import init, { MeshBvh, cameraRays, queryPoints, randomRays } from 'meshq-wasm';
import { MeshqPool } from 'meshq-wasm/pool';
import { median, paired, pairedAsync, peerFirstHits } from './timing.js';

const log = document.getElementById('log');

/**
 * Runs every workload on the mesh `positions` / `index` (typed arrays) with `rays` random rays
 * and `points` closest-point queries; resolves to `{ userAgent, triangles, rows }`, each row
 * `{ workload, meshq_ms, three_mesh_bvh_ms?, ratio?, meshq_per_s?, three_mesh_bvh_per_s? }`.
 */
async function run(positions, index, { rays = 1_000_000, points = 100_000, rounds = 5 } = {}) {
  await init();
  const rows = [];
  const lines = [];
  const report = (workload, ours, theirs, count, unit) => {
    const row = { workload, meshq_ms: ours, three_mesh_bvh_ms: theirs, ratio: theirs / ours };
    let rate = '';
    if (count) {
      row.meshq_per_s = (count / ours) * 1000;
      row.three_mesh_bvh_per_s = (count / theirs) * 1000;
      rate = `  (${(row.meshq_per_s / 1e6).toFixed(2)} vs ${(row.three_mesh_bvh_per_s / 1e6).toFixed(2)} M ${unit}/s)`;
    }
    rows.push(row);
    lines.push(`${workload.padEnd(52)} ${row.ratio.toFixed(2)}×${rate}`);
    log.textContent = lines.join('\n');
  };

  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  let bvh = null;
  const buildOurs = median(() => { bvh?.free(); bvh = MeshBvh.build(positions, index); }, 5);
  const buildTheirs = median(() => new MeshBVH(geometry), 5);
  report('build (default settings)', buildOurs, buildTheirs);
  const peer = new MeshBVH(geometry);
  // three-mesh-bvh reorders the index it builds over: its SAH tree gets its own copy.
  const sahGeometry = geometry.clone();
  const peerSah = new MeshBVH(sahGeometry, { strategy: SAH });

  const blob = bvh.toBlob();
  for (let i = 0; i < 30; i++) MeshBvh.fromBlob(blob).free();
  const load = median(() => MeshBvh.fromBlob(blob).free(), 21);
  rows.push({ workload: 'meshq fromBlob load', meshq_ms: load });
  lines.push(`meshq fromBlob (validated load of a ${blob.length}-byte blob): ${load.toFixed(1)} ms`);

  const bounds = bvh.bounds();
  const random = randomRays(bounds, 1, rays);
  const camera = cameraRays(bounds, 1024, 1024);
  const queries = queryPoints(bounds, 1, points);

  // Agreement first: the same triangle, or the same distance (a tie), on the random rays.
  {
    const n = Math.min(rays, 100_000);
    const ray = new THREE.Ray();
    let same = 0;
    for (let k = 0; k < n; k++) {
      ray.origin.fromArray(random, 6 * k);
      ray.direction.fromArray(random, 6 * k + 3);
      const theirs = peer.raycastFirst(ray, THREE.DoubleSide);
      const ours = bvh.raycastXyz(...random.subarray(6 * k, 6 * k + 6), 0, Infinity);
      if ((theirs === null) !== (ours === null)) continue;
      if (ours === null || theirs.faceIndex === ours.triangle
        || Math.abs(theirs.distance - ours.distance) <= 1e-6 * Math.max(1, ours.distance)) same++;
    }
    rows.push({ workload: 'agreement', rays: n, identical: same });
    lines.push(`agreement on ${n} random rays: ${same} the same answer`);
  }

  const batch = (tree, input) => {
    const n = input.length / 6;
    const t = new Float32Array(n);
    const tri = new Uint32Array(n);
    return () => tree.raycastBatch(input, 0, Infinity, t, tri);
  };
  const nRandom = random.length / 6;
  const nCamera = camera.length / 6;
  report('random rays, batched vs raycastFirst',
    ...paired(batch(bvh, random), () => peerFirstHits(THREE, peer, random, nRandom), rounds), nRandom, 'rays');
  report('random rays, batched vs raycastFirst on an SAH tree',
    ...paired(batch(bvh, random), () => peerFirstHits(THREE, peerSah, random, nRandom), rounds), nRandom, 'rays');
  {
    const loaded = MeshBvh.fromBlob(blob);
    report('random rays, batched on the blob-loaded tree vs raycastFirst',
      ...paired(batch(loaded, random), () => peerFirstHits(THREE, peer, random, nRandom), rounds), nRandom, 'rays');
    loaded.free();
  }
  report('camera rays 1024², batched vs raycastFirst',
    ...paired(batch(bvh, camera), () => peerFirstHits(THREE, peer, camera, nCamera), rounds), nCamera, 'rays');
  {
    const hit = new Uint8Array(nRandom);
    report('random rays, any hit batched vs raycastFirst',
      ...paired(() => bvh.raycastAnyBatch(random, 0, Infinity, hit),
        () => peerFirstHits(THREE, peer, random, nRandom), rounds), nRandom, 'rays');
  }
  {
    const n = queries.length / 3;
    const closest = new Float32Array(3 * n);
    const tri = new Uint32Array(n);
    const distance = new Float32Array(n);
    const p = new THREE.Vector3();
    const target = {};
    report('closest point, batched vs closestPointToPoint',
      ...paired(() => bvh.closestPointBatch(queries, Infinity, closest, tri, distance), () => {
        for (let k = 0; k < n; k++) peer.closestPointToPoint(p.fromArray(queries, 3 * k), target);
      }, rounds), n, 'points');
  }
  {
    // Every core: the worker pool, each worker holding the blob (shared memory where the page
    // is cross-origin isolated, as the runner serves it), against the peer on this thread.
    const pool = await MeshqPool.fromBlob(blob);
    // Its answers are the single-thread batch's, bit for bit, before it is timed.
    const wantT = new Float32Array(nRandom);
    const wantTri = new Uint32Array(nRandom);
    bvh.raycastBatch(random, 0, Infinity, wantT, wantTri);
    const got = await pool.raycastBatch(random, 0, Infinity);
    if (!got.triangles.every((x, k) => x === wantTri[k] && Object.is(got.t[k], wantT[k]))) {
      throw new Error(`pool of ${pool.size}: other answers than one thread's`);
    }
    const [ours, theirs] = await pairedAsync(() => pool.raycastBatch(random, 0, Infinity),
      () => peerFirstHits(THREE, peer, random, nRandom), rounds);
    report(`random rays, pool of ${pool.size} workers${pool.shared ? ' (shared memory)' : ''} vs raycastFirst`,
      ours, theirs, nRandom, 'rays');
    pool.terminate();
  }
  bvh.free();
  return { userAgent: navigator.userAgent, triangles: index.length / 3, rows };
}

window.meshqBench = { run };

const query = new URLSearchParams(location.search);
if (!query.has('driven')) {
  const bytes = new Uint8Array(await (await fetch('../assets/bunny.meshq')).arrayBuffer());
  await init();
  const loaded = MeshBvh.fromBlob(bytes);
  const positions = loaded.vertexPositions();
  const index = loaded.indices();
  loaded.free();
  // `?rays=N&points=N&rounds=N` for other counts.
  const counts = Object.fromEntries(['rays', 'points', 'rounds']
    .filter((k) => query.has(k)).map((k) => [k, Number(query.get(k))]));
  await run(positions, index, counts);
  log.textContent += '\ndone';
}
