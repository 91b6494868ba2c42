// Types of the meshq three.js drop-in (`meshq-wasm/three`).
//
// `BufferGeometry.boundsTree`, `computeBoundsTree` and `disposeBoundsTree` are declared on
// three's `BufferGeometry` by `meshq-wasm/three-augment` (import it once), not here: three-mesh-bvh
// declares the same members with its own types, and TypeScript refuses two declarations of one
// member with different types, so a project that has both installed during a migration keeps
// compiling with this file alone.
import type { Box3, BufferGeometry, Intersection, Material, Matrix4, Mesh, Ray, Raycaster, Side, Sphere, Triangle, Vector3 } from 'three';
import type { MeshBvh } from './meshq_wasm.js';

/**
 * Build settings; every field is optional. `quality`: `'balanced'` (binned SAH, the default),
 * `'fast'` (centre splits like three-mesh-bvh's default: quicker to build, somewhat
 * slower rays) or `'high'`.
 */
export interface BuildOptions {
  quality?: 'fast' | 'balanced' | 'high';
  structure?: 'bvh' | 'kdtree' | 'octree' | 'grid';
  maxLeafSize?: number;
  bins?: number;
  maxDepth?: number;
  /** three-mesh-bvh's names: `maxLeafTris` is `maxLeafSize`; `strategy` CENTER or SAH. */
  maxLeafTris?: number;
  strategy?: 0 | 2;
  indirect?: boolean;
  setBoundingBox?: boolean;
  verbose?: boolean;
  onProgress?: (progress: number) => void;
}

/** three-mesh-bvh's split strategies (AVERAGE is refused by computeBoundsTree). */
export const CENTER: 0;
export const AVERAGE: 1;
export const SAH: 2;

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

/** A hit as the bounds tree's `raycast` and `raycastFirst` report it, in the tree's frame. */
export interface LocalHit {
  distance: number;
  point: Vector3;
  face: { a: number; b: number; c: number; normal: Vector3; materialIndex: number };
  faceIndex: number;
  barycoord: Vector3;
}

/** What `closestPointToPoint` fills. */
export interface ClosestPointTarget {
  point: Vector3;
  distance: number;
  faceIndex: number;
}

declare module './meshq_wasm.js' {
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
    /** three-mesh-bvh's `raycast`: every hit of `ray` (in the tree's frame), nearest first. */
    raycast(ray: Ray, materialOrSide?: Material | Side, near?: number, far?: number): LocalHit[];
    /** three-mesh-bvh's `raycastFirst`: the closest hit, or null. */
    raycastFirst(ray: Ray, materialOrSide?: Material | Side, near?: number, far?: number): LocalHit | null;
    /** three-mesh-bvh's `closestPointToPoint`: `target` filled, or null beyond `maxThreshold`. */
    closestPointToPoint(point: Vector3, target?: Partial<ClosestPointTarget>, minThreshold?: number, maxThreshold?: number): ClosestPointTarget | null;
    /** three-mesh-bvh's `getBoundingBox`. */
    getBoundingBox(target?: Box3): Box3;
    /** Not supported: throws (rebuild with `computeBoundsTree`). */
    refit(): never;
    /**
     * three-mesh-bvh's `closestPointToGeometry`: the closest pair of points of this mesh and
     * `geometry` placed by `geometryToBvh`; `target1` (this mesh, its frame) filled and
     * returned, `target2` (the geometry, its own frame) filled when given; null beyond
     * `maxThreshold`. `minThreshold` stops at the first pair that close.
     */
    closestPointToGeometry(geometry: BufferGeometry, geometryToBvh: Matrix4, target1?: Partial<ClosestPointTarget>, target2?: Partial<ClosestPointTarget> | null, minThreshold?: number, maxThreshold?: number): ClosestPointTarget | null;
  }
}

declare module 'three' {
  interface Raycaster {
    /** Stop at the closest hit (three-mesh-bvh's flag, declared identically). */
    firstHitOnly?: boolean;
  }
}
