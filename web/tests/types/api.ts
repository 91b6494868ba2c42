// Compiled by `tsc --noEmit` (web/tests/types.mjs) against the installed package's typings, in
// bundler and Node resolution: every call of the API as documented, and calls the typings must
// refuse (each marked as an expected error), so they cannot silently decay to `any`.
import init, {
  MeshBvh,
  cameraRays,
  queryPoints,
  randomRays,
  remesh,
  geometry,
  type BlobLayout,
  type RayOptions,
  type TriangleClosestPoint,
  type TriangleHit,
  type ClosestPoint,
  type MeshBvhOptions,
  type MeshDistance,
  type SweepHit,
  type PairsResult,
  type SignedDistance,
  type SignedDistanceGrid,
  type RayHit,
  type RemeshResult,
  type Vec3Like,
} from 'meshq-wasm';
import { MeshqPool } from 'meshq-wasm/pool';

export async function everyCall(positions: Float32Array, indices: Uint32Array, blob: Uint8Array): Promise<number> {
  await init();
  const options: MeshBvhOptions = { structure: 'grid', quality: 'fast', maxLeafSize: 4, bins: 16, maxDepth: 40 };
  const bvh = MeshBvh.build(positions, indices);
  const grid = MeshBvh.build(positions, indices, options);
  const soup = MeshBvh.build([0, 0, 0, 1, 0, 0, 0, 1, 0]);
  const swept = MeshBvh.build(positions, indices, { sweepSah: true } satisfies MeshBvhOptions);
  MeshBvh.build(positions, indices, { sweepSah: 32 }).free();
  const loaded = MeshBvh.fromBlob(blob);

  const origin: Vec3Like = [0, 0, 1];
  const hit: RayHit | null = bvh.raycast(origin, { x: 0, y: 0, z: -1 });
  const t: number | undefined = hit?.t;
  const distance: number | undefined = hit?.distance;
  bvh.raycast(new Float32Array(3), [0, 0, -1], 0, 10, 2);
  bvh.raycastXyz(0, 0, 1, 0, 0, -1);
  bvh.raycastXyz(0, 0, 1, 0, 0, -1, 0, Infinity, 0);
  const any: boolean = bvh.raycastAny(origin, [0, 0, -1]);
  const twoStep: RayOptions = { test: 'two-step', side: 0 };
  bvh.raycast(origin, [0, 0, -1], null, null, twoStep);
  bvh.raycastAll(origin, [0, 0, -1], null, null, { test: 'moller-trumbore' });
  const onTriangle: TriangleClosestPoint = geometry.closestPointTriangle(origin, [0, 0, 0], [1, 0, 0], [0, 1, 0], 'rotation');
  const feature: 'face' | 'edge' | 'vertex' = onTriangle.feature;
  const crossing: TriangleHit | null = geometry.intersectRayTriangle(origin, [0, 0, -1], [0, 0, 0], [1, 0, 0], [0, 1, 0], { test: 'two-step' });
  const planeT: number | undefined = geometry.intersectRayPlane(origin, [0, 0, -1], [0, 0, 1], 0);
  const span = geometry.intersectRayAabb(origin, [0, 0, -1], [0, 0, 0], [1, 1, 1]);
  const meet: boolean = geometry.trianglesMeet([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]]);
  const flat: boolean = geometry.pointOnPlane(origin, [0, 0, 1], 1, 1e-6);
  const angle: number = geometry.solidAngleTriangle(origin, [0, 0, 0], [1, 0, 0], [0, 1, 0]);
  geometry.closestPointSegment(origin, [0, 0, 0], [1, 0, 0]).t;
  geometry.closestPointsSegmentSegment(origin, [0, 0, 0], [1, 0, 0], [1, 1, 1]).pointB.x;
  geometry.closestPointPlane(origin, [0, 0, 1], 0).z;
  geometry.pointOnSegment(origin, [0, 0, 0], [1, 0, 0], 0.1);
  geometry.overlapTriangleAabb([0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 0], [1, 1, 1]);
  // @ts-expect-error the triangle test is one of three names
  bvh.raycast(origin, [0, 0, -1], null, null, { test: 'fast' });
  // @ts-expect-error the closest-point method is one of three names
  geometry.closestPointTriangle(origin, [0, 0, 0], [1, 0, 0], [0, 1, 0], 'voronoi');
  const all: RayHit[] = bvh.raycastAll(origin, [0, 0, -1], null, null, 1);
  const near: ClosestPoint | null = bvh.closestPoint([1, 2, 3]);
  bvh.closestPoint({ x: 1, y: 2, z: 3 }, 0.5);

  const rays = randomRays(bvh.bounds(), 1, 100);
  const ts = new Float32Array(100);
  const triangles = new Uint32Array(100);
  const hits: number = bvh.raycastBatch(rays, undefined, undefined, ts, triangles);
  bvh.raycastBatch(rays, 0, 5, ts, triangles, 0);
  bvh.raycastBatchBarycentric(rays, null, null, ts, triangles, new Float32Array(200));
  bvh.raycastAnyBatch(cameraRays(bvh.bounds(), 10, 10), 0, 1, new Uint8Array(100));
  loaded.fourWideNodes();
  loaded.eightWideNodes();
  loaded.compactNodes();
  const nodeBytes: number = loaded.queryNodeBytes;
  const points = queryPoints(bvh.bounds(), 1, 10);
  bvh.closestPointBatch(points, undefined, new Float32Array(30), new Uint32Array(10), new Float32Array(10));
  const misses: number = MeshBvh.MISS_T + MeshBvh.MISS_DISTANCE + MeshBvh.MISS_TRIANGLE;
  const w: number = bvh.windingNumber([0, 0, 0]);
  const inside: boolean = bvh.contains({ x: 0, y: 0, z: 0 }, 3);
  const signed: SignedDistance | null = bvh.signedDistance([0, 0, 0], null, Infinity);
  const insideCount: number = bvh.windingNumberBatch(points, new Float32Array(10));
  bvh.signedDistanceBatch(points, 0.5, new Float32Array(10), new Uint32Array(10), 2);
  const volume: SignedDistanceGrid = bvh.signedDistanceGrid(32, 0.1, null, 2);
  const texel: number = volume.values[0] + volume.counts[0] + volume.origin[0] + volume.spacing;

  const layout: BlobLayout = 'packed';
  const bytes: Uint8Array = loaded.toBlob();
  grid.toBlob(layout);
  const pairs: PairsResult = bvh.intersectingPairs(grid, [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], 10);
  bvh.intersectingPairs(grid, { elements: new Float64Array(16) });
  bvh.intersectsMesh(grid);
  const met: boolean = bvh.intersectsMesh(grid, null, 1_000_000);
  bvh.intersectingPairs(grid, null, null, 1_000_000);
  const apart: MeshDistance | null = bvh.distanceToMesh(grid, null, 0.5, 0, 1_000_000);
  const gap: number = (bvh.distanceToMesh(grid)?.pointA.x ?? 0) + (apart?.triangleB ?? 0);
  const byNormals: SignedDistance | null = bvh.signedDistance([0, 0, 0], null, 'pseudo-normal');
  bvh.signedDistanceBatch(points, null, new Float32Array(10), new Uint32Array(10), 'pseudo-normal');
  const landed: SweepHit | null = bvh.sweepSphere([0, 1, 0], 0.1, [0, -2, 0]);
  const slid = bvh.sweepCapsule([0, 1, 0], [0, 1.5, 0], 0.2, { x: 1, y: 0, z: 0 });
  const pushed = bvh.sweepBox([0, 1, 0], [1, 0, 0, 0, 1, 0, 0, 0, 1], [0.1, 0.2, 0.3], [0, -1, 0]);
  const when: number = (landed?.t ?? 0) + (slid?.normal.y ?? 0) + (pushed?.triangle ?? 0);
  bvh.intersectionSegments(grid, null);
  bvh.intersectionSegments(grid, null, 1_000_000);
  bvh.selfIntersections();
  bvh.selfIntersections(100, 1_000_000);
  bvh.overlapsSphere([0, 0, 0], 1);
  bvh.overlapsOrientedBox([0, 0, 0], [1, 0, 0, 0, 1, 0, 0, 0, 1], [1, 1, 1]);
  bvh.overlapsTriangle([0, 0, 0], [1, 0, 0], [0, 1, 0]);
  const boxes: Float32Array = bvh.levelBoxes(2);
  const structure: 'bvh' | 'kdtree' | 'octree' | 'grid' = grid.structure;
  const remeshed: RemeshResult = remesh(bvh.vertexPositions(), bvh.indices(), { targetRatio: 1, iterations: 3, featureAngle: 45 });
  remesh(positions);
  remesh(positions, null, { maxDistanceTests: 1 << 20 });
  const measured: number = remeshed.distanceSamplesMeasured + remeshed.distanceSamples;
  const tree = bvh.treeArrays();
  soup.free();
  swept.free();

  const pool = await MeshqPool.fromBlob(blob, { workers: 2, eightWide: true });
  const pooled: { t: Float32Array; triangles: Uint32Array; hits: number } = await pool.raycastBatch(rays, 0, 1);
  const flags: Uint8Array = (await pool.raycastAnyBatch(rays)).hits;
  const nearest: Float32Array = (await pool.closestPointBatch(points, 0.5)).distances;
  pool.terminate();
  // @ts-expect-error a pool answers typed arrays of queries
  await pool.raycastBatch([0, 0, 0, 0, 0, 1]);

  // @ts-expect-error a ray needs a direction
  bvh.raycast(origin);
  // @ts-expect-error points are Vec3Like, not strings
  bvh.closestPoint('1, 2, 3');
  // @ts-expect-error side is 0, 1 or 2
  bvh.raycast(origin, origin, 0, 1, 3);
  // @ts-expect-error a closest point has no ray parameter
  near?.t;
  // @ts-expect-error unknown build option
  MeshBvh.build(positions, indices, { maxLeafTris: 4 });
  // @ts-expect-error unknown structure
  MeshBvh.build(positions, indices, { structure: 'quadtree' });
  // @ts-expect-error unknown blob layout
  bvh.toBlob('zip');
  // @ts-expect-error batches write into typed arrays
  bvh.raycastBatch(rays, 0, 1, [], triangles);

  return measured + (t ?? 0) + (distance ?? 0) + Number(any) + all.length + hits + misses + bytes.length
    + pairs.total + boxes.length + structure.length + remeshed.after.valence6Percent + tree.first.length
    + pooled.hits + flags.length + nearest.length + nodeBytes + (crossing?.t ?? 0) + (planeT ?? 0)
    + (span?.far ?? 0) + Number(meet) + Number(flat) + angle + feature.length;
}
