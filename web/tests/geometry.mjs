// The package's `geometry` functions against three.js's own math (an independent reference
// in double precision) on random cases: closest points on triangles by every method, on
// segments and planes; ray against triangle by every test, against planes and boxes; triangle
// against box (three's Box3.intersectsTriangle) and against triangle (three-mesh-bvh's
// ExtendedTriangle); solid angles against the closed form in double precision. Tolerances are
// relative to the size of each case.
// Run after scripts/build-web.sh: node web/tests/geometry.mjs
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { ExtendedTriangle } from 'three-mesh-bvh';
import { geometry } from 'meshq-wasm';

const CASES = 3000;
let seed = 0x9e3779b9;
/** A deterministic uniform number in [-1, 1). */
function random() {
  seed = (Math.imul(seed ^ (seed >>> 15), 0x2c1b3c6d) + 0x6d2b79f5) >>> 0;
  seed ^= seed >>> 13;
  return (seed >>> 0) / 2 ** 31 - 1;
}
/** A point with float32 coordinates (what meshq computes on), as a three.js vector. */
const f32 = Math.fround;
const point = (scale = 1) => new THREE.Vector3(f32(random() * scale), f32(random() * scale), f32(random() * scale));
const arr = (v) => [v.x, v.y, v.z];
const EPS = 2 ** -23;
/** The size of a case: its largest coordinate magnitude. */
const sizeOf = (...vs) => Math.max(...vs.flatMap((v) => [Math.abs(v.x), Math.abs(v.y), Math.abs(v.z)]));
const dist = (p, q) => Math.hypot(p.x - q.x, p.y - q.y, p.z - q.z);

let counted = { closest: 0, rays: 0, hits: 0, boxes: 0, meets: 0 };
for (let i = 0; i < CASES; i++) {
  const scale = 10 ** Math.round(3 * random());
  const [a, b, c, p] = [point(scale), point(scale), point(scale), point(2 * scale)];
  const tri = new THREE.Triangle(a, b, c);
  const size = sizeOf(a, b, c, p);

  // Closest point on the triangle: three's region walk in doubles; every meshq method within
  // rounding of the size (slivers get the projection's wider error, as its docs say).
  const want = tri.closestPointToPoint(p, new THREE.Vector3());
  const slender = Math.max(a.distanceTo(b), b.distanceTo(c), c.distanceTo(a)) ** 2 / (2 * tri.getArea() || 1);
  for (const method of ['regions', 'projection', 'rotation']) {
    const got = geometry.closestPointTriangle(arr(p), arr(a), arr(b), arr(c), method);
    const bound = 64 * EPS * size * (method === 'projection' ? Math.max(1, slender) : 1);
    assert.ok(dist(got.point, want) <= bound, `${method} case ${i}: ${JSON.stringify(got.point)} vs ${arr(want)} (bound ${bound})`);
    assert.ok(Math.abs(got.distance - p.distanceTo(want)) <= bound, `${method} case ${i}: distance`);
    const rebuilt = new THREE.Vector3().addScaledVector(a, 1 - got.u - got.v).addScaledVector(b, got.u).addScaledVector(c, got.v);
    assert.ok(dist(rebuilt, got.point) <= bound * 4, `${method} case ${i}: barycentrics`);
  }
  counted.closest++;

  // Ray against triangle, half the rays aimed at the plane in and around the triangle every test
  // agrees with three's Ray.intersectTriangle away from the edges (barycentric margin 1e-4)
  // and at incidences steeper than 0.1.
  const [u, v] = [0.375 + 0.625 * random(), 0.375 + 0.625 * random()];
  const aim = a.clone().addScaledVector(b.clone().sub(a), u).addScaledVector(c.clone().sub(a), v);
  const origin = point(3 * scale);
  const direction = i % 2 ? new THREE.Vector3().subVectors(aim, origin) : point();
  if (direction.lengthSq() > 0 && tri.getArea() > 1e-3 * scale * scale) {
    const ray = new THREE.Ray(origin, direction.clone().normalize());
    const hit = ray.intersectTriangle(a, b, c, false, new THREE.Vector3());
    const normal = tri.getNormal(new THREE.Vector3());
    const cos = Math.abs(normal.dot(direction.clone().normalize()));
    const plane = new THREE.Plane().setFromCoplanarPoints(a, b, c);
    const crossing = ray.intersectPlane(plane, new THREE.Vector3());
    const bary = crossing && tri.getBarycoord(crossing, new THREE.Vector3());
    const margin = bary ? Math.min(bary.x, bary.y, bary.z) : 1;
    if (cos > 0.1 && Math.abs(margin) > 1e-4) {
      for (const test of ['watertight', 'moller-trumbore', 'two-step']) {
        const got = geometry.intersectRayTriangle(arr(origin), arr(direction), arr(a), arr(b), arr(c), { test });
        assert.equal(got !== null, hit !== null, `${test} case ${i}: hit ${JSON.stringify(got)} vs ${hit && arr(hit)}`);
        if (got) {
          const at = origin.clone().addScaledVector(direction, got.t);
          assert.ok(at.distanceTo(hit) <= 1e3 * EPS * sizeOf(origin, a, b, c), `${test} case ${i}: point`);
        }
      }
      counted.rays++;
      if (hit) counted.hits++;
      // The plane crossing, against three's (both sides of the plane count in meshq; three
      // reports crossings ahead of the origin only, as does `near = 0`).
      const unit = normal.clone();
      const t = geometry.intersectRayPlane(arr(origin), arr(direction), arr(unit), f32(-plane.constant));
      if (crossing && t !== undefined) {
        const at = origin.clone().addScaledVector(direction, t);
        assert.ok(at.distanceTo(crossing) <= 1e3 * EPS * sizeOf(origin, a, b, c), `plane case ${i}`);
      }
    }
  }

  // Box overlaps: three's separating-axis test in doubles, away from touching (boxes grown
  // or shrunk by a thousandth of the size must agree with each other first).
  const lo = point(scale);
  const hi = lo.clone().add(new THREE.Vector3(Math.abs(random()), Math.abs(random()), Math.abs(random())).multiplyScalar(scale));
  const box = new THREE.Box3(lo.clone().min(hi), lo.clone().max(hi));
  box.min.set(f32(box.min.x), f32(box.min.y), f32(box.min.z));
  box.max.set(f32(box.max.x), f32(box.max.y), f32(box.max.z));
  const grow = 1e-3 * size;
  const outer = box.clone().expandByScalar(grow).intersectsTriangle(tri);
  const inner = box.clone().expandByScalar(-grow).intersectsTriangle(tri);
  if (outer === inner && !box.isEmpty()) {
    assert.equal(geometry.overlapTriangleAabb(arr(a), arr(b), arr(c), arr(box.min), arr(box.max)), outer, `box case ${i}`);
    counted.boxes++;
    const span = geometry.intersectRayAabb(arr(origin), arr(direction), arr(box.min), arr(box.max));
    const entry = new THREE.Ray(origin, direction).intersectBox(box, new THREE.Vector3());
    assert.equal(span !== null, entry !== null, `ray box case ${i}: ${JSON.stringify(span)}`);
    if (span && entry) {
      // three reports the exit from an origin inside the box, meshq the span from t = 0.
      const at = origin.clone().addScaledVector(direction, box.containsPoint(origin) ? span.far : span.near);
      assert.ok(at.distanceTo(entry) <= 1e3 * EPS * sizeOf(origin, box.min, box.max), `ray box case ${i}`);
    }
  }

  // Triangle against triangle: three-mesh-bvh's test, where it is not near touching (the
  // second triangle moved by a thousandth either way gives the same answer).
  const [d, e, f] = [point(scale), point(scale), point(scale)];
  const shift = normal0(d, e, f).multiplyScalar(1e-3 * size);
  const meets = (s) => new ExtendedTriangle(a, b, c).intersectsTriangle(new ExtendedTriangle(d.clone().add(s), e.clone().add(s), f.clone().add(s)));
  const plain = meets(new THREE.Vector3());
  if (plain === meets(shift) && plain === meets(shift.clone().negate())) {
    assert.equal(geometry.trianglesMeet([arr(a), arr(b), arr(c)], [arr(d), arr(e), arr(f)]), plain, `triangles case ${i}`);
    counted.meets++;
  }

  // Segments and planes.
  const line = new THREE.Line3(a, b);
  const onLine = line.closestPointToPoint(p, true, new THREE.Vector3());
  const seg = geometry.closestPointSegment(arr(p), arr(a), arr(b));
  assert.ok(dist(seg.point, onLine) <= 64 * EPS * size, `segment case ${i}`);
  const flat = new THREE.Plane().setFromNormalAndCoplanarPoint(new THREE.Vector3(0, 0, 1), c);
  const projected = flat.projectPoint(p, new THREE.Vector3());
  assert.ok(dist(geometry.closestPointPlane(arr(p), [0, 0, 1], c.z), projected) <= 64 * EPS * size, `plane case ${i}`);
  assert.equal(geometry.pointOnPlane(arr(projected), [0, 0, 1], c.z), true, `on plane case ${i}`);
  assert.equal(geometry.pointOnPlane(arr(projected.clone().setZ(c.z + 1e-3 * size)), [0, 0, 1], c.z), false, `off plane case ${i}`);

  // Solid angle: Van Oosterom and Strackee's closed form in doubles.
  const [ra, rb, rc] = [a, b, c].map((v) => v.clone().sub(p));
  const [la, lb, lc] = [ra, rb, rc].map((v) => v.length());
  const omega = 2 * Math.atan2(ra.dot(rb.clone().cross(rc)), la * lb * lc + ra.dot(rb) * lc + ra.dot(rc) * lb + rb.dot(rc) * la);
  const angle = geometry.solidAngleTriangle(arr(p), arr(a), arr(b), arr(c));
  assert.ok(Math.abs(angle - omega) <= 1e-4, `solid angle case ${i}: ${angle} vs ${omega}`);
}

// Huge coordinates: the distance stays finite and right (an f32 square would overflow past
// 1.8e19); the projection and rotation methods rescale at any size, the region walk up to
// triangles about 1e18 across (its squared edges overflow beyond: documented); the two-step
// ray test hits a triangle 1e15 across, where the other two tests' products of three
// coordinates overflow.
for (const [big, methods] of [[1e18, ['regions', 'projection', 'rotation']], [1e30, ['projection', 'rotation']]]) {
  for (const method of methods) {
    const got = geometry.closestPointTriangle([big / 4, big / 4, big], [0, 0, 0], [big, 0, 0], [0, big, 0], method);
    assert.equal(got.feature, 'face', method);
    assert.ok(Math.abs(got.distance - big) <= 1e-6 * big, `${method}: distance ${got.distance}`);
    assert.ok(Math.abs(got.point.x - big / 4) <= 1e-6 * big && got.point.z === 0, `${method}: point`);
  }
}
{
  const s = 1e15;
  const hit = geometry.intersectRayTriangle([s / 4, s / 4, s], [0, 0, -1], [0, 0, 0], [s, 0, 0], [0, s, 0], { test: 'two-step' });
  assert.deepEqual(hit, { t: Math.fround(s), u: 0.25, v: 0.25 });
}

function normal0(d, e, f) {
  return new THREE.Triangle(d, e, f).getNormal(new THREE.Vector3());
}

assert.ok(counted.rays > CASES / 4 && counted.hits > CASES / 10, JSON.stringify(counted));
assert.ok(counted.boxes > CASES / 2 && counted.meets > CASES / 2, JSON.stringify(counted));
console.log(`geometry: ${CASES} cases against three.js: ${JSON.stringify(counted)}`);
