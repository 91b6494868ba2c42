// The three.js drop-in against three's own brute-force Raycaster (every triangle tested), in
// Node, on the bundled bunny: same first hit for 10,000 random rays (DESIGN.md workload), the
// same full intersection lists, material sides, near/far, a transformed mesh, draw ranges and
// groups with an array of materials; intersectsGeometry and the mesh–mesh bindings on
// spheres whose meeting is known from geometry.
// Run after scripts/build-web.sh: node web/tests/three-dropin.mjs
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { Worker, isMainThread, parentPort, workerData } from 'node:worker_threads';
import * as THREE from 'three';
import { OBJLoader } from 'three/addons/loaders/OBJLoader.js';
import { mergeVertices } from 'three/addons/utils/BufferGeometryUtils.js';
import { AVERAGE, CENTER, CONTAINED, INTERSECTED, NOT_INTERSECTED, SAH, acceleratedRaycast, computeBoundsTree, disposeBoundsTree } from 'meshq-wasm/three';
import * as meshq from 'meshq-wasm';
import { MeshBVH } from 'three-mesh-bvh';

const root = fileURLToPath(new URL('../..', import.meta.url));
const RAYS = Number(process.env.MESHQ_DROPIN_RAYS ?? 10000);

const obj = new OBJLoader().parse(readFileSync(`${root}/assets/stanford-bunny.obj`, 'utf8'));
const loaded = obj.children[0].geometry;
loaded.deleteAttribute('normal');
loaded.deleteAttribute('uv');
const indexed = mergeVertices(loaded);

// Two meshes sharing a geometry: one raycasts through meshq, one with three's brute force.
THREE.BufferGeometry.prototype.computeBoundsTree = computeBoundsTree;
THREE.BufferGeometry.prototype.disposeBoundsTree = disposeBoundsTree;
const material = new THREE.MeshBasicMaterial({ side: THREE.DoubleSide });
const fast = new THREE.Mesh(indexed, material);
fast.raycast = acceleratedRaycast;
const brute = new THREE.Mesh(indexed, material);
indexed.computeBoundsTree();
assert.equal(indexed.boundsTree.triangleCount, indexed.index.count / 3);

const rays = meshq.randomRays(indexed.boundsTree.bounds(), 1, RAYS);
const raycaster = new THREE.Raycaster();

function cast(mesh, k, firstHitOnly) {
  raycaster.set(
    new THREE.Vector3(rays[6 * k], rays[6 * k + 1], rays[6 * k + 2]),
    new THREE.Vector3(rays[6 * k + 3], rays[6 * k + 4], rays[6 * k + 5]),
  );
  raycaster.firstHitOnly = firstHitOnly;
  return raycaster.intersectObject(mesh, false);
}

// Equal bit for bit (every field of three's intersection, by strict deep equality), or a tie:
// both hit points at the same distance (a ray through a shared edge, where three and meshq
// may pick either triangle).
function sameHit(a, b, what) {
  if (a.faceIndex !== b.faceIndex) {
    const close = Math.abs(a.distance - b.distance) <= 1e-5 * Math.max(1, b.distance);
    assert.ok(close, `${what}: distance ${a.distance} vs three ${b.distance}`);
    return false;
  }
  assert.equal(a.object, fast);
  assert.deepStrictEqual({ ...a, object: null }, { ...b, object: null }, `${what}: intersection`);
  return true;
}

/** First hits of rays `from..to` against three's brute force: `{ hits, ties }`. */
function firstHits(from, to) {
  let hits = 0;
  let ties = 0;
  for (let k = from; k < to; k++) {
    const ours = cast(fast, k, true);
    const theirs = cast(brute, k, false);
    assert.equal(ours.length > 0, theirs.length > 0, `ray ${k}: hit or miss`);
    if (!ours.length) continue;
    hits++;
    if (!sameHit(ours[0], theirs[0], `ray ${k}`)) ties++;
  }
  return { hits, ties };
}

// The brute-force reference dominates the run time: half of the rays go to a second thread.
if (!isMainThread) {
  parentPort.postMessage(firstHits(workerData.from, workerData.to));
  process.exit(0);
}
const started = performance.now();
const half = Math.floor(RAYS / 2);
const other = new Promise((resolve, reject) => {
  const worker = new Worker(new URL(import.meta.url), { workerData: { from: half, to: RAYS } });
  worker.once('message', resolve);
  worker.once('error', reject);
});
const mine = firstHits(0, half);
const theirs = await other;
const hits = mine.hits + theirs.hits;
const ties = mine.ties + theirs.ties;
console.log(`first hit: ${RAYS} rays, ${hits} hits, all equal to three's brute force ` +
  `(${ties} ties on a shared edge) in ${((performance.now() - started) / 1000).toFixed(1)} s`);
assert.ok(hits > RAYS / 4);
assert.ok(ties <= RAYS / 1000, `${ties} ties is too many to be edge hits`);

// Full lists (firstHitOnly unset): every intersection, in order.
for (let k = 0; k < 300; k++) {
  const ours = cast(fast, k, false);
  const theirs = cast(brute, k, false);
  assert.equal(ours.length, theirs.length, `ray ${k}: number of intersections`);
  ours.forEach((hit, i) => sameHit(hit, theirs[i], `ray ${k}, intersection ${i}`));
}

// Material sides, near/far and a moved, rotated, scaled mesh.
for (const side of [THREE.FrontSide, THREE.BackSide]) {
  material.side = side;
  for (let k = 0; k < 300; k++) {
    const ours = cast(fast, k, true);
    const theirs = cast(brute, k, false);
    assert.equal(ours.length > 0, theirs.length > 0, `side ${side}, ray ${k}`);
    if (ours.length) sameHit(ours[0], theirs[0], `side ${side}, ray ${k}`);
  }
}
material.side = THREE.DoubleSide;
for (const mesh of [fast, brute]) {
  // Small enough that the rays, placed around the untransformed bunny, still hit it.
  mesh.position.set(0.01, -0.02, 0.005);
  mesh.rotation.set(0.2, 0.3, -0.1);
  mesh.scale.set(1.2, 0.9, 1.1);
  mesh.updateMatrixWorld(true);
}
raycaster.near = 0.12;
raycaster.far = 0.2;
let limited = 0;
for (let k = 0; k < 300; k++) {
  const ours = cast(fast, k, false);
  const theirs = cast(brute, k, false);
  assert.equal(ours.length, theirs.length, `transformed, near/far, ray ${k}`);
  ours.forEach((hit, i) => sameHit(hit, theirs[i], `transformed, ray ${k}, intersection ${i}`));
  limited += ours.length;
}
assert.ok(limited > 50, `the near/far window keeps some hits (${limited})`);

// Draw ranges, and groups with an array of materials of different sides (one group
// overlapping another, so its triangles are reported twice, as three does).
for (const mesh of [fast, brute]) {
  mesh.position.set(0, 0, 0);
  mesh.rotation.set(0, 0, 0);
  mesh.scale.set(1, 1, 1);
  mesh.updateMatrixWorld(true);
}
raycaster.near = 0;
raycaster.far = Infinity;
// Counts the queries that reach meshq, to tell the accelerated path from three's fallback.
const tree = indexed.boundsTree;
let accelerated = 0;
for (const name of ['raycastAll', 'raycastXyz']) {
  const query = tree[name];
  tree[name] = (...args) => {
    accelerated++;
    return query.apply(tree, args);
  };
}
function compareLists(what, expectAccelerated = true) {
  const before = accelerated;
  let listed = 0;
  for (let k = 0; k < 300; k++) {
    const ours = cast(fast, k, false);
    const theirs = cast(brute, k, false);
    assert.equal(ours.length, theirs.length, `${what}, ray ${k}: number of intersections`);
    const matched = ours.filter((hit, i) => sameHit(hit, theirs[i], `${what}, ray ${k}, intersection ${i}`));
    if (matched.length === ours.length) {
      // A triangle in two groups is listed twice at the same distance; three's two distances
      // differ in the last bits (it swaps the corners for back sides), so its order of the two
      // is arbitrary: compare which (triangle, material) pairs are listed, not their order.
      const pairs = (hits) => hits.map((h) => `${h.faceIndex}/${h.face.materialIndex}`).sort();
      assert.deepEqual(pairs(ours), pairs(theirs), `${what}, ray ${k}: triangles and materials`);
    }
    const [first] = cast(fast, k, true);
    assert.equal(Boolean(first), theirs.length > 0, `${what}, ray ${k}: first hit or miss`);
    if (first) sameHit(first, theirs[0], `${what}, ray ${k}, first hit`);
    listed += ours.length;
  }
  assert.equal(accelerated - before, expectAccelerated ? 600 : 0, `${what}: queries through meshq`);
  return listed;
}
const corners = indexed.index.count;
const third = 3 * Math.floor(corners / 9);
indexed.setDrawRange(3 * 1000, 3 * Math.floor(corners / 6));
const ranged = compareLists('draw range');
const sides = [THREE.FrontSide, THREE.BackSide, THREE.DoubleSide];
const materials = sides.map((side) => new THREE.MeshBasicMaterial({ side }));
fast.material = materials;
brute.material = materials;
indexed.addGroup(0, third, 0);
indexed.addGroup(third, third, 1);
indexed.addGroup(2 * third, corners - 2 * third, 2);
indexed.addGroup(3 * Math.floor(third / 9), third, 2);
indexed.setDrawRange(0, Infinity);
const grouped = compareLists('groups');
indexed.setDrawRange(3 * 2000, 3 * Math.floor(corners / 4));
const both = compareLists('groups within a draw range');
// A group starting inside a triangle: three reads corners across triangles; only its own
// raycast reproduces that, so the drop-in hands such meshes to it.
indexed.setDrawRange(0, Infinity);
indexed.addGroup(1, 3 * 500, 0);
compareLists('a group not starting on a triangle', false);
console.log(`draw range and groups: ${ranged}, ${grouped} and ${both} intersections equal to three's`);
assert.ok(ranged > 30 && grouped > 100 && both > 30, 'the ranges keep some hits');
indexed.clearGroups();
indexed.setDrawRange(0, Infinity);
fast.material = material;
brute.material = material;

// Interpolated attributes: uv and vertex normal on a sphere that has both.
{
  const sphere = new THREE.SphereGeometry(0.05, 48, 32);
  sphere.computeBoundsTree();
  const ours = new THREE.Mesh(sphere, material);
  ours.raycast = acceleratedRaycast;
  const reference = new THREE.Mesh(sphere, material);
  const sphereRays = meshq.randomRays(sphere.boundsTree.bounds(), 7, 200);
  let checked = 0;
  for (let k = 0; k < 200; k++) {
    raycaster.set(
      new THREE.Vector3(...sphereRays.subarray(6 * k, 6 * k + 3)),
      new THREE.Vector3(...sphereRays.subarray(6 * k + 3, 6 * k + 6)),
    );
    raycaster.near = 0;
    raycaster.far = Infinity;
    const [a] = raycaster.intersectObject(ours, false);
    const [b] = raycaster.intersectObject(reference, false);
    assert.equal(Boolean(a), Boolean(b), `sphere ray ${k}`);
    if (!a || a.faceIndex !== b.faceIndex) continue;
    assert.ok(a.uv.isVector2 && a.normal.isVector3, `sphere ray ${k}: uv and normal`);
    assert.deepStrictEqual({ ...a, object: null }, { ...b, object: null }, `sphere ray ${k}`);
    checked++;
  }
  assert.ok(checked > 100, `uv and normal compared on ${checked} hits`);
  sphere.disposeBoundsTree();
}

// intersectsGeometry, judged by geometry: two unit spheres (inscribed polyhedra) whose
// centres are 1 apart cross; 2.2 apart they cannot meet; a sphere of radius 0.4 inside one
// of radius 1 meets nothing (the volumes overlap, the surfaces do not).
{
  const unit = new THREE.SphereGeometry(1, 32, 24);
  const small = new THREE.SphereGeometry(0.4, 16, 12);
  unit.computeBoundsTree();
  const at = (x, y, z) => new THREE.Matrix4().makeRotationZ(0.3).setPosition(x, y, z);
  assert.equal(unit.boundsTree.intersectsGeometry(unit, at(1, 0, 0)), true, 'crossing');
  assert.equal(unit.boundsTree.intersectsGeometry(unit, at(0, 2.2, 0)), false, 'apart');
  // `small` has no bounds tree: one is built for the call and freed.
  assert.equal(unit.boundsTree.intersectsGeometry(small, at(0.1, 0, 0)), false, 'inside');
  assert.equal(small.boundsTree, undefined);
  assert.equal(unit.boundsTree.intersectsGeometry(small, at(0.8, 0, 0)), true, 'poking out');
  // The pairs behind the answer, and the curve where the surfaces cross.
  const found = unit.boundsTree.intersectingPairs(unit.boundsTree, at(1, 0, 0).elements);
  assert.ok(found.total > 0 && found.pairs.length === 2 * found.total && !found.overflowed);
  const segments = unit.boundsTree.intersectionSegments(unit.boundsTree, at(1, 0, 0).elements);
  assert.ok(segments.length > 0 && segments.length % 6 === 0);
  // Every segment end lies on the plane x = 0.5 where two unit spheres 1 apart meet, to
  // within the polyhedra's sag.
  for (let k = 0; k < segments.length; k += 3) {
    assert.ok(Math.abs(segments[k] - 0.5) < 0.02, `segment end x ${segments[k]}`);
  }
  assert.equal(unit.boundsTree.selfIntersections().total, 0);
  assert.throws(() => unit.boundsTree.intersectsMesh(unit.boundsTree, [1, 2, 3]), /16 numbers/);
  // intersectsSphere and intersectsBox: only the surface counts, not the volume inside.
  const tree = unit.boundsTree;
  assert.equal(tree.intersectsSphere(new THREE.Sphere(new THREE.Vector3(), 0.5)), false, 'sphere inside');
  assert.equal(tree.intersectsSphere(new THREE.Sphere(new THREE.Vector3(0.5, 0, 0), 0.6)), true, 'sphere across');
  const slab = new THREE.Box3(new THREE.Vector3(-0.55, -0.55, -0.05), new THREE.Vector3(0.55, 0.55, 0.05));
  // Turned 45° its corners stay 0.78 from the centre, inside the sphere, though its
  // axis-aligned bounds reach past the surface: the box, not its bounds, is tested.
  const turned = new THREE.Matrix4().makeRotationZ(Math.PI / 4);
  assert.equal(tree.intersectsBox(slab, turned), false, 'turned slab inside');
  assert.equal(tree.intersectsBox(slab, turned.clone().scale(new THREE.Vector3(1.5, 1.5, 1))), true, 'scaled past the surface');
  assert.equal(tree.intersectsBox(slab, new THREE.Matrix4().makeTranslation(0.6, 0, 0)), true, 'moved across');
  assert.throws(() => tree.intersectsBox(slab, new THREE.Matrix4().makeShear(0.5, 0, 0, 0, 0, 0)), /shear/);
  unit.disposeBoundsTree();
}

// A tree freed by hand counts as none: raycasts fall back to three's own (the same hits), and
// computeBoundsTree and disposeBoundsTree replace or clear it without a "null pointer" error.
{
  const geometry = new THREE.SphereGeometry(1, 24, 12);
  const ours = new THREE.Mesh(geometry, material);
  ours.raycast = acceleratedRaycast;
  const reference = new THREE.Mesh(geometry, material);
  geometry.computeBoundsTree();
  geometry.boundsTree.free();
  const caster = new THREE.Raycaster(new THREE.Vector3(0.1, 0.2, 5), new THREE.Vector3(0, 0, -1));
  const freed = caster.intersectObject(ours, false);
  assert.deepEqual(freed.map((h) => h.faceIndex), caster.intersectObject(reference, false).map((h) => h.faceIndex));
  assert.ok(freed.length === 2, 'through both sides');
  geometry.computeBoundsTree();
  assert.equal(caster.intersectObject(ours, false)[0].faceIndex, freed[0].faceIndex, 'rebuilt');
  geometry.boundsTree.free();
  geometry.disposeBoundsTree();
  assert.equal(geometry.boundsTree, null);
}

// shapecast against brute force: the triangles of the bunny within a sphere, found with
// three's own box and triangle maths, once with INTERSECTED only and once letting contained
// boxes pass their triangles through; an early stop; the order callback.
{
  const tree = indexed.boundsTree;
  const position = indexed.getAttribute('position');
  const index = indexed.index;
  const corner = (t, k) => new THREE.Vector3().fromBufferAttribute(position, index.getX(3 * t + k));
  const bounds = new THREE.Box3().setFromBufferAttribute(position);
  const size = bounds.getSize(new THREE.Vector3()).length();
  const closest = new THREE.Vector3();
  for (let k = 0; k < 6; k++) {
    const centre = bounds.getCenter(new THREE.Vector3()).add(new THREE.Vector3(Math.sin(k), Math.cos(k), 0.3).multiplyScalar(0.2 * size));
    const sphere = new THREE.Sphere(centre, size * (0.05 + 0.04 * k));
    const want = [];
    for (let t = 0; t < index.count / 3; t++) {
      const tri = new THREE.Triangle(corner(t, 0), corner(t, 1), corner(t, 2));
      if (tri.getArea() > 0 && tri.closestPointToPoint(sphere.center, closest).distanceTo(sphere.center) <= sphere.radius) want.push(t);
    }
    let fullWalk = 0;
    for (const useContained of [false, true]) {
      const got = [];
      let containedSeen = 0;
      const stopped = tree.shapecast({
        intersectsBounds: (box) => {
          if (!box.intersectsSphere(sphere)) return NOT_INTERSECTED;
          if (useContained) {
            const far = box.getCenter(new THREE.Vector3()).distanceTo(sphere.center) + box.getSize(new THREE.Vector3()).length() / 2;
            if (far <= sphere.radius) return CONTAINED;
          }
          return INTERSECTED;
        },
        intersectsTriangle: (tri, t, contained) => {
          containedSeen += Number(contained);
          if (!useContained) fullWalk++;
          if (tri.getArea() > 0 && (contained || tri.closestPointToPoint(sphere.center, closest).distanceTo(sphere.center) <= sphere.radius)) got.push(t);
          return false;
        },
      });
      assert.equal(stopped, false);
      got.sort((a, b) => a - b);
      assert.deepEqual(got, want, `shapecast sphere ${k}, contained ${useContained}`);
      if (useContained && k === 5) assert.ok(containedSeen > 0, 'some boxes were contained');
    }
    // Stopping at the first triangle inside the sphere.
    let offered = 0;
    const stopped = tree.shapecast({
      intersectsBounds: (box) => box.intersectsSphere(sphere),
      intersectsTriangle: (tri) => { offered++; return tri.closestPointToPoint(sphere.center, closest).distanceTo(sphere.center) <= sphere.radius; },
      boundsTraverseOrder: (box) => box.distanceToPoint(sphere.center),
    });
    assert.equal(stopped, want.length > 0, `shapecast stop ${k}`);
    assert.ok(want.length === 0 || offered < fullWalk, `stopped early: ${offered} of ${fullWalk} offered`);
  }
  assert.throws(() => tree.shapecast({ intersectsBounds: () => true, intersectsRange: () => false }), /intersectsRange/);
  console.log('shapecast: triangles within 6 spheres equal to brute force, with and without contained boxes');
}

// three-mesh-bvh's MeshBVH options: honoured, or refused by name, never ignored.
{
  const geometry = indexed.clone();
  const leafSizes = (tree) => {
    const { count } = tree.treeArrays();
    return Math.max(...count);
  };
  let progress = null;
  geometry.computeBoundsTree({ maxLeafTris: 3, maxDepth: 40, strategy: SAH, indirect: true, verbose: false, onProgress: (p) => { progress = p; } });
  assert.ok(leafSizes(geometry.boundsTree) <= 3, 'maxLeafTris');
  assert.ok(geometry.boundsTree.depth <= 40, 'maxDepth');
  assert.equal(progress, 1, 'onProgress');
  // setBoundingBox (on by default): the geometry's box holds every vertex.
  const box = geometry.boundingBox;
  const own = new THREE.Box3().setFromBufferAttribute(geometry.getAttribute('position'));
  assert.ok(box.containsBox(own) && box.min.distanceTo(own.min) < 1e-3 * own.getSize(new THREE.Vector3()).length(), 'setBoundingBox');
  geometry.computeBoundsTree({ maxDepth: 12, maxLeafSize: 64 });
  assert.ok(geometry.boundsTree.depth <= 12, 'a low maxDepth is held');
  // CENTER builds what meshq's 'fast' quality builds.
  geometry.computeBoundsTree({ strategy: CENTER });
  const center = geometry.boundsTree.toBlob();
  geometry.computeBoundsTree({ quality: 'fast' });
  assert.deepEqual(center, geometry.boundsTree.toBlob(), 'strategy CENTER = quality fast');
  assert.throws(() => geometry.computeBoundsTree({ strategy: AVERAGE }), /strategy 1 is not supported/);
  assert.throws(() => geometry.computeBoundsTree({ range: { start: 0, count: 3 } }), /option range is not supported/);
  assert.throws(() => geometry.computeBoundsTree({ useSharedArrayBuffer: true }), /useSharedArrayBuffer/);
  assert.throws(() => geometry.computeBoundsTree({ maxLeafTris: 4, maxLeafSize: 8 }), /disagree/);
  assert.throws(() => geometry.computeBoundsTree({ maxDepth: 0 }), /depth/i);
  geometry.disposeBoundsTree();
  console.log('MeshBVH options: maxLeafTris, maxDepth, strategy, indirect, setBoundingBox, onProgress honoured; the rest refused by name');
}

// The bounds tree's own queries, with three-mesh-bvh's signatures and result shapes, against
// three's brute force (brute's meshes have identity transforms, so frames agree).
{
  const tree = indexed.boundsTree;
  const bruteRaycaster = new THREE.Raycaster();
  const ray = new THREE.Ray();
  let hitsChecked = 0;
  for (const side of [THREE.FrontSide, THREE.DoubleSide]) {
    const sided = new THREE.Mesh(indexed, new THREE.MeshBasicMaterial({ side }));
    for (let k = 0; k < 60; k++) {
      ray.origin.fromArray(rays, 6 * k);
      ray.direction.fromArray(rays, 6 * k + 3).normalize();
      bruteRaycaster.ray.copy(ray);
      const want = [];
      THREE.Mesh.prototype.raycast.call(sided, bruteRaycaster, want);
      want.sort((p, q) => p.distance - q.distance);
      const all = tree.raycast(ray, side);
      assert.deepEqual(all.map((h) => h.faceIndex).sort((p, q) => p - q), want.map((h) => h.faceIndex).sort((p, q) => p - q), `raycast ${k}`);
      const first = tree.raycastFirst(ray, sided.material);
      assert.equal(first === null, want.length === 0, `raycastFirst ${k}`);
      if (first) {
        assert.ok(Math.abs(first.distance - want[0].distance) < 1e-5 * (1 + want[0].distance), `raycastFirst distance ${k}`);
        assert.ok(first.point.distanceTo(want[0].point) < 1e-4, `raycastFirst point ${k}`);
        assert.deepEqual([first.face.a, first.face.b, first.face.c], [indexed.index.getX(3 * first.faceIndex), indexed.index.getX(3 * first.faceIndex + 1), indexed.index.getX(3 * first.faceIndex + 2)]);
        hitsChecked++;
      }
    }
  }
  assert.ok(hitsChecked > 20, `${hitsChecked} first hits checked`);
  // closestPointToPoint against every triangle's closest point.
  const position = indexed.getAttribute('position');
  const triangle = new THREE.Triangle();
  const closest = new THREE.Vector3();
  for (let k = 0; k < 10; k++) {
    const p = new THREE.Vector3().fromArray(rays, 6 * k);
    let best = Infinity;
    for (let t = 0; t < indexed.index.count / 3; t++) {
      triangle.setFromAttributeAndIndices(position, indexed.index.getX(3 * t), indexed.index.getX(3 * t + 1), indexed.index.getX(3 * t + 2));
      best = Math.min(best, triangle.closestPointToPoint(p, closest).distanceTo(p));
    }
    const target = {};
    assert.equal(tree.closestPointToPoint(p, target), target);
    assert.ok(Math.abs(target.distance - best) < 1e-5 * (1 + best), `closestPointToPoint ${k}: ${target.distance} vs ${best}`);
    assert.ok(target.point.isVector3 && Number.isInteger(target.faceIndex));
    assert.equal(tree.closestPointToPoint(p, {}, 0, best * 0.5), null, 'maxThreshold');
  }
  const box = tree.getBoundingBox(new THREE.Box3());
  assert.ok(box.containsBox(new THREE.Box3().setFromBufferAttribute(position)), 'getBoundingBox');
  assert.throws(() => tree.refit(), /computeBoundsTree/);
  // closestPointToGeometry against three-mesh-bvh's own, on a sphere placed near the bunny,
  // into it, and far off (scaled and turned, so target2's frame differs from target1's).
  const sphere = new THREE.SphereGeometry(0.02, 24, 16);
  const size = box.getSize(new THREE.Vector3()).length();
  const theirs = new MeshBVH(indexed);
  const placements = [
    new THREE.Vector3(box.max.x + 0.01, (box.min.y + box.max.y) / 2, 0),
    box.getCenter(new THREE.Vector3()),
    new THREE.Vector3(box.max.x + 0.5, box.max.y, box.max.z),
  ];
  for (const [k, at] of placements.entries()) {
    const matrix = new THREE.Matrix4().compose(at, new THREE.Quaternion().setFromEuler(new THREE.Euler(0.3, 0.5, 0.1)), new THREE.Vector3(1.5, 1, 0.7));
    const [ours1, ours2, want1, want2] = [{}, {}, {}, {}];
    assert.equal(tree.closestPointToGeometry(sphere, matrix, ours1, ours2), ours1);
    assert.equal(theirs.closestPointToGeometry(sphere, matrix, want1, want2), want1);
    assert.ok(Math.abs(ours1.distance - want1.distance) <= 1e-5 * size, `closestPointToGeometry ${k}: ${ours1.distance} vs three-mesh-bvh ${want1.distance}`);
    assert.ok(Math.abs(ours2.distance - want2.distance) <= 1e-5 * size, `closestPointToGeometry target2 ${k}: ${ours2.distance} vs ${want2.distance}`);
    assert.ok(ours1.point.isVector3 && Number.isInteger(ours1.faceIndex) && Number.isInteger(ours2.faceIndex));
    // target2's point is on the sphere in its own frame, and maps onto target1's distance.
    const back = ours2.point.clone().applyMatrix4(matrix);
    assert.ok(Math.abs(back.distanceTo(ours1.point) - ours1.distance) <= 1e-5 * size, `closestPointToGeometry frames ${k}`);
    if (ours1.distance > 0) {
      assert.equal(tree.closestPointToGeometry(sphere, matrix, {}, {}, 0, ours1.distance * 0.5), null, 'maxThreshold');
    }
  }
  console.log(`bounds tree: raycast, raycastFirst (${hitsChecked} first hits), closestPointToPoint, getBoundingBox agree with three's brute force; closestPointToGeometry with three-mesh-bvh's`);
}

indexed.disposeBoundsTree();
assert.equal(indexed.boundsTree, null);
console.log('three.js drop-in: full lists, sides, near/far, transforms, draw ranges and groups equal three\'s intersections bit for bit; intersectsGeometry judged by geometry');
