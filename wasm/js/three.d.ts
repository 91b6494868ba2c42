// Types of the meshq three.js drop-in (three.js / three.mjs).
import type { Box3, BufferGeometry, Intersection, Matrix4, Mesh, Raycaster, Sphere, Triangle } from 'three';
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

/** `shapecast`'s answers from `intersectsBounds`, as in three-mesh-bvh. */
export const NOT_INTERSECTED: 0;
export const INTERSECTED: 1;
export const CONTAINED: 2;

/** The callbacks of `shapecast` (three-mesh-bvh's, without `intersectsRange`). */
export interface ShapecastCallbacks {
  intersectsBounds: (box: Box3, isLeaf: boolean, score: number, depth: number, nodeIndex: number) => boolean | 0 | 1 | 2;
  intersectsTriangle?: (triangle: Triangle, triangleIndex: number, contained: boolean, depth: number) => boolean | void;
  boundsTraverseOrder?: (box: Box3) => number;
}

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
    /** three-mesh-bvh's `shapecast`: true when `intersectsTriangle` ended the walk. */
    shapecast(callbacks: ShapecastCallbacks): boolean;
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
