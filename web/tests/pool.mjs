// meshq-wasm/pool in Node (worker_threads): pools of 1, 2 and 3 workers, with memory shared (the
// workers taking pieces of a batch as they go) and copied (an equal share each), answer the
// bunny's DESIGN.md workloads exactly as the single-thread batch calls do (the same bits),
// batches smaller than the pool and batches of odd sizes included; bad input is refused with the
// error the single-thread call gives; a damaged blob rejects the pool; a terminated pool
// rejects. Run after scripts/build-web.sh: node web/tests/pool.mjs
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { MeshBvh, queryPoints, randomRays, cameraRays } from 'meshq-wasm';
import { MeshqPool } from 'meshq-wasm/pool';

const root = fileURLToPath(new URL('../..', import.meta.url));
const blob = readFileSync(`${root}/web/assets/bunny.meshq`);
const bvh = MeshBvh.fromBlob(blob);
const bounds = bvh.bounds();
const rays = new Float32Array([...randomRays(bounds, 3, 50_000), ...cameraRays(bounds, 64, 64)]);
const n = rays.length / 6;
const points = queryPoints(bounds, 4, 20_000);
const m = points.length / 3;

// The single-thread answers.
const t = new Float32Array(n);
const triangles = new Uint32Array(n);
const hits = bvh.raycastBatch(rays, 0, Infinity, t, triangles);
const any = new Uint8Array(n);
const anyCount = bvh.raycastAnyBatch(rays, 0, Infinity, any);
const closest = new Float32Array(3 * m);
const closestTriangles = new Uint32Array(m);
const distances = new Float32Array(m);
const found = bvh.closestPointBatch(points, 0.05, closest, closestTriangles, distances);
const bits = (a) => new Uint32Array(a.buffer, a.byteOffset, a.length);
assert.ok(hits > n / 4 && found > 0 && found < m, 'the workloads hit and miss');

for (const shared of [true, false]) {
  for (const workers of [1, 2, 3]) {
    const pool = await MeshqPool.fromBlob(blob, { workers, shared });
    assert.equal(pool.size, workers);
    assert.equal(pool.shared, shared);
    const what = `${workers} workers, ${shared ? 'shared' : 'copied'}`;
    const r = await pool.raycastBatch(rays);
    assert.equal(r.hits, hits, what);
    assert.deepEqual(bits(r.t), bits(t), `${what}: t bits`);
    assert.deepEqual(r.triangles, triangles, `${what}: triangles`);
    const a = await pool.raycastAnyBatch(rays, 0, Infinity);
    assert.equal(a.count, anyCount, what);
    assert.deepEqual(a.hits, any, `${what}: any hit`);
    const c = await pool.closestPointBatch(points, 0.05);
    assert.equal(c.found, found, what);
    assert.deepEqual(bits(c.closest), bits(closest), `${what}: closest points`);
    assert.deepEqual(c.triangles, closestTriangles, what);
    assert.deepEqual(bits(c.distances), bits(distances), what);
    // A batch whose last piece is not whole packets: each ray's answer is its answer in the
    // full batch.
    const odd = await pool.raycastBatch(rays.subarray(0, 6 * (n - 3)));
    assert.deepEqual(bits(odd.t), bits(t.subarray(0, n - 3)), `${what}: ${n - 3} rays`);
    assert.deepEqual(odd.triangles, triangles.subarray(0, n - 3), `${what}: ${n - 3} rays`);
    // Fewer queries than workers, and none at all.
    const two = await pool.raycastBatch(rays.subarray(0, 12), 0, 10, 2);
    const t2 = new Float32Array(2);
    const tri2 = new Uint32Array(2);
    bvh.raycastBatch(rays.subarray(0, 12), 0, 10, t2, tri2, 2);
    assert.deepEqual([...bits(two.t), ...two.triangles], [...bits(t2), ...tri2], `${what}: two rays`);
    assert.equal((await pool.raycastBatch(new Float32Array(0))).hits, 0);
    // Bad input: the single-thread call's errors.
    await assert.rejects(pool.raycastBatch([0, 0, 0, 0, 0, 1]), TypeError);
    await assert.rejects(pool.raycastBatch(rays.subarray(0, 7)), RangeError);
    await assert.rejects(pool.raycastBatch(rays, 2, 1), /near .* must not exceed far/);
    await assert.rejects(pool.closestPointBatch(points, -1), RangeError);
    // Still answering after errors.
    assert.equal((await pool.raycastBatch(rays)).hits, hits);
    // Two batches at once share the workers; terminating rejects a batch still running.
    const [x, y] = await Promise.all([pool.raycastBatch(rays), pool.raycastAnyBatch(rays)]);
    assert.equal(x.hits, hits, `${what}: concurrent batches`);
    assert.equal(y.count, anyCount, `${what}: concurrent batches`);
    const running = pool.raycastBatch(rays);
    pool.terminate();
    await assert.rejects(running, /terminated/);
    await assert.rejects(pool.raycastBatch(rays), /terminated/);
  }
}

// Four-wide workers (a loaded BVH walks eight-wide nodes): the same answers.
{
  const pool = await MeshqPool.fromBlob(blob, { workers: 2, eightWide: false });
  const r = await pool.raycastBatch(rays);
  assert.equal(r.hits, hits, 'four-wide workers');
  assert.deepEqual(bits(r.t), bits(t), 'four-wide workers: t bits');
  assert.deepEqual(r.triangles, triangles, 'four-wide workers: triangles');
  const a = await pool.raycastAnyBatch(rays, 0, Infinity);
  assert.deepEqual(a.hits, any, 'four-wide workers: any hit');
  const c = await pool.closestPointBatch(points, 0.05);
  assert.deepEqual(bits(c.distances), bits(distances), 'four-wide workers: closest points');
  assert.deepEqual(c.triangles, closestTriangles, 'four-wide workers: closest triangles');
  pool.terminate();
}
await assert.rejects(MeshqPool.fromBlob(blob, { workers: 1, eightWide: 'yes' }), TypeError);

const damaged = Uint8Array.from(blob);
damaged[damaged.length - 5] ^= 1;
await assert.rejects(MeshqPool.fromBlob(damaged, { workers: 2 }), /checksum|blob/);
await assert.rejects(MeshqPool.fromBlob([1, 2, 3]), TypeError);
bvh.free();
console.log(`pool: ${n} rays and ${m} points on 1-3 workers, shared and copied, equal to one thread bit for bit`);
