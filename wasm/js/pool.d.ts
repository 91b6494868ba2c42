// Types of meshq-wasm/pool: batches over a pool of workers, each holding the same blob.

/** Options of `MeshqPool.fromBlob`. */
export interface MeshqPoolOptions {
  /** Workers to start (default: one per core, at most 16). */
  workers?: number;
  /** `false` copies blobs, queries and answers between threads even where memory could be shared. */
  shared?: boolean;
  /** `false`: every worker walks the four-wide tree (`MeshBvh.fourWideNodes()`) instead of the eight-wide one a loaded BVH walks; the same answers. */
  eightWide?: boolean;
}

/** Batches answered by a pool of workers; every answer is the single-thread answer, bit for bit. */
export class MeshqPool {
  private constructor();
  /** Starts the workers, each loading `bytes` (a blob). Rejects with the blob's error. */
  static fromBlob(bytes: Uint8Array, options?: MeshqPoolOptions): Promise<MeshqPool>;
  /** How many workers answer. */
  readonly size: number;
  /** Whether queries and answers live in shared memory (the workers then take each batch in pieces as they go, so a slower one answers fewer; copied, each answers an equal share). */
  readonly shared: boolean;
  /** Stops the workers; batches still running and later calls reject. */
  terminate(): void;
  /** `MeshBvh.raycastBatch` on the pool: `t` and `triangles` one per ray, and the hit count. */
  raycastBatch(rays: Float32Array, near?: number | null, far?: number | null, side?: 0 | 1 | 2 | null):
    Promise<{ t: Float32Array; triangles: Uint32Array; hits: number }>;
  /** `MeshBvh.raycastAnyBatch` on the pool: one flag per ray and the count of rays that hit. */
  raycastAnyBatch(rays: Float32Array, near?: number | null, far?: number | null, side?: 0 | 1 | 2 | null):
    Promise<{ hits: Uint8Array; count: number }>;
  /** `MeshBvh.closestPointBatch` on the pool. */
  closestPointBatch(points: Float32Array, maxDistance?: number | null):
    Promise<{ closest: Float32Array; triangles: Uint32Array; distances: Float32Array; found: number }>;
}
