// meshq for three.js: a drop-in for three-mesh-bvh's computeBoundsTree / acceleratedRaycast.
//
//   import { computeBoundsTree, disposeBoundsTree, acceleratedRaycast } from 'meshq-wasm/three.js';
//   THREE.BufferGeometry.prototype.computeBoundsTree = computeBoundsTree;
//   THREE.BufferGeometry.prototype.disposeBoundsTree = disposeBoundsTree;
//   THREE.Mesh.prototype.raycast = acceleratedRaycast;
//   geometry.computeBoundsTree();          // or geometry.boundsTree = MeshBvh.fromBlob(bytes)
//
// Raycaster results are three's own intersection objects, bit for bit (meshq finds the
// triangles; each hit is then recomputed with three's math), and respect raycaster.near / far, the material's side, raycaster.firstHitOnly, the
// geometry's draw range, and groups with an array of materials (as three does: each group is
// tested with its own material's side and reported with its materialIndex). Meshes without a
// bounds tree, with morph targets or skinning, instanced meshes, and draw ranges or groups that
// do not start on a whole triangle fall back to three's own raycast.
import { BackSide, Box3, DoubleSide, FrontSide, Mesh, Matrix4, Ray, Triangle, Vector2, Vector3 } from 'three';
import { MeshBvh } from './meshq_wasm.js';

const threeRaycast = Mesh.prototype.raycast;

/** A MeshBvh built from a BufferGeometry's position and index arrays. */
function buildFor(geometry, options) {
  const position = geometry.getAttribute('position');
  let positions;
  if (!position.isInterleavedBufferAttribute && position.itemSize === 3 &&
      position.array instanceof Float32Array && !position.normalized) {
    positions = position.array.subarray(0, position.count * 3);
  } else {
    positions = new Float32Array(position.count * 3);
    for (let i = 0; i < position.count; i++) {
      positions[3 * i] = position.getX(i);
      positions[3 * i + 1] = position.getY(i);
      positions[3 * i + 2] = position.getZ(i);
    }
  }
  let index = geometry.index ? geometry.index.array : null;
  if (index && !(index instanceof Uint32Array || index instanceof Uint16Array)) {
    index = Uint32Array.from(index);
  }
  return MeshBvh.build(positions, index, options);
}

/** three-mesh-bvh's split strategies (its `CENTER`, `AVERAGE`, `SAH` exports). */
export const CENTER = 0;
export const AVERAGE = 1;
export const SAH = 2;

/**
 * meshq build options from `options`, which may be three-mesh-bvh's `MeshBVH` options or
 * meshq's own. Honoured: `maxLeafTris` / `maxLeafSize` (largest leaf), `maxDepth` (deepest
 * level, root 1), `strategy` (`CENTER` → centre splits, meshq's `quality: 'fast'`; `SAH` →
 * binned SAH, the default), `indirect` (meshq never reorders the geometry's index, so either
 * value gives what three-mesh-bvh's `indirect: true` does), `setBoundingBox` (default true:
 * the geometry's bounding box is set from the tree), `verbose` and `onProgress` (called with 1
 * when the build is done). Anything else, `strategy: AVERAGE` and `range` included, throws
 * naming the option, rather than being ignored.
 */
function buildOptions(options) {
  if (options === undefined || options === null) return { meshq: undefined, setBoundingBox: true };
  if (typeof options !== 'object') throw new TypeError(`computeBoundsTree options must be an object, got ${typeof options}`);
  const meshq = {};
  let setBoundingBox = true;
  let onProgress = null;
  for (const [key, value] of Object.entries(options)) {
    if (value === undefined) continue;
    switch (key) {
      case 'structure': case 'quality': case 'bins': case 'maxDepth':
        meshq[key] = value;
        break;
      case 'maxLeafTris': case 'maxLeafSize':
        if (meshq.maxLeafSize !== undefined && meshq.maxLeafSize !== value) {
          throw new RangeError(`maxLeafTris (${options.maxLeafTris}) and maxLeafSize (${options.maxLeafSize}) disagree`);
        }
        meshq.maxLeafSize = value;
        break;
      case 'strategy':
        if (value === CENTER) meshq.quality ??= 'fast';
        else if (value === SAH) meshq.quality ??= 'balanced';
        else throw new RangeError(`strategy ${value} is not supported by meshq: use CENTER (${CENTER}) or SAH (${SAH})`);
        break;
      case 'indirect': case 'verbose':
        if (typeof value !== 'boolean') throw new TypeError(`${key} must be true or false`);
        break;
      case 'setBoundingBox':
        setBoundingBox = Boolean(value);
        break;
      case 'onProgress':
        if (typeof value !== 'function') throw new TypeError('onProgress must be a function');
        onProgress = value;
        break;
      default:
        throw new TypeError(`computeBoundsTree: option ${key} is not supported by meshq`);
    }
  }
  return { meshq, setBoundingBox, onProgress };
}

/**
 * The geometry's tree when it has one that was not freed: a tree freed by hand
 * (`geometry.boundsTree.free()`) counts as none, so the next `computeBoundsTree` replaces it
 * and raycasts fall back to three's own until then. (wasm-bindgen zeroes `__wbg_ptr` on
 * `free`; the version is pinned, and `web/tests/three-dropin.mjs` checks this.)
 */
function liveTree(geometry) {
  const tree = geometry.boundsTree;
  return tree && tree.__wbg_ptr !== 0 ? tree : null;
}

/**
 * Builds `this.boundsTree` (a MeshBvh) from a BufferGeometry's position and index arrays, with
 * three-mesh-bvh's options or meshq's (see `buildOptions`).
 */
export function computeBoundsTree(options) {
  const { meshq, setBoundingBox, onProgress } = buildOptions(options);
  this.disposeBoundsTree?.();
  this.boundsTree = buildFor(this, meshq);
  if (setBoundingBox) {
    const b = this.boundsTree.bounds();
    this.boundingBox ??= new Box3();
    this.boundingBox.min.set(b[0], b[1], b[2]);
    this.boundingBox.max.set(b[3], b[4], b[5]);
  }
  onProgress?.(1);
  return this.boundsTree;
}

/**
 * three-mesh-bvh's `boundsTree.intersectsGeometry(geometry, geometryToBvh)`: whether
 * `geometry`, placed in this tree's frame by the Matrix4 `geometryToBvh`, meets this tree's
 * mesh (touching counts). Uses `geometry.boundsTree` when it has one, else builds one for
 * the call and frees it. Throws a `RangeError` when the two meshes pile so many triangles in
 * one place that `intersectsMesh`'s default pair budget is spent before an answer.
 */
MeshBvh.prototype.intersectsGeometry = function intersectsGeometry(geometry, geometryToBvh) {
  const own = liveTree(geometry);
  const temporary = own ? null : buildFor(geometry);
  try {
    return this.intersectsMesh(own ?? temporary, geometryToBvh.elements);
  } finally {
    temporary?.free();
  }
};

/**
 * three-mesh-bvh's `boundsTree.intersectsSphere(sphere)`: whether a triangle comes within the
 * `Sphere`'s radius of its centre (touching counts).
 */
MeshBvh.prototype.intersectsSphere = function intersectsSphere(sphere) {
  const c = sphere.center;
  return this.overlapsSphere([c.x, c.y, c.z], sphere.radius);
};

/**
 * three-mesh-bvh's `boundsTree.intersectsBox(box, boxToMesh)`: whether a triangle shares a
 * point with the `Box3` placed in the mesh's frame by the Matrix4 `boxToMesh` (rotation,
 * translation and scale; a matrix with shear or a zero scale throws, since the box is then
 * no longer a box).
 */
MeshBvh.prototype.intersectsBox = function intersectsBox(box, boxToMesh) {
  const e = boxToMesh.elements;
  const columns = [[e[0], e[1], e[2]], [e[4], e[5], e[6]], [e[8], e[9], e[10]]];
  const lengths = columns.map((c) => Math.hypot(c[0], c[1], c[2]));
  const dotOf = (p, q) => p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
  for (const [i, j] of [[0, 1], [1, 2], [0, 2]]) {
    if (!(lengths[i] > 0) || Math.abs(dotOf(columns[i], columns[j])) > 1e-5 * lengths[i] * lengths[j]) {
      throw new Error('intersectsBox: boxToMesh must be a rotation, translation and scale (no shear, no zero scale)');
    }
  }
  const center = box.getCenter(new Vector3()).applyMatrix4(boxToMesh);
  const half = box.getSize(new Vector3()).multiplyScalar(0.5);
  const axes = columns.flatMap((c, i) => c.map((x) => x / lengths[i]));
  const halfExtents = [half.x * lengths[0], half.y * lengths[1], half.z * lengths[2]];
  return this.overlapsOrientedBox([center.x, center.y, center.z], axes, halfExtents);
};

/** `shapecast`'s answers from `intersectsBounds`, as in three-mesh-bvh. */
export const NOT_INTERSECTED = 0;
export const INTERSECTED = 1;
export const CONTAINED = 2;

/**
 * three-mesh-bvh's `boundsTree.shapecast({ intersectsBounds, intersectsTriangle,
 * boundsTraverseOrder })`: walks the BVH depth first. `intersectsBounds(box, isLeaf, score,
 * depth, nodeIndex)` answers `NOT_INTERSECTED` (or false: skip the node), `INTERSECTED` (or
 * true: go in) or `CONTAINED` (every triangle below is offered with `contained` true, no more
 * boxes asked). `intersectsTriangle(triangle, triangleIndex, contained, depth)` gets a
 * `THREE.Triangle` (reused between calls) and ends the walk by returning true, which
 * `shapecast` then returns. With `boundsTraverseOrder(box)`, the child with the lower score
 * is walked first. `intersectsRange` is not supported (throws): triangles are offered one by
 * one.
 */
MeshBvh.prototype.shapecast = function shapecast(callbacks) {
  const { intersectsBounds, intersectsTriangle, boundsTraverseOrder, intersectsRange } = callbacks;
  if (intersectsRange) throw new Error('shapecast: intersectsRange is not supported; use intersectsTriangle');
  if (typeof intersectsBounds !== 'function') throw new Error('shapecast: intersectsBounds is required');
  const tree = (this._meshqTree ??= this.treeArrays());
  const positions = (this._meshqPositions ??= this.vertexPositions());
  const indices = (this._meshqIndices ??= this.indices());
  const { boxes, first, count, order } = tree;
  const box = new Box3();
  const triangle = new Triangle();
  const setBox = (node) => {
    box.min.set(boxes[6 * node], boxes[6 * node + 1], boxes[6 * node + 2]);
    box.max.set(boxes[6 * node + 3], boxes[6 * node + 4], boxes[6 * node + 5]);
    return box;
  };
  const offer = (slot, contained, depth) => {
    const t = order[slot];
    const corner = (k, target) => {
      const v = indices[3 * t + k];
      return target.set(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    };
    corner(0, triangle.a); corner(1, triangle.b); corner(2, triangle.c);
    return Boolean(intersectsTriangle?.(triangle, t, contained, depth));
  };
  // Every triangle below `node`, offered as contained.
  const offerAll = (node, depth) => {
    if (count[node] > 0) {
      for (let s = first[node]; s < first[node] + count[node]; s++) if (offer(s, true, depth)) return true;
      return false;
    }
    return offerAll(first[node], depth + 1) || offerAll(first[node] + 1, depth + 1);
  };
  const visit = (node, depth) => {
    const isLeaf = count[node] > 0;
    const score = boundsTraverseOrder ? boundsTraverseOrder(setBox(node)) : 0;
    const answer = intersectsBounds(setBox(node), isLeaf, score, depth, node);
    if (!answer) return false;
    if (answer === CONTAINED) return offerAll(node, depth);
    if (isLeaf) {
      for (let s = first[node]; s < first[node] + count[node]; s++) if (offer(s, false, depth)) return true;
      return false;
    }
    let [near, far] = [first[node], first[node] + 1];
    if (boundsTraverseOrder && boundsTraverseOrder(setBox(far)) < boundsTraverseOrder(setBox(near))) {
      [near, far] = [far, near];
    }
    return visit(near, depth + 1) || visit(far, depth + 1);
  };
  return count.length > 0 && visit(0, 0);
};

/** A side from three-mesh-bvh's `materialOrSide` argument (a material, a side constant, or
 *  omitted for `FrontSide`, three-mesh-bvh's default). */
function sideOf(materialOrSide) {
  if (materialOrSide === undefined || materialOrSide === null) return FrontSide;
  return typeof materialOrSide === 'number' ? materialOrSide : materialOrSide.side;
}

/** The index of each tree's mesh, read once (three-mesh-bvh's `face` names its corners). */
const treeIndices = new WeakMap();
function cornersOf(tree, triangle) {
  let indices = treeIndices.get(tree);
  if (!indices) {
    indices = tree.indices();
    treeIndices.set(tree, indices);
  }
  return [indices[3 * triangle], indices[3 * triangle + 1], indices[3 * triangle + 2]];
}

/** A hit as three-mesh-bvh reports one, in the tree's frame. */
function localIntersection(tree, ray, t, triangle, u, v) {
  const [ia, ib, ic] = cornersOf(tree, triangle);
  const positions = tree.vertexPositionsCached ??= tree.vertexPositions();
  const at = (i, target) => target.set(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
  const normal = new Vector3();
  Triangle.getNormal(at(ia, a), at(ib, b), at(ic, c), normal);
  return {
    distance: t * ray.direction.length(),
    point: ray.direction.clone().multiplyScalar(t).add(ray.origin),
    face: { a: ia, b: ib, c: ic, normal, materialIndex: 0 },
    faceIndex: triangle,
    barycoord: new Vector3(1 - u - v, u, v),
  };
}

const coreRaycast = MeshBvh.prototype.raycast;

/**
 * Two forms. three-mesh-bvh's `boundsTree.raycast(ray, materialOrSide = FrontSide, near = 0,
 * far = Infinity)` (a `THREE.Ray`, in the tree's frame) returns every hit as
 * `{ distance, point, face, faceIndex, barycoord }`, nearest first. meshq's own
 * `raycast(origin, direction, near, far, side)` returns the closest hit or `null`.
 */
MeshBvh.prototype.raycast = function raycast(first, ...rest) {
  if (first?.origin === undefined) return coreRaycast.call(this, first, ...rest);
  const [materialOrSide, near, far] = rest;
  return this.raycastAll(first.origin, first.direction, near, far, sideOf(materialOrSide))
    .map((hit) => localIntersection(this, first, hit.t, hit.triangle, hit.u, hit.v));
};

/** three-mesh-bvh's `boundsTree.raycastFirst(ray, materialOrSide = FrontSide, near, far)`:
 *  the closest hit as `raycast` reports hits, or `null`. */
MeshBvh.prototype.raycastFirst = function raycastFirst(ray, materialOrSide, near, far) {
  const o = ray.origin;
  const d = ray.direction;
  const hit = this.raycastXyz(o.x, o.y, o.z, d.x, d.y, d.z, near, far, sideOf(materialOrSide));
  return hit && localIntersection(this, ray, hit.t, hit.triangle, hit.u, hit.v);
};

/**
 * three-mesh-bvh's `boundsTree.closestPointToPoint(point, target = {}, minThreshold = 0,
 * maxThreshold = Infinity)`: fills `target` with `{ point, distance, faceIndex }` for the
 * surface point nearest `point` within `maxThreshold`, or returns `null`. The answer is always
 * the exact nearest point (so `minThreshold`, an early-exit hint, changes nothing).
 */
MeshBvh.prototype.closestPointToPoint = function closestPointToPoint(point, target = {}, minThreshold = 0, maxThreshold = Infinity) {
  const found = this.closestPoint(point, maxThreshold);
  if (!found) return null;
  target.point ??= new Vector3();
  target.point.set(found.point.x, found.point.y, found.point.z);
  target.distance = found.distance;
  target.faceIndex = found.triangle;
  return target;
};

/** three-mesh-bvh's `boundsTree.getBoundingBox(target)`: the tree's bounds as a `Box3`. */
MeshBvh.prototype.getBoundingBox = function getBoundingBox(target = new Box3()) {
  const b = this.bounds();
  target.min.set(b[0], b[1], b[2]);
  target.max.set(b[3], b[4], b[5]);
  return target;
};

/** Not supported: meshq trees are rebuilt, not refitted. Throws, naming what to do instead. */
MeshBvh.prototype.refit = function refit() {
  throw new Error('refit is not supported by meshq: call geometry.computeBoundsTree() again after moving vertices');
};

/**
 * three-mesh-bvh's `boundsTree.closestPointToGeometry(geometry, geometryToBvh, target1 = {},
 * target2 = {}, minThreshold = 0, maxThreshold = Infinity)`: the closest pair of points of this
 * tree's mesh and `geometry`, placed in this tree's frame by the Matrix4 `geometryToBvh`.
 * Fills `target1` with `{ point, distance, faceIndex }` on this mesh (in its frame) and, when
 * given, `target2` with the same on `geometry` (its point in `geometry`'s own frame, its
 * distance measured there), and returns `target1`; `null` when nothing lies within
 * `maxThreshold`. `minThreshold` ends the search at the first pair found that close. Uses
 * `geometry.boundsTree` when it has one, else builds one for the call and frees it. Meshes
 * that meet are at distance 0.
 */
MeshBvh.prototype.closestPointToGeometry = function closestPointToGeometry(geometry, geometryToBvh, target1 = {}, target2 = {}, minThreshold = 0, maxThreshold = Infinity) {
  const own = liveTree(geometry);
  const temporary = own ? null : buildFor(geometry);
  let found;
  try {
    found = this.distanceToMesh(own ?? temporary, geometryToBvh.elements, maxThreshold, minThreshold);
  } finally {
    temporary?.free();
  }
  if (!found) return null;
  target1.point ??= new Vector3();
  target1.point.set(found.pointA.x, found.pointA.y, found.pointA.z);
  target1.distance = found.distance;
  target1.faceIndex = found.triangleA;
  if (target2) {
    const toGeometry = new Matrix4().copy(geometryToBvh).invert();
    target2.point ??= new Vector3();
    target2.point.set(found.pointB.x, found.pointB.y, found.pointB.z).applyMatrix4(toGeometry);
    const onThis = new Vector3(found.pointA.x, found.pointA.y, found.pointA.z).applyMatrix4(toGeometry);
    target2.distance = onThis.distanceTo(target2.point);
    target2.faceIndex = found.triangleB;
  }
  return target1;
};

/** Frees `this.boundsTree`. */
export function disposeBoundsTree() {
  liveTree(this)?.free();
  this.boundsTree = null;
}

const inverse = new Matrix4();
const origin = new Vector3();
const end = new Vector3();
const direction = new Vector3();
const a = new Vector3();
const b = new Vector3();
const c = new Vector3();

function corner(geometry, triangle, k) {
  return geometry.index ? geometry.index.getX(3 * triangle + k) : 3 * triangle + k;
}

const localRay = new Ray();
const localPoint = new Vector3();

/**
 * The intersection of triangle `triangle` (found by meshq) as three's own raycast reports it,
 * bit for bit: three's ray–triangle test in the mesh's space with the material's `side`, the
 * point taken to the world, its distance from the ray's origin checked against near/far, and
 * the barycentric coordinates, uv, uv1 and normals interpolated as three does. `null` where
 * three's test misses the triangle (a ray grazing an edge meshq's watertight test assigns to
 * this triangle), as three would not list it either.
 */
function intersection(mesh, raycaster, side, triangle, materialIndex = 0) {
  const geometry = mesh.geometry;
  const ia = corner(geometry, triangle, 0);
  const ib = corner(geometry, triangle, 1);
  const ic = corner(geometry, triangle, 2);
  mesh.getVertexPosition(ia, a);
  mesh.getVertexPosition(ib, b);
  mesh.getVertexPosition(ic, c);
  const hitLocal = side === BackSide
    ? localRay.intersectTriangle(c, b, a, true, localPoint)
    : localRay.intersectTriangle(a, b, c, side === FrontSide, localPoint);
  if (hitLocal === null) return null;
  const point = localPoint.clone().applyMatrix4(mesh.matrixWorld);
  const distance = raycaster.ray.origin.distanceTo(point);
  if (distance < raycaster.near || distance > raycaster.far) return null;
  const hit = { distance, point, object: mesh };
  const barycoord = new Vector3();
  Triangle.getBarycoord(localPoint, a, b, c, barycoord);
  const { uv, uv1, normal: normals } = geometry.attributes;
  if (uv) hit.uv = Triangle.getInterpolatedAttribute(uv, ia, ib, ic, barycoord, new Vector2());
  if (uv1) hit.uv1 = Triangle.getInterpolatedAttribute(uv1, ia, ib, ic, barycoord, new Vector2());
  if (normals) {
    hit.normal = Triangle.getInterpolatedAttribute(normals, ia, ib, ic, barycoord, new Vector3());
    if (hit.normal.dot(localRay.direction) > 0) hit.normal.multiplyScalar(-1);
  }
  const face = { a: ia, b: ib, c: ic, normal: new Vector3(), materialIndex: 0 };
  Triangle.getNormal(a, b, c, face.normal);
  hit.face = face;
  hit.barycoord = barycoord;
  hit.faceIndex = triangle;
  face.materialIndex = materialIndex;
  return hit;
}

/** The triangles three would test, as `{ from, to, side, materialIndex }` ranges of triangle
 *  indices (`to` exclusive): `null` when that is every triangle with the one material,
 *  `undefined` when a range does not start on a whole triangle (three then reads corners across
 *  triangles, which only its own raycast reproduces). */
function triangleRanges(geometry, material) {
  const count = geometry.index ? geometry.index.count : geometry.attributes.position.count;
  const whole = Math.floor(count / 3);
  const drawStart = geometry.drawRange.start;
  const drawEnd = drawStart + geometry.drawRange.count;
  // Corner positions [start, end) as three loops over them: a triangle per start position.
  const range = (start, end, side, materialIndex) => {
    start = Math.max(0, start);
    end = Math.min(count, end);
    if (start % 3 !== 0) return undefined;
    return { from: start / 3, to: Math.min(whole, Math.ceil(end / 3)), side, materialIndex };
  };
  if (!Array.isArray(material)) {
    if (drawStart <= 0 && drawEnd >= count) return null;
    const only = range(drawStart, drawEnd, material.side, 0);
    return only && [only];
  }
  const ranges = [];
  for (const group of geometry.groups) {
    const groupMaterial = material[group.materialIndex];
    if (!groupMaterial) continue;
    const r = range(Math.max(group.start, drawStart),
      Math.min(group.start + group.count, drawEnd), groupMaterial.side, group.materialIndex);
    if (!r) return undefined;
    ranges.push(r);
  }
  return ranges;
}

/** Whether a hit on `triangle` counts for a material with `side`: three keeps a front-side hit
 *  when the ray meets the face against its normal, a back-side hit when along it. */
function facingAllows(geometry, triangle, side) {
  if (side === DoubleSide) return true;
  const position = geometry.attributes.position;
  a.fromBufferAttribute(position, corner(geometry, triangle, 0));
  b.fromBufferAttribute(position, corner(geometry, triangle, 1));
  c.fromBufferAttribute(position, corner(geometry, triangle, 2));
  const facing = c.sub(a).cross(b.sub(a)).dot(direction); // −(normal · direction)
  return side === FrontSide ? facing > 0 : facing < 0;
}

/** Replacement for `THREE.Mesh.prototype.raycast` that uses `geometry.boundsTree`. */
export function acceleratedRaycast(raycaster, intersects) {
  const geometry = this.geometry;
  const bvh = liveTree(geometry);
  const material = this.material;
  const ranges = bvh && material !== undefined ? triangleRanges(geometry, material) : undefined;
  if (ranges === undefined || this.isInstancedMesh || this.isSkinnedMesh ||
      (this.morphTargetInfluences && this.morphTargetInfluences.length)) {
    threeRaycast.call(this, raycaster, intersects);
    return;
  }
  // The ray in the mesh's own space. Transforming two points keeps t the same in both spaces
  // (the map is affine), so t stays the world distance along three's unit direction.
  inverse.copy(this.matrixWorld).invert();
  origin.copy(raycaster.ray.origin).applyMatrix4(inverse);
  end.copy(raycaster.ray.origin).add(raycaster.ray.direction).applyMatrix4(inverse);
  direction.subVectors(end, origin);
  // three's own local ray, for recomputing each hit with its math.
  localRay.copy(raycaster.ray).applyMatrix4(inverse);
  if (ranges === null) {
    raycastWhole(this, bvh, raycaster, intersects, material.side);
  } else {
    raycastRanges(this, bvh, raycaster, intersects, ranges);
  }
}

/** Every triangle, one material: the culling happens in meshq. */
function raycastWhole(mesh, bvh, raycaster, intersects, side) {
  if (raycaster.firstHitOnly === true) {
    const first = bvh.raycastXyz(origin.x, origin.y, origin.z, direction.x, direction.y,
      direction.z, raycaster.near, raycaster.far, side);
    const hit = first && intersection(mesh, raycaster, side, first.triangle);
    if (hit) intersects.push(hit);
    return;
  }
  for (const found of bvh.raycastAll(origin, direction, raycaster.near, raycaster.far, side)) {
    const hit = intersection(mesh, raycaster, side, found.triangle);
    if (hit) intersects.push(hit);
  }
}

/** Only the triangles of `ranges`, each with its material's side: every hit is listed nearest
 *  first and filtered here. A triangle in two ranges is reported twice, as three does. */
function raycastRanges(mesh, bvh, raycaster, intersects, ranges) {
  const sides = new Set(ranges.map((r) => r.side));
  // One side for all: meshq culls; mixed sides: meshq keeps both faces and each range filters.
  const side = sides.size === 1 ? ranges[0].side : DoubleSide;
  const found = [];
  for (const { triangle } of bvh.raycastAll(origin, direction, raycaster.near, raycaster.far, side)) {
    for (const r of ranges) {
      if (triangle < r.from || triangle >= r.to) continue;
      if (side === DoubleSide && !facingAllows(mesh.geometry, triangle, r.side)) continue;
      const hit = intersection(mesh, raycaster, r.side, triangle, r.materialIndex);
      if (hit) found.push(hit);
    }
  }
  if (raycaster.firstHitOnly !== true) {
    intersects.push(...found);
    return;
  }
  // The nearest by three's distance (a triangle in two groups has two, differing in the last
  // bits), the earlier on a tie, as three's sorted list has it.
  let nearest = null;
  for (const hit of found) if (nearest === null || hit.distance < nearest.distance) nearest = hit;
  if (nearest) intersects.push(nearest);
}

export { MeshBvh };
