// meshq for three.js: a drop-in for three-mesh-bvh's computeBoundsTree / acceleratedRaycast.
//
//   import { computeBoundsTree, disposeBoundsTree, acceleratedRaycast } from 'meshq-wasm/three.js';
//   THREE.BufferGeometry.prototype.computeBoundsTree = computeBoundsTree;
//   THREE.BufferGeometry.prototype.disposeBoundsTree = disposeBoundsTree;
//   THREE.Mesh.prototype.raycast = acceleratedRaycast;
//   geometry.computeBoundsTree();          // or geometry.boundsTree = MeshBvh.fromBlob(bytes)
//
// Raycaster results keep three's shape (distance, point, face, faceIndex, object, barycoord,
// uv, normal), respect raycaster.near / far, the material's side and raycaster.firstHitOnly.
// Meshes without a bounds tree, with an array of materials, morph targets or skinning, and
// instanced meshes fall back to three's own raycast.
import { Mesh, Matrix4, Triangle, Vector2, Vector3 } from 'three';
import { MeshBvh } from './meshq_wasm.js';

const threeRaycast = Mesh.prototype.raycast;

/** Builds `this.boundsTree` (a MeshBvh) from a BufferGeometry's position and index arrays. */
export function computeBoundsTree(options) {
  const position = this.getAttribute('position');
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
  let index = this.index ? this.index.array : null;
  if (index && !(index instanceof Uint32Array || index instanceof Uint16Array)) {
    index = Uint32Array.from(index);
  }
  this.disposeBoundsTree?.();
  this.boundsTree = MeshBvh.build(positions, index, options);
  return this.boundsTree;
}

/** Frees `this.boundsTree`. */
export function disposeBoundsTree() {
  if (this.boundsTree) this.boundsTree.free();
  this.boundsTree = null;
}

const inverse = new Matrix4();
const origin = new Vector3();
const end = new Vector3();
const direction = new Vector3();
const a = new Vector3();
const b = new Vector3();
const c = new Vector3();
const ta = new Vector2();
const tb = new Vector2();
const tc = new Vector2();

function corner(geometry, triangle, k) {
  return geometry.index ? geometry.index.getX(3 * triangle + k) : 3 * triangle + k;
}

/** `attribute` at the barycentric point `barycoord` of corners `ia, ib, ic`, into `target`
 *  (scratch vectors `pa, pb, pc` of the same size). */
function interpolate(attribute, ia, ib, ic, barycoord, target, pa, pb, pc) {
  pa.fromBufferAttribute(attribute, ia);
  pb.fromBufferAttribute(attribute, ib);
  pc.fromBufferAttribute(attribute, ic);
  return target
    .addScaledVector(pa, barycoord.x)
    .addScaledVector(pb, barycoord.y)
    .addScaledVector(pc, barycoord.z);
}

function intersection(mesh, raycaster, t, triangle, u, v) {
  const point = direction.clone().multiplyScalar(t).add(origin).applyMatrix4(mesh.matrixWorld);
  const distance = raycaster.ray.origin.distanceTo(point);
  if (distance < raycaster.near || distance > raycaster.far) return null;
  const geometry = mesh.geometry;
  const ia = corner(geometry, triangle, 0);
  const ib = corner(geometry, triangle, 1);
  const ic = corner(geometry, triangle, 2);
  const position = geometry.attributes.position;
  a.fromBufferAttribute(position, ia);
  b.fromBufferAttribute(position, ib);
  c.fromBufferAttribute(position, ic);
  const normal = new Vector3();
  Triangle.getNormal(a, b, c, normal);
  const barycoord = new Vector3(1 - u - v, u, v);
  const hit = {
    distance,
    point,
    object: mesh,
    face: { a: ia, b: ib, c: ic, normal, materialIndex: 0 },
    faceIndex: triangle,
    barycoord,
  };
  const uv = geometry.attributes.uv;
  if (uv) hit.uv = interpolate(uv, ia, ib, ic, barycoord, new Vector2(), ta, tb, tc);
  const normals = geometry.attributes.normal;
  if (normals) {
    // As three does: interpolated, not renormalised, facing the ray.
    hit.normal = interpolate(normals, ia, ib, ic, barycoord, new Vector3(), a, b, c);
    if (hit.normal.dot(direction) > 0) hit.normal.multiplyScalar(-1);
  }
  return hit;
}

/** Replacement for `THREE.Mesh.prototype.raycast` that uses `geometry.boundsTree`. */
export function acceleratedRaycast(raycaster, intersects) {
  const bvh = this.geometry.boundsTree;
  const material = this.material;
  if (!bvh || material === undefined || Array.isArray(material) || this.isInstancedMesh ||
      this.isSkinnedMesh || (this.morphTargetInfluences && this.morphTargetInfluences.length)) {
    threeRaycast.call(this, raycaster, intersects);
    return;
  }
  // The ray in the mesh's own space. Transforming two points keeps t the same in both spaces
  // (the map is affine), so t stays the world distance along three's unit direction.
  inverse.copy(this.matrixWorld).invert();
  origin.copy(raycaster.ray.origin).applyMatrix4(inverse);
  end.copy(raycaster.ray.origin).add(raycaster.ray.direction).applyMatrix4(inverse);
  direction.subVectors(end, origin);
  const side = material.side;
  if (raycaster.firstHitOnly === true) {
    const first = bvh.raycastXyz(origin.x, origin.y, origin.z, direction.x, direction.y,
      direction.z, raycaster.near, raycaster.far, side);
    const hit = first && intersection(this, raycaster, first.distance, first.triangle, first.u, first.v);
    if (hit) intersects.push(hit);
    return;
  }
  const all = bvh.raycastAll(origin.x, origin.y, origin.z, direction.x, direction.y, direction.z,
    raycaster.near, raycaster.far, side);
  for (let k = 0; k < all.length; k += 4) {
    const hit = intersection(this, raycaster, all[k], all[k + 1], all[k + 2], all[k + 3]);
    if (hit) intersects.push(hit);
  }
}

export { MeshBvh };
