// A project migrating from three-mesh-bvh, with both packages' typings in one compilation:
// three-mesh-bvh's declarations of BufferGeometry.boundsTree / computeBoundsTree stand, and
// meshq's drop-in typings must coexist with them (web/tests/types.mjs).
import * as THREE from 'three';
import { MeshBVH, acceleratedRaycast as bvhRaycast, computeBoundsTree as bvhCompute } from 'three-mesh-bvh';
import { acceleratedRaycast, computeBoundsTree, disposeBoundsTree } from 'meshq-wasm/three';
import { MeshBvh } from 'meshq-wasm';

export function migrating(geometry: THREE.BufferGeometry, useMeshq: boolean): number {
  if (useMeshq) {
    const tree: MeshBvh = computeBoundsTree.call(geometry, { maxLeafTris: 10 });
    THREE.Mesh.prototype.raycast = acceleratedRaycast;
    const hit = tree.raycastFirst(new THREE.Ray(), THREE.FrontSide);
    disposeBoundsTree.call(geometry);
    return hit?.distance ?? 0;
  }
  THREE.BufferGeometry.prototype.computeBoundsTree = bvhCompute;
  THREE.Mesh.prototype.raycast = bvhRaycast;
  geometry.computeBoundsTree();
  const theirs = new MeshBVH(geometry);
  return theirs.raycast(new THREE.Ray()).length;
}
