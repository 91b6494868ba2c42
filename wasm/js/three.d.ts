// Types of the meshq three.js drop-in (three.js / three.mjs).
import type { Box3, BufferGeometry, Intersection, Matrix4, Mesh, Raycaster, Sphere } from 'three';
import type { MeshBvh } from './meshq_wasm';

/**
 * Build settings; every field is optional. `quality`: `'balanced'` (binned SAH, the default),
 * `'fast'` (centre splits like three-mesh-bvh's default: about 4× quicker to build, somewhat
 * slower rays) or `'high'`.
 */
export interface BuildOptions {
  quality?: 'fast' | 'balanced' | 'high';
  maxLeafSize?: number;
  bins?: number;
}

/** Builds `this.boundsTree` from the geometry's position and index arrays. */
export function computeBoundsTree(this: BufferGeometry, options?: BuildOptions): MeshBvh;
/** Frees `this.boundsTree`. */
export function disposeBoundsTree(this: BufferGeometry): void;
/**
 * Replacement for `THREE.Mesh.prototype.raycast`: the same `intersects` as three's, honouring
 * `near`/`far`, `firstHitOnly`, the material's `side`, the draw range, and groups with an array
 * of materials. Falls back to three's raycast for morph targets, skinning, instancing, and
 * ranges that start inside a triangle.
 */
export function acceleratedRaycast(this: Mesh, raycaster: Raycaster, intersects: Intersection[]): void;
export { MeshBvh };

declare module './meshq_wasm' {
  interface MeshBvh {
    /**
     * three-mesh-bvh's `intersectsGeometry`: whether `geometry`, placed in this tree's frame
     * by `geometryToBvh`, meets this tree's mesh (touching counts). Uses
     * `geometry.boundsTree` when present, else builds a temporary one.
     */
    intersectsGeometry(geometry: BufferGeometry, geometryToBvh: Matrix4): boolean;
    /** three-mesh-bvh's `intersectsSphere`: whether a triangle touches the sphere. */
    intersectsSphere(sphere: Sphere): boolean;
    /**
     * three-mesh-bvh's `intersectsBox`: whether a triangle touches `box` placed by
     * `boxToMesh` (rotation, translation and scale; shear throws).
     */
    intersectsBox(box: Box3, boxToMesh: Matrix4): boolean;
  }
}

declare module 'three' {
  interface BufferGeometry {
    boundsTree?: MeshBvh | null;
    computeBoundsTree(options?: BuildOptions): MeshBvh;
    disposeBoundsTree(): void;
  }
  interface Raycaster {
    firstHitOnly?: boolean;
  }
}
