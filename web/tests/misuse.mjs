// The Node package under misuse: every query with missing, wrong-typed, NaN and out-of-range
// arguments throws a TypeError or RangeError naming the argument (or takes the documented
// default), leaves output arrays untouched and nothing borrowed, and 10,000 misuse calls in a
// row leave the module answering correctly. Run after scripts/build-web.sh: node web/tests/misuse.mjs
import assert from 'node:assert/strict';
import * as meshq from 'meshq-wasm';

const { MeshBvh, randomRays, cameraRays, queryPoints, remesh, geometry } = meshq;

// A bumpy 40 × 40 grid of quads in the z = 0 plane, seen from +z.
function grid(n) {
  const positions = new Float32Array((n + 1) * (n + 1) * 3);
  let k = 0;
  for (let i = 0; i <= n; i++) {
    for (let j = 0; j <= n; j++) positions.set([i / n, j / n, 0.02 * Math.sin(i) * Math.cos(j)], 3 * k++);
  }
  const indices = new Uint32Array(n * n * 6);
  k = 0;
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < n; j++) {
      const a = i * (n + 1) + j;
      indices.set([a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2], k);
      k += 6;
    }
  }
  return { positions, indices };
}

const { positions, indices } = grid(40);
const bvh = MeshBvh.build(positions, indices);
const down = [0, 0, -1];
const above = [0.3, 0.6, 1];
const reference = bvh.raycast(above, down);
assert.ok(reference, 'the reference ray hits');

/** Asserts `f` throws an error of `type` whose message mentions `words`. */
function throws(f, type, words, label) {
  let error = null;
  try {
    f();
  } catch (e) {
    error = e;
  }
  assert.ok(error, `${label}: no error`);
  assert.ok(error instanceof type, `${label}: ${error?.constructor?.name}: ${error?.message}`);
  assert.match(error.message, words, label);
}

// A RayOptions object in place of the side: the same side, and the triangle test; every test
// answers a ray through the middle of a triangle alike (the reference ray meets a grid corner,
// where the non-watertight tests may slip through).
assert.deepEqual(bvh.raycast(above, down, 0, Infinity, { side: 0 }), bvh.raycast(above, down, 0, Infinity, 0));
assert.deepEqual(bvh.raycast(above, down, 0, Infinity, {}), reference);
{
  const inside = [0.3 + 0.3 / 40, 0.6 + 0.6 / 40, 1];
  const want = bvh.raycast(inside, down);
  for (const test of ['watertight', 'moller-trumbore', 'two-step']) {
    const hit = bvh.raycast(inside, down, null, null, { test });
    assert.equal(hit.triangle, want.triangle, test);
    assert.ok(Math.abs(hit.t - want.t) <= 1e-6, `${test}: t ${hit.t} vs ${want.t}`);
    assert.equal(bvh.raycastAny(inside, down, null, null, { test, side: 2 }), true);
    assert.equal(bvh.raycastAll(inside, down, null, null, { test })[0].triangle, want.triangle);
  }
}

// Documented defaults: near/far omitted → [0, ∞]; the same ray given as arrays, typed arrays
// or Vector3-like objects; side omitted → both faces; maxDistance omitted → no limit, in the
// single call and the batch alike.
assert.deepEqual(bvh.raycast(above, down, 0, Infinity), reference);
assert.deepEqual(bvh.raycast(Float32Array.from(above), { x: 0, y: 0, z: -1 }), reference);
assert.deepEqual(bvh.raycast({ x: 0.3, y: 0.6, z: 1 }, down, undefined, undefined, undefined), reference);
assert.deepEqual(bvh.raycastXyz(0.3, 0.6, 1, 0, 0, -1), reference);
assert.equal(bvh.raycastAny(above, down), true);
const far = bvh.closestPoint([5, 5, 5]);
assert.ok(far && far.distance > 5, 'no limit when maxDistance is omitted');
{
  const points = Float32Array.from([5, 5, 5, 0.5, 0.5, 1]);
  const closest = new Float32Array(6);
  const triangles = new Uint32Array(2);
  const distances = new Float32Array(2);
  assert.equal(bvh.closestPointBatch(points, undefined, closest, triangles, distances), 2, 'batch: no limit either');
  assert.equal(distances[0], Math.fround(far.distance));
}
assert.equal(MeshBvh.MISS_TRIANGLE, 0xFFFFFFFF);
assert.equal(MeshBvh.MISS_DISTANCE, Infinity);
assert.equal(MeshBvh.MISS_T, Infinity);

// One word, one meaning: `t` is the ray parameter, `distance` Euclidean, in every result.
{
  const long = bvh.raycast(above, [0, 0, -2]);
  assert.equal(long.triangle, reference.triangle);
  assert.equal(long.t, Math.fround(reference.t / 2), 't is in units of the direction');
  assert.equal(long.distance, long.t * 2, 'distance = t·|direction|');
  assert.equal(reference.distance, reference.t, 'a unit direction: distance = t');
  assert.deepEqual(Object.keys(reference).sort(), ['distance', 'normal', 'point', 't', 'triangle', 'u', 'v']);
  assert.deepEqual(Object.keys(far).sort(), ['distance', 'normal', 'point', 'triangle', 'u', 'v']);
  // The reference ray passes through a grid vertex: every triangle around it is hit, once,
  // lower index first on the equal t.
  const all = bvh.raycastAll(above, down);
  assert.deepEqual(all[0], reference, 'raycastAll: the same objects, same defaults');
  assert.ok(all.length > 1 && all.every((h, i) => i === 0 || (h.t >= all[i - 1].t && h.triangle > all[i - 1].triangle)));
  assert.deepEqual(bvh.raycastAll({ x: 0.3, y: 0.6, z: 1 }, Float64Array.from(down), null, null, null), all);
}

// Other documented defaults: options omitted or null, a matrix as 16 numbers or a Matrix4.
{
  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const shifted = [...identity.slice(0, 12), 0.25, 0, 0, 1];
  const other = MeshBvh.build(positions, indices, null);
  assert.equal(bvh.intersectsMesh(other), true);
  const a = bvh.intersectingPairs(other, shifted);
  const b = bvh.intersectingPairs(other, { elements: Float64Array.from(shifted) }, null);
  assert.deepEqual(a, b, 'a Matrix4-like object = its elements');
  assert.ok(a.total > 0);
  assert.equal(bvh.intersectingPairs(other, shifted, 2).pairs.length, 4, 'maxPairs caps');
  assert.deepEqual(MeshBvh.build(positions, indices, { quality: undefined, structure: null }).toBlob(), bvh.toBlob());
  // Spatial splits off (false, null) is the ordinary build; on, the same answers.
  assert.deepEqual(MeshBvh.build(positions, indices, { spatialSplits: false }).toBlob(), bvh.toBlob());
  const split = MeshBvh.build(positions, indices, { spatialSplits: 0.5 });
  const splitBack = MeshBvh.fromBlob(split.toBlob());
  for (const [o, d] of [[[0.1, 0.2, 5], [0, 0, -1]], [[0.3, -2, 0.2], [0, 1, 0]], [above, down]]) {
    assert.deepEqual(split.raycast(o, d), bvh.raycast(o, d));
    assert.deepEqual(splitBack.raycast(o, d), bvh.raycast(o, d));
  }
  split.free();
  splitBack.free();
  // Sweep SAH (true: every 32 triangles; a number: that step): the same answers, read back
  // from its blob; off (false) is the ordinary build.
  assert.deepEqual(MeshBvh.build(positions, indices, { sweepSah: false }).toBlob(), bvh.toBlob());
  for (const sweepSah of [true, 1, 5]) {
    const swept = MeshBvh.build(positions, indices, { sweepSah });
    const sweptBack = MeshBvh.fromBlob(swept.toBlob());
    for (const [o, d] of [[[0.1, 0.2, 5], [0, 0, -1]], [[0.3, -2, 0.2], [0, 1, 0]], [above, down]]) {
      assert.deepEqual(swept.raycast(o, d), bvh.raycast(o, d));
      assert.deepEqual(sweptBack.raycast(o, d), bvh.raycast(o, d));
    }
    swept.free();
    sweptBack.free();
  }
  assert.deepEqual(MeshBvh.fromBlob(bvh.toBlob()).toBlob(), bvh.toBlob(), 'toBlob on a loaded blob');
  assert.deepEqual(MeshBvh.fromBlob(bvh.toBlob()).toBlob('packed'), bvh.toBlob('packed'));
  // With the winding-number expansions (format version 6, 112 bytes per node): a load keeps
  // them and answers as the built mesh; without asking, a fresh BVH's blob holds none.
  {
    const fresh = MeshBvh.build(positions, indices);
    const plain = fresh.toBlob();
    const withWinding = fresh.toBlob(null, true);
    assert.equal(withWinding[4], 6, 'format version 6');
    assert.ok(withWinding.length > plain.length);
    const loaded = MeshBvh.fromBlob(withWinding);
    for (const p of [[0.25, 0.5, 0.1], [3, 3, 3], above]) {
      assert.equal(loaded.windingNumber(p), fresh.windingNumber(p));
      assert.deepEqual(loaded.signedDistance(p), fresh.signedDistance(p));
    }
    assert.deepEqual(loaded.toBlob(null, true), withWinding, 'kept as loaded');
    fresh.free();
    loaded.free();
  }
  // Built or loaded, a BVH walks eight-wide nodes (256 bytes each); four-wide ones are 128
  // bytes each, compact ones half of those; each the same blob and answers; twice is once. The
  // planned eight-wide tree can take fewer bytes in all than the four-wide one (here 26,880
  // against 30,464), so only the change of tree is checked here; wasm/tests/parity.rs checks
  // the four-wide size against the core's own collapse.
  const compact = MeshBvh.fromBlob(bvh.toBlob());
  const eightBytes = compact.queryNodeBytes;
  assert.equal(eightBytes % 256, 0, 'eight-wide nodes by default');
  assert.equal(bvh.queryNodeBytes, eightBytes, 'built and loaded walk the same nodes');
  compact.fourWideNodes();
  compact.fourWideNodes();
  const fullBytes = compact.queryNodeBytes;
  assert.equal(fullBytes % 128, 0, 'four-wide nodes are 128 bytes');
  assert.notEqual(fullBytes, eightBytes, 'four-wide nodes walked instead of eight-wide ones');
  assert.deepEqual(compact.raycast([0.3, -2, 0.2], [0, 1, 0]), bvh.raycast([0.3, -2, 0.2], [0, 1, 0]));
  compact.compactNodes();
  compact.compactNodes();
  assert.equal(compact.queryNodeBytes * 2, fullBytes, 'compact nodes are half the bytes');
  assert.deepEqual(compact.toBlob('packed'), bvh.toBlob('packed'));
  assert.deepEqual(compact.raycast([0.1, 0.2, 5], [0, 0, -1]), bvh.raycast([0.1, 0.2, 5], [0, 0, -1]));
  // Eight-wide nodes again after four-wide: 256 bytes each, the same blob and answers; twice
  // is once; then compact.
  const eight = MeshBvh.fromBlob(bvh.toBlob());
  eight.fourWideNodes();
  eight.eightWideNodes();
  eight.eightWideNodes();
  assert.equal(eight.queryNodeBytes, eightBytes, 'eight-wide nodes are 256 bytes');
  assert.deepEqual(eight.toBlob(), bvh.toBlob());
  for (const [o, d] of [[[0.1, 0.2, 5], [0, 0, -1]], [[0.3, -2, 0.2], [0, 1, 0]]]) {
    assert.deepEqual(eight.raycast(o, d), bvh.raycast(o, d));
  }
  eight.compactNodes();
  assert.equal(eight.queryNodeBytes, compact.queryNodeBytes, 'eight-wide then compact');
  eight.free();
  compact.free();
  other.free();
}

// Bad single-query arguments. Number arguments (near, far, side) must be numbers: a string, a
// boolean or null where a number is required is a TypeError, never converted (the batch calls
// refuse the same values). raycastXyz alone takes plain numbers JavaScript converts, as
// documented: what converts to NaN is a RangeError.
const cases = [
  [() => bvh.raycast(), TypeError, /origin/],
  [() => bvh.raycast(above), TypeError, /direction/],
  [() => bvh.raycast([0, 0], down), RangeError, /origin must hold exactly 3/],
  [() => bvh.raycast([NaN, 0, 1], down), RangeError, /origin\.x must be a finite/],
  [() => bvh.raycast(above, [0, 0, 0]), RangeError, /direction must not be zero/],
  [() => bvh.raycast(above, ['a', 0, -1]), TypeError, /direction\.x must be a number/],
  [() => bvh.raycast(above, down, NaN), RangeError, /near/],
  [() => bvh.raycast(above, down, 0, 'far'), TypeError, /far must be a number, got string/],
  [() => bvh.raycast(above, down, '1'), TypeError, /near must be a number, got string/],
  [() => bvh.raycast(above, down, 0, Infinity, true), TypeError, /side must be a number, got boolean/],
  [() => bvh.raycast(above, down, 2, 1), RangeError, /near .* must not exceed far/],
  [() => bvh.raycast(above, down, 0, Infinity, 256), RangeError, /side/],
  [() => bvh.raycast(above, down, 0, Infinity, 1.5), RangeError, /side/],
  [() => bvh.raycast(above, down, 0, Infinity, 'front'), TypeError, /side/],
  [() => bvh.raycastXyz(0.3, 0.6, 1, 0, 0), RangeError, /dz must be a finite number, got NaN/],
  [() => bvh.raycastXyz('a', 0.6, 1, 0, 0, -1), RangeError, /ox must be a finite number, got NaN/],
  [() => bvh.raycastAny(above, down, 0, Infinity, '2'), TypeError, /side/],
  [() => bvh.raycastXyz(0.3, 0.6, Infinity, 0, 0, -1), RangeError, /oz/],
  [() => bvh.raycastAll(0.3, NaN, 1, 0, 0, -1), TypeError, /origin must be \[x, y, z\]/],
  [() => bvh.raycastAll(above), TypeError, /direction/],
  [() => bvh.raycastAll(above, down, 0, Infinity, 9), RangeError, /side/],
  [() => bvh.raycastAny(), TypeError, /origin/],
  [() => bvh.raycastAny(above, 'down'), TypeError, /direction/],
  [() => bvh.closestPoint(), TypeError, /point/],
  [() => bvh.closestPoint([0, 0, 0], -1), RangeError, /maxDistance/],
  [() => bvh.closestPoint([0, 0, 0], NaN), RangeError, /maxDistance/],
  [() => bvh.closestPoint([0, 0, 0], '1'), TypeError, /maxDistance/],
  [() => bvh.overlapsSphere([0, 0, 0], NaN), RangeError, /radius/],
  [() => bvh.overlapsTriangle([0, 0, 0], [1, 0, 0]), TypeError, /c must be/],
  [() => MeshBvh.fromBlob([1, 2, 3]), TypeError, /Uint8Array/],
  [() => MeshBvh.fromBlob(new Uint8Array([1, 2, 3])), Error, /blob/],
  [() => MeshBvh.build('positions'), TypeError, /positions/],
  [() => MeshBvh.build(), TypeError, /positions/],
  [() => MeshBvh.build(positions, 'indices'), TypeError, /indices must be/],
  [() => MeshBvh.build(positions, [0, 1, 2.5]), RangeError, /indices\[2\] must be a whole number/],
  [() => MeshBvh.build(positions, [0, 1, 'x']), TypeError, /indices\[2\] must be a number/],
  [() => MeshBvh.build(positions, indices, 'fast'), TypeError, /options must be an object/],
  [() => MeshBvh.build(positions, indices, { maxLeafTris: 4 }), RangeError, /unknown option "maxLeafTris"/],
  [() => MeshBvh.build(positions, indices, { quality: 5 }), TypeError, /options.quality must be a string/],
  [() => MeshBvh.build(positions, indices, { quality: 'best' }), RangeError, /options.quality must be one of/],
  [() => MeshBvh.build(positions, indices, { structure: 'tree' }), RangeError, /options.structure must be one of/],
  [() => MeshBvh.build(positions, indices, { maxLeafSize: '4' }), TypeError, /options.maxLeafSize must be a number/],
  [() => MeshBvh.build(positions, indices, { bins: NaN }), RangeError, /options.bins must be a number, got NaN/],
  [() => MeshBvh.build(positions, indices, { maxDepth: 2.5 }), RangeError, /options.maxDepth must be a whole number/],
  [() => MeshBvh.build(positions, indices, { maxLeafSize: 0 }), RangeError, /options.maxLeafSize must be in 1..=\d+, got 0/],
  [() => MeshBvh.build(positions, indices, { spatialSplits: 'yes' }), TypeError, /options.spatialSplits must be a boolean or a number/],
  // Numbers are echoed as JavaScript writes them.
  [() => MeshBvh.build(positions, indices, { spatialSplits: Infinity }), RangeError, /options.spatialSplits .* got Infinity$/],
  [() => MeshBvh.build(positions, indices, { spatialSplits: -1e30 }), RangeError, /got -1e\+30$/],
  [() => bvh.raycastXyz(0.3, 0.6, -Infinity, 0, 0, -1), RangeError, /oz must be a finite number, got -Infinity$/],
  [() => bvh.raycast(above, down, 0, Infinity, 0.5), RangeError, /side .* got 0\.5$/],
  [() => MeshBvh.build(positions, indices, { spatialSplits: 5 }), RangeError, /options.spatialSplits must be true, false or a number in 0..=4, got 5/],
  [() => MeshBvh.build(positions, indices, { spatialSplits: -1 }), RangeError, /options.spatialSplits must be/],
  [() => MeshBvh.build(positions, indices, { spatialSplits: true, structure: 'grid' }), TypeError, /options.spatialSplits applies to the BVH/],
  [() => MeshBvh.build(positions, indices, { sweepSah: 'yes' }), TypeError, /options.sweepSah must be a boolean or a number/],
  [() => MeshBvh.build(positions, indices, { sweepSah: 0 }), RangeError, /options.sweepSah must be true, false or a whole number of triangles in 1..=\d+, got 0$/],
  [() => MeshBvh.build(positions, indices, { sweepSah: 2.5 }), RangeError, /options.sweepSah .* got 2.5$/],
  [() => MeshBvh.build(positions, indices, { sweepSah: true, spatialSplits: true }), TypeError, /options.sweepSah and options.spatialSplits do not go together/],
  [() => MeshBvh.build(positions, indices, { sweepSah: 8, structure: 'kdtree' }), TypeError, /options.sweepSah applies to the BVH/],
  [() => bvh.toBlob(5), TypeError, /layout must be a string/],
  [() => bvh.toBlob('zip'), RangeError, /layout must be one of "indexed", "packed", "omitted"/],
  [() => bvh.toBlob(null, 'yes'), TypeError, /winding must be a boolean, got/],
  [() => MeshBvh.build(positions, indices, { structure: 'octree' }).toBlob(null, true), TypeError, /winding applies to a BVH/],
  [() => bvh.levelBoxes(), TypeError, /level must be a whole number/],
  [() => bvh.levelBoxes('1'), TypeError, /level must be a number/],
  [() => bvh.levelBoxes(-1), RangeError, /level must be a whole number/],
  [() => bvh.closestPointBatch(Float32Array.from([0, 0, 0]), 'far', new Float32Array(3), new Uint32Array(1), new Float32Array(1)), TypeError, /maxDistance/],
  [() => bvh.intersectsMesh(), Error, /MeshBvh/],
  [() => bvh.intersectsMesh(bvh, 'identity'), TypeError, /matrix must be an array or typed array/],
  [() => bvh.intersectsMesh(bvh, [1, 0, 0]), RangeError, /matrix must hold exactly 16 numbers, got 3/],
  [() => bvh.intersectsMesh(bvh, { elements: new Array(16).fill(NaN) }), RangeError, /matrix\[0\] must be a finite number/],
  [() => bvh.intersectsMesh(bvh, { rows: 4 }), TypeError, /matrix must be 16 numbers .* or a Matrix4/],
  [() => bvh.intersectsMesh(bvh, [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]), RangeError, /matrix: .*bottom row/],
  [() => bvh.intersectingPairs(bvh, null, 'all'), TypeError, /maxPairs must be a number/],
  [() => bvh.intersectingPairs(bvh, null, -3), RangeError, /maxPairs must be a whole number/],
  [() => bvh.intersectionSegments(bvh, [0]), RangeError, /matrix must hold exactly 16/],
  [() => bvh.selfIntersections(0.5), RangeError, /maxPairs must be a whole number/],
  [() => bvh.selfIntersections(null, 'many'), TypeError, /maxTests must be a number/],
  [() => bvh.intersectsMesh(bvh, null, -1), RangeError, /maxTests must be a whole number/],
  [() => bvh.intersectsMesh(bvh, null, 10), RangeError, /budget of 10 pairs is spent.*maxTests/],
  [() => bvh.intersectionSegments(bvh, null, 10), RangeError, /budget of 10 pairs is spent/],
  [() => bvh.overlapsSphere([0, 0, 0]), TypeError, /radius must be a number/],
  [() => bvh.overlapsSphere([0, 0, 0], -1), RangeError, /radius must be a finite number >= 0, got -1/],
  [() => MeshBvh.build(positions, indices, new Map([['structure', 'grid']])), TypeError, /options must be an object, got Map/],
  [() => MeshBvh.build(positions, indices, { get structure() { throw new SyntaxError('from the getter'); } }), SyntaxError, /from the getter/],
  [() => remesh(positions, indices, { get iterations() { throw new SyntaxError('from the getter'); } }), SyntaxError, /from the getter/],
  [() => bvh.overlapsOrientedBox([0, 0, 0], [1, 0, 0, 0, 1, 0, 0, 0], [1, 1, 1]), RangeError, /axes must hold exactly 9 numbers, got 8/],
  [() => bvh.overlapsOrientedBox([0, 0, 0], 'xyz', [1, 1, 1]), TypeError, /axes must be an array/],
  [() => bvh.overlapsOrientedBox([0, 0, 0], [1, 0, 0, 0, 1, 0, 0, 0, 1]), TypeError, /halfExtents/],
  [() => randomRays(bvh.bounds(), 1), TypeError, /count must be a whole number/],
  [() => randomRays(bvh.bounds(), 'one', 10), TypeError, /seed must be a number/],
  [() => randomRays(bvh.bounds(), -1, 10), RangeError, /seed must be a whole number/],
  [() => randomRays([0, 0, 0], 1, 10), RangeError, /bounds must hold exactly 6 numbers, got 3/],
  [() => randomRays(bvh.bounds(), 1, 1e9), RangeError, /count: .* more than 1 GiB/],
  [() => cameraRays(bvh.bounds(), 64), TypeError, /height must be a whole number/],
  [() => cameraRays(bvh.bounds(), 64.5, 64), RangeError, /width must be a whole number/],
  [() => queryPoints('bounds', 1, 10), TypeError, /bounds must be an array/],
  [() => remesh(), TypeError, /positions/],
  [() => remesh(positions, indices, { targetRatio: 0 }), RangeError, /options.targetRatio must be a positive finite number/],
  [() => remesh(positions, indices, { targetRatio: 1, targetLength: 0.1 }), RangeError, /not both/],
  [() => remesh(positions, indices, { iterations: 1.5 }), RangeError, /options.iterations must be a whole number/],
  [() => remesh(positions, indices, { featureAngle: 'sharp' }), TypeError, /options.featureAngle must be a number/],
  [() => remesh(positions, indices, { steps: 3 }), RangeError, /unknown option "steps"/],
  [() => remesh(positions, indices, 10), TypeError, /options must be an object/],
  [() => remesh(positions, indices, { maxDistanceTests: -1 }), RangeError, /options.maxDistanceTests must be a whole number/],
  [() => remesh(positions, indices, { maxDistanceTests: '5' }), TypeError, /options.maxDistanceTests must be a number/],
  [() => MeshBvh.build(positions, indices, { structure: 'kdtree' }).compactNodes(), TypeError, /compactNodes applies to a BVH/],
  [() => bvh.raycast(above, down, 0, Infinity, { test: 'fast' }), RangeError, /test must be one of "watertight", "moller-trumbore", "two-step", got "fast"/],
  [() => bvh.raycast(above, down, 0, Infinity, { test: 2 }), TypeError, /test must be a string/],
  [() => bvh.raycastAll(above, down, 0, Infinity, { side: 3 }), RangeError, /side must be 0 \(front\), 1 \(back\) or 2/],
  [() => bvh.raycastAny(above, down, 0, Infinity, { cull: 0 }), RangeError, /unknown option "cull" \(the options are side, test\)/],
  [() => bvh.raycast(above, down, 0, Infinity, [0]), TypeError, /side \(a number or \{ side, test \}\) must be an object, got/],
  [() => geometry.closestPointTriangle([0, 0, 0], [0, 0, 0], [1, 0, 0], [0, 1, 0], 'voronoi'), RangeError, /method must be one of "regions", "projection", "rotation"/],
  [() => geometry.closestPointTriangle([0, 0, 0], [0, 0, 0], [1, 0, 0]), TypeError, /c must be \[x, y, z\]/],
  [() => geometry.intersectRayTriangle([0, 0, 1], [0, 0, 0], [0, 0, 0], [1, 0, 0], [0, 1, 0]), RangeError, /direction must not be zero/],
  [() => geometry.intersectRayTriangle([0, 0, 1], [0, 0, -1], [0, 0, 0], [1, 0, 0], [0, 1, 0], { test: 'exact' }), RangeError, /test must be one of/],
  [() => geometry.intersectRayPlane([0, 0, 1], [0, 0, -1], [0, 0, 0], 0), RangeError, /normal must not be zero/],
  [() => geometry.closestPointPlane([0, 0, 1], [0, 0, 1], 'zero'), TypeError, /offset must be a number/],
  [() => geometry.pointOnPlane([0, 0, 1], [0, 0, 1], 0, -1), RangeError, /relative must be a number ≥ 0/],
  [() => geometry.pointOnSegment([0, 0, 1], [0, 0, 0], [1, 0, 0], NaN), RangeError, /tolerance must be a finite number/],
  [() => geometry.intersectRayAabb([0, 0, 1], [0, 0, -1], [1, 1, 1], [0, 0, 0]), RangeError, /min must not exceed max/],
  [() => geometry.overlapTriangleAabb([0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 0], { x: 1, y: 1 }), TypeError, /max.z must be a number/],
  [() => geometry.trianglesMeet([[0, 0, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 1, 0]]), TypeError, /first must be an array of three corners/],
  [() => geometry.trianglesMeet([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [1, 0, 0], [0, 1, Infinity]]), RangeError, /second\[2\].z must be a finite number/],
  [() => MeshBvh.build(positions, indices, { structure: 'grid' }).eightWideNodes(), TypeError, /eightWideNodes applies to a BVH/],
  [() => MeshBvh.build(positions, indices, { structure: 'octree' }).fourWideNodes(), TypeError, /fourWideNodes applies to a BVH/],
];

// Bad batch outputs: wrong type, wrong length; the arrays stay as they were.
const rays = Float32Array.from([...above, ...down, 0.5, 0.5, 1, 0, 0, -1]);
const sentinel = (array) => array.fill(7);
const batchCases = [
  [(d, t) => bvh.raycastBatch(rays, 0, Infinity, new Uint16Array(2), t), TypeError, /t must be a Float32Array, got Uint16Array/],
  [(d, t) => bvh.raycastBatch(rays, 'near', Infinity, d, t), TypeError, /near must be a number/],
  [(d, t) => bvh.raycastBatch(rays, 0, NaN, d, t), RangeError, /far must be a number, got NaN/],
  [(d, t) => bvh.raycastBatch(rays), TypeError, /t must be a Float32Array, got undefined/],
  [(d) => bvh.raycastBatch(rays, 0, Infinity, d, [0, 0]), TypeError, /triangles must be a Uint32Array, got Array/],
  [(d, t) => bvh.raycastBatch(rays, 0, Infinity, new Float64Array(2), t), TypeError, /Float32Array, got Float64Array/],
  [(d, t) => bvh.raycastBatch(rays, 0, Infinity, new Float32Array(3), t), RangeError, /exactly 2/],
  [(d, t) => bvh.raycastBatch(rays.subarray(0, 7), 0, Infinity, d, t), RangeError, /multiple of 6/],
  [(d, t) => bvh.raycastBatch([...rays], 0, Infinity, d, t), TypeError, /rays must be a Float32Array/],
  [(d, t) => bvh.raycastBatch(rays, 0, Infinity, d, t, 7), RangeError, /side/],
  [(d) => bvh.raycastBatch(rays, 0, Infinity, d, new Uint32Array(d.buffer, d.byteOffset, 2)), RangeError, /t and triangles share memory/],
  [(d, t) => bvh.raycastBatchBarycentric(rays, 0, Infinity, d, t, new Float32Array(2)), RangeError, /barycentrics .* exactly 4/],
  [() => bvh.raycastAnyBatch(rays, 0, Infinity, new Uint32Array(2)), TypeError, /hits must be a Uint8Array/],
  [(d, t) => bvh.closestPointBatch(Float32Array.from([0, 0, 0]), -2, new Float32Array(3), t.subarray(0, 1), d.subarray(0, 1)), RangeError, /maxDistance/],
  [(d, t) => bvh.closestPointBatch(Float32Array.from([0, 0, 0]), 1, new Float32Array(2), t.subarray(0, 1), d.subarray(0, 1)), RangeError, /closest .* exactly 3/],
];
{
  const d = new Float32Array(2);
  const t = new Uint32Array(2);
  for (const [i, [f, type, words]] of batchCases.entries()) {
    sentinel(d);
    sentinel(t);
    throws(() => f(d, t), type, words, `batch case ${i}`);
    assert.deepEqual([...d, ...t], [7, 7, 7, 7], `batch case ${i}: outputs untouched`);
  }
  // The same arrays still work in a correct call afterwards.
  assert.equal(bvh.raycastBatch(rays, undefined, undefined, d, t), 2);
  assert.equal(d[0], reference.t);
  assert.equal(t[0], reference.triangle);
}
for (const [i, [f, type, words]] of cases.entries()) throws(f, type, words, `case ${i}`);

// Outputs in the rays' own buffer (over rays not yet read, when a batch is read a chunk at a
// time) get the answers of separate arrays: every ray is read before any answer is written.
{
  const n = 3 * MeshBvh.RAY_CHUNK + 5;
  const fresh = randomRays(bvh.bounds(), 3, n);
  const want = [new Float32Array(n), new Uint32Array(n), new Float32Array(2 * n), new Uint8Array(n)];
  bvh.raycastBatchBarycentric(fresh, 0, Infinity, want[0], want[1], want[2]);
  bvh.raycastAnyBatch(fresh, 0, Infinity, want[3]);
  assert.ok(want[1].some((tri) => tri !== MeshBvh.MISS_TRIANGLE), 'some rays hit');
  // Each output laid over a different part of the rays: t over their start, triangles over the
  // second chunk's, barycentrics over the tail, the any-hit flags over the middle.
  const shared = (at, make) => {
    const buffer = new ArrayBuffer(fresh.byteLength);
    const rays = new Float32Array(buffer);
    rays.set(fresh);
    return [rays, make(buffer, at)];
  };
  let [r, t] = shared(0, (b) => new Float32Array(b, 0, n));
  bvh.raycastBatch(r, 0, Infinity, t, new Uint32Array(n));
  assert.deepEqual(t, want[0], 't over the rays');
  let tri;
  [r, tri] = shared(0, (b) => new Uint32Array(b, 4 * 6 * MeshBvh.RAY_CHUNK, n));
  bvh.raycastBatch(r, 0, Infinity, new Float32Array(n), tri);
  assert.deepEqual(tri, want[1], 'triangles over the rays');
  let uv;
  [r, uv] = shared(0, (b) => new Float32Array(b, b.byteLength - 8 * n, 2 * n));
  bvh.raycastBatchBarycentric(r, 0, Infinity, new Float32Array(n), new Uint32Array(n), uv);
  assert.deepEqual(uv, want[2], 'barycentrics over the rays');
  let hits;
  [r, hits] = shared(0, (b) => new Uint8Array(b, 4 * 6 * MeshBvh.RAY_CHUNK + 1, n));
  bvh.raycastAnyBatch(r, 0, Infinity, hits);
  assert.deepEqual(hits, want[3], 'any-hit flags over the rays');
}

// Triangles no box separates stop at the pair budget with a RangeError, in bounded time and
// memory: 20,000 copies of one triangle (200 million meeting pairs), and 50,000 zero-area
// triangles at one point. Within the budget the pairs are listed, at most 2^20 by default.
{
  const corners = Float32Array.from([0, 0, 0, 1, 0, 0, 0, 1, 0]);
  const copiesOf = (n) => Uint32Array.from({ length: 3 * n }, (_, i) => i % 3);
  const copies = MeshBvh.build(corners, copiesOf(20_000));
  throws(() => copies.selfIntersections(), RangeError, /budget of \d+ pairs is spent.*maxTests/, 'copies: self');
  throws(() => copies.intersectingPairs(copies), RangeError, /budget .* is spent/, 'copies: pairs');
  assert.equal(copies.intersectsMesh(copies), true, 'a yes before the budget runs out');
  const fewer = MeshBvh.build(corners, copiesOf(1_200));
  const listed = fewer.selfIntersections();
  assert.equal(listed.total, (1_200 * 1_199) / 2, 'every pair of copies meets');
  assert.equal(listed.pairs.length, 2 * listed.total);
  const all = fewer.intersectingPairs(fewer);
  assert.equal(all.total, 1_200 * 1_200);
  assert.equal(all.pairs.length, 2 * (1 << 20), 'at most 2^20 pairs by default');
  assert.equal(all.overflowed, true);
  const point = MeshBvh.build(new Float32Array(3 * 150_000).fill(0.5), Uint32Array.from({ length: 150_000 }, (_, i) => i));
  throws(() => point.intersectsMesh(point), RangeError, /budget .* is spent/, 'points: yes/no');
  throws(() => point.selfIntersections(null, 1e6), RangeError, /budget of 1000000 pairs/, 'points: given budget');
  for (const m of [copies, fewer, point]) m.free();
}

// The remesh distance report within its point–triangle test budget: 4,000 triangles that all
// span one box are remeshed in bounded time, the distance from the samples the budget paid
// for; with room for them all (or on an ordinary mesh) every sample is measured.
{
  const n = 4_000;
  const spans = new Float32Array(9 * n);
  for (let i = 0; i < n; i++) {
    const t = i / n;
    spans.set([-1, -1 + 2 * t, -1, 1, 1 - 2 * t, -1, 2 * t - 1, 0, 1], 9 * i);
  }
  const bounded = remesh(spans, null, { iterations: 1 });
  assert.equal(bounded.distanceSamples, 4 * (n + bounded.after.triangles));
  assert.ok(bounded.distanceSamplesMeasured > 0 && bounded.distanceSamplesMeasured < bounded.distanceSamples,
    `measured ${bounded.distanceSamplesMeasured} of ${bounded.distanceSamples}`);
  const none = remesh(spans, null, { iterations: 1, maxDistanceTests: 0 });
  assert.equal(none.distanceSamplesMeasured, 0);
  assert.equal(none.distance, 0);
  const plain = remesh(positions, indices, { iterations: 2 });
  assert.equal(plain.distanceSamplesMeasured, plain.distanceSamples, 'an ordinary mesh: every sample');
  assert.ok(plain.distance > 0 && plain.distance < 0.1);
}

// A mesh too large for WebAssembly's 4 GiB is refused with an Error naming the limit, before
// anything is allocated for it (17 million triangles, all corners at vertex 0).
throws(() => MeshBvh.build(new Float32Array(3), new Uint16Array(3 * 17_000_000)), Error, /too large for WebAssembly.*4 GiB/,
  'huge mesh');

// 10,000 misuse calls in a row, then the module still answers, and frees, normally.
const all = [...cases.map(([f]) => f), ...batchCases.map(([f]) => () => f(new Float32Array(2), new Uint32Array(2)))];
let thrown = 0;
for (let i = 0; i < 10_000; i++) {
  try {
    all[i % all.length]();
  } catch {
    thrown++;
  }
}
assert.equal(thrown, 10_000);
assert.deepEqual(bvh.raycast(above, down), reference);
const again = MeshBvh.build(positions, indices);
assert.deepEqual(again.raycast(above, down), reference);
again.free();
bvh.free();
console.log(`misuse: ${cases.length + batchCases.length + 1} kinds of bad argument refused by name; 10,000 misuse calls, then correct answers`);
