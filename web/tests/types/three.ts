// The three.js drop-in's typings on their own (with meshq's BufferGeometry members from
// 'meshq-wasm/three-augment'), compiled by web/tests/types.mjs.
import * as THREE from 'three';
import 'meshq-wasm/three-augment';
import {
  CONTAINED,
  INTERSECTED,
  NOT_INTERSECTED,
  SAH,
  acceleratedRaycast,
  computeBoundsTree,
  disposeBoundsTree,
  type LocalHit,
} from 'meshq-wasm/three';
import { MeshBvh } from 'meshq-wasm';

THREE.BufferGeometry.prototype.computeBoundsTree = computeBoundsTree;
THREE.BufferGeometry.prototype.disposeBoundsTree = disposeBoundsTree;
THREE.Mesh.prototype.raycast = acceleratedRaycast;

export function dropIn(geometry: THREE.BufferGeometry, blob: Uint8Array): number {
  const tree: MeshBvh = geometry.computeBoundsTree({ maxLeafTris: 8, strategy: SAH });
  geometry.boundsTree = MeshBvh.fromBlob(blob);
  const raycaster = new THREE.Raycaster();
  raycaster.firstHitOnly = true;
  const hits = raycaster.intersectObject(new THREE.Mesh(geometry));
  const first: LocalHit | null = tree.raycastFirst(raycaster.ray, THREE.DoubleSide);
  const every: LocalHit[] = tree.raycast(raycaster.ray);
  const own = tree.raycast([0, 0, 1], [0, 0, -1]);
  const target = tree.closestPointToPoint(new THREE.Vector3(), {});
  const box = tree.getBoundingBox(new THREE.Box3());
  const pair = tree.closestPointToGeometry(geometry, new THREE.Matrix4(), {}, null, 0, 10);
  const meets = tree.intersectsSphere(new THREE.Sphere()) || tree.intersectsBox(box, new THREE.Matrix4())
    || tree.intersectsGeometry(geometry, new THREE.Matrix4());
  const stopped = tree.shapecast({
    intersectsBounds: (b) => (b.isEmpty() ? NOT_INTERSECTED : b.min.x > 0 ? CONTAINED : INTERSECTED),
    intersectsTriangle: (triangle, index) => triangle.getArea() > index,
  });
  geometry.disposeBoundsTree();
  // @ts-expect-error computeBoundsTree takes an options object
  geometry.computeBoundsTree('fast');
  return hits.length + (first?.distance ?? 0) + every.length + (own?.t ?? 0) + (target?.distance ?? 0)
    + (pair?.faceIndex ?? 0) + Number(meets) + Number(stopped);
}
