//! The TypeScript types the exported functions name (through `unchecked_param_type` and
//! `unchecked_return_type`), written into the package's `.d.ts` beside the generated
//! declarations. `web/tests/types/` compiles examples against them with `tsc --noEmit`,
//! including calls that must be refused.

use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TYPES: &'static str = r#"
/** A point or direction: `[x, y, z]` (an array or typed array of three numbers) or an
 *  object with numeric `x`, `y`, `z` such as three.js's `Vector3`. */
export type Vec3Like = ArrayLike<number> | { readonly x: number; readonly y: number; readonly z: number };

/** A 4×4 affine matrix: 16 numbers in column-major order (three.js `Matrix4.elements`), or a
 *  `Matrix4` itself. The bottom row must be `0, 0, 0, 1`. */
export type Matrix4Like = ArrayLike<number> | { readonly elements: ArrayLike<number> };

/** Which faces a ray hits: `0` front only, `1` back only, `2` both (three.js `FrontSide`,
 *  `BackSide`, `DoubleSide`). Counter-clockwise triangles face front. */
export type Side = 0 | 1 | 2;

/** The ray–triangle test: `"watertight"` (the default; no ray slips through a closed mesh),
 *  `"moller-trumbore"`, or `"two-step"` (the plane, then barycentric coordinates). They
 *  differ only at edges shared by two triangles. */
export type TriangleTest = 'watertight' | 'moller-trumbore' | 'two-step';

/** Ray options, in place of a `side` argument: the faces a ray hits and the triangle test,
 *  both optional. */
export interface RayOptions { side?: Side | null; test?: TriangleTest | null }

/** Coordinates in a result. */
export interface XYZ { x: number; y: number; z: number }

/** How `geometry.closestPointTriangle` finds the point: `"regions"` (the default, the
 *  Voronoi-region walk every mesh query uses), `"projection"` (onto the plane, then half-plane
 *  tests) or `"rotation"` (onto a plane, solved in 2D, turned back). */
export type ClosestPointMethod = 'regions' | 'projection' | 'rotation';

/** The point of one triangle nearest a query point (`geometry.closestPointTriangle`): `u`, `v`
 *  weigh the second and third corners; `feature` says where it lies, `featureIndex` which edge
 *  (0 = ab, 1 = bc, 2 = ca) or corner (0 = a, 1 = b, 2 = c); 0 for the face. */
export interface TriangleClosestPoint {
  point: XYZ;
  distance: number;
  u: number;
  v: number;
  feature: 'face' | 'edge' | 'vertex';
  featureIndex: number;
}

/** The point of a segment nearest a query point: at `a + t·(b − a)`. */
export interface SegmentClosestPoint { point: XYZ; t: number; distance: number }

/** The closest points of two segments: `pointA = p1 + s·(q1 − p1)`, `pointB = p2 + t·(q2 − p2)`. */
export interface SegmentPair { pointA: XYZ; pointB: XYZ; s: number; t: number; distance: number }

/** A ray's hit on one triangle: the ray parameter and the weights of the second and third
 *  corners. */
export interface TriangleHit { t: number; u: number; v: number }

/** The entry and exit ray parameters of a ray through a box. */
export interface RaySpan { near: number; far: number }

/** A ray hit. `t` is the ray parameter (the hit is at `origin + t·direction`, `t` in units
 *  of the direction's length); `distance` is the Euclidean distance from the origin to the
 *  hit, `t·|direction|` (so `t` and `distance` agree, up to rounding, for a unit direction).
 *  `u`, `v` weigh the triangle's second and third corners; `normal` is the unit geometric
 *  normal of its front face. */
export interface RayHit {
  t: number;
  distance: number;
  point: XYZ;
  triangle: number;
  u: number;
  v: number;
  normal: XYZ;
}

/** The surface point nearest a query point. `distance` is the Euclidean distance to it. */
export interface ClosestPoint {
  distance: number;
  point: XYZ;
  triangle: number;
  u: number;
  v: number;
  normal: XYZ;
}

/** A signed distance: the surface point nearest a query point, `distance` negative inside
 *  (where the generalized winding number is at least 1/2 in magnitude), and the winding
 *  number that gave the sign. */
export interface SignedDistance extends ClosestPoint {
  windingNumber: number;
}

/** The closest pair of points of two meshes (`MeshBvh.distanceToMesh`): `pointA` on this
 *  mesh, `pointB` on the other, both in this mesh's frame, `distance` between them (0 where
 *  the meshes meet), and the triangles holding them. */
export interface MeshDistance {
  distance: number;
  pointA: XYZ;
  pointB: XYZ;
  triangleA: number;
  triangleB: number;
}

/** Where a swept shape first touches the mesh (`MeshBvh.sweepSphere`, `sweepCapsule`,
 *  `sweepBox`): `t` the fraction of the motion done at contact (0 to 1), `point` on the mesh,
 *  `normal` a unit vector from the mesh toward the shape, and the triangle touched. */
export interface SweepHit {
  t: number;
  point: XYZ;
  normal: XYZ;
  triangle: number;
}

/** A signed-distance volume (`MeshBvh.signedDistanceGrid`): `values` x fastest, then y, then
 *  z, negative inside; sample `(i, j, k)` lies at `origin + spacing·(i, j, k)`. */
export interface SignedDistanceGrid {
  values: Float32Array;
  counts: Uint32Array;
  origin: Float32Array;
  spacing: number;
}

/** Options of `MeshBvh.build`; every field is optional. */
export interface MeshBvhOptions {
  /** Which structure answers (default `'bvh'`); every structure gives the same answers. */
  structure?: 'bvh' | 'kdtree' | 'octree' | 'grid' | null;
  /** BVH build quality: `'balanced'` (binned SAH, the default), `'fast'` (centre splits,
   *  quicker to build, somewhat slower rays) or `'high'`. */
  quality?: 'fast' | 'balanced' | 'high' | null;
  /** Largest BVH leaf, in triangles (default 4). */
  maxLeafSize?: number | null;
  /** SAH bins per axis (default 32). */
  bins?: number | null;
  /** Deepest BVH level (default and maximum 64). */
  maxDepth?: number | null;
  /** Spatial splits for the BVH: `true`, or the room for extra references as a fraction of
   *  the triangle count (0 to 4; `true` is 1). A node may cut space and hold the triangles
   *  crossing the plane on both sides: much faster rays on scenes of long crossing triangles,
   *  the same answers, several times the build time. */
  spatialSplits?: boolean | number | null;
  /** Split BVH nodes by sweep SAH instead of binning: `true` (a cut weighed every 32
   *  triangles) or the number of triangles between weighed cuts (1 weighs every cut). The
   *  triangles are sorted by centroid on each axis: exact split positions, many times the
   *  build time. Not with `spatialSplits`. */
  sweepSah?: boolean | number | null;
}

/** How a blob stores its mesh: `'indexed'` (positions and indices; the default), `'packed'`
 *  (three corners per triangle in leaf order: larger, fastest to query in place) or
 *  `'omitted'` (no mesh; only for readers that have it). */
export type BlobLayout = 'indexed' | 'packed' | 'omitted';

/** Triangle pairs that meet: `pairs` holds triangle indices two by two (this mesh's, then
 *  the other's); `total` counts every pair found, `tested` the triangle pairs tested, and
 *  `overflowed` says some pairs were left out by `maxPairs`. */
export interface PairsResult {
  pairs: Uint32Array;
  total: number;
  tested: number;
  overflowed: boolean;
}

/** The BVH as flat arrays (see `MeshBvh.treeArrays`). */
export interface TreeArrays {
  boxes: Float32Array;
  first: Uint32Array;
  count: Uint32Array;
  order: Uint32Array;
}

/** Options of `remesh`; every field is optional. Give `targetLength` or `targetRatio`, not
 *  both. */
export interface RemeshOptions {
  /** Target edge length in the mesh's units. */
  targetLength?: number | null;
  /** Target edge length as a multiple of the mean edge length (default 1). */
  targetRatio?: number | null;
  /** Iterations (default 10). */
  iterations?: number | null;
  /** Keep creases sharper than this many degrees (default: none kept). */
  featureAngle?: number | null;
  /** The most point–triangle tests the distance report may make (default 2^20 + 256 per
   *  triangle of the input and the result). */
  maxDistanceTests?: number | null;
}

/** Mesh quality figures, before or after remeshing. */
export interface MeshQualityFigures {
  triangles: number;
  vertices: number;
  valence6Percent: number;
  /** Degrees. */
  minAngleOffBoundary: number;
  under30Percent: number;
  meanEdge: number;
  edgeCv: number;
  /** Interior vertices by valence; the last entry counts 12 and more. */
  valences: Uint32Array;
}

/** What `remesh` returns. */
export interface RemeshResult {
  positions: Float32Array;
  indices: Uint32Array;
  iterations: number;
  splits: number;
  collapses: number;
  flips: number;
  relaxed: number;
  creases: number;
  peakVertices: number;
  peakTriangles: number;
  /** Two-sided distance to the input over its bounding-box diagonal: the largest over the
   *  samples measured. */
  distance: number;
  /** Samples of both meshes (four per triangle). */
  distanceSamples: number;
  /** Samples measured within `maxDistanceTests`: all of them unless no box separates the
   *  triangles. */
  distanceSamplesMeasured: number;
  before: MeshQualityFigures;
  after: MeshQualityFigures;
}
"#;
