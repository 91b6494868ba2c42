// meshq-wasm/pool: batches spread over a pool of workers (Web Workers in the browser,
// worker_threads in Node), each holding the same blob.
//
//   import { MeshqPool } from 'meshq-wasm/pool';
//   const pool = await MeshqPool.fromBlob(bytes);           // one worker per core by default
//   const { t, triangles, hits } = await pool.raycastBatch(rays);
//   pool.terminate();
//
// Every worker loads the blob once (`MeshBvh.fromBlob`). Where SharedArrayBuffer is available
// (Node; a cross-origin-isolated page), the blob, the queries and the answers live in shared
// memory: nothing is copied between threads but each worker's own load. Elsewhere each worker
// gets a copy of the blob and of its share of the queries, and sends its answers back.
// In shared memory a batch is cut into pieces that the workers take one after another until
// none are left, so a worker on a slower core (or one the system runs less) answers fewer of
// them; copied, it is cut into one contiguous share per worker. Each piece or share is
// answered by the same batch call as on one thread, so every answer is the single-thread
// answer, bit for bit.

const inNode = typeof process !== 'undefined' && process.versions?.node !== undefined
  && typeof window === 'undefined';

/** Whether typed arrays can live in memory shared with workers. */
function canShare() {
  if (typeof SharedArrayBuffer === 'undefined') return false;
  return inNode || globalThis.crossOriginIsolated === true;
}

/**
 * The smallest piece a worker takes of a shared ray batch (the last may be smaller): small
 * enough that the workers finish within a fraction of a millisecond of each other, large
 * enough that taking it (an atomic exchange) costs nothing measurable. A multiple of the 8
 * rays of a packet.
 */
const RAY_PIECE = 1024;
/**
 * The same for closest points: larger, as a batch call answers its points in Morton order,
 * which pays more the more points it orders at once.
 */
const POINT_PIECE = 8192;
/** Rays per packet: pieces of ray batches are whole packets. */
const PACKET = 8;

/** A worker running pool-worker, with a promise-per-message interface. */
class Thread {
  constructor(worker) {
    this.worker = worker;
    this.pending = new Map();
    this.next = 0;
    const receive = (message) => {
      const waiting = this.pending.get(message.id);
      if (!waiting) return;
      this.pending.delete(message.id);
      if (message.error) {
        const Type = { TypeError, RangeError }[message.error.name] ?? Error;
        waiting.reject(new Type(message.error.message));
      } else {
        waiting.resolve(message.result);
      }
    };
    const fail = (error) => this.fail(error instanceof Error ? error : new Error(String(error)));
    if (inNode) {
      worker.on('message', receive);
      worker.on('error', fail);
      worker.on('exit', () => fail(new Error('a pool worker stopped')));
    } else {
      worker.onmessage = (e) => receive(e.data);
      worker.onerror = (e) => fail(new Error(e.message ?? 'a pool worker failed'));
    }
  }

  /** Rejects every call still waiting for an answer. */
  fail(error) {
    for (const w of this.pending.values()) w.reject(error);
    this.pending.clear();
  }

  /** Stops the worker; calls still waiting reject. */
  stop() {
    this.fail(new Error('this pool was terminated'));
    this.worker.terminate();
  }

  call(request, transfer = []) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ ...request, id }, transfer);
    });
  }
}

async function startWorker() {
  if (inNode) {
    const { Worker } = await import('node:worker_threads');
    return new Worker(new URL('./pool-worker.mjs', import.meta.url));
  }
  return new Worker(new URL('./pool-worker.js', import.meta.url), { type: 'module' });
}

function defaultSize() {
  const cores = inNode ? globalThis.process?.availableParallelism?.() : globalThis.navigator?.hardwareConcurrency;
  return Math.max(1, Math.min(Number(cores) || 1, 16));
}

/** `values` in memory the workers can read: shared when possible, else as they are. */
function shareable(values, share) {
  if (!share || values.buffer instanceof SharedArrayBuffer) return values;
  // A Node Buffer is a Uint8Array; its own constructor is deprecated.
  const Type = values instanceof Uint8Array ? Uint8Array : values.constructor;
  const copy = new Type(new SharedArrayBuffer(values.byteLength));
  copy.set(values);
  return copy;
}

/** A typed array of `length` elements, in shared memory when `share`. */
function output(Type, length, share) {
  return share ? new Type(new SharedArrayBuffer(length * Type.BYTES_PER_ELEMENT)) : new Type(length);
}

/**
 * A pool of workers answering batches on one blob. Create it with `MeshqPool.fromBlob`; free
 * it with `terminate()`.
 */
export class MeshqPool {
  #threads;
  #share;

  constructor(threads, share) {
    this.#threads = threads;
    this.#share = share;
  }

  /**
   * Starts `workers` workers (default: one per core, at most 16) that each load `bytes` (a
   * `Uint8Array` holding a blob baked by `meshq bake` or `toBlob`). `shared: false` copies
   * instead of sharing memory even where it could be shared. Workers walk the eight-wide tree
   * a loaded `MeshBvh` walks; `eightWide: false` has them walk the four-wide tree instead
   * (`MeshBvh.fourWideNodes()`), with the same answers. Rejects with the blob's error if it
   * does not load.
   */
  static async fromBlob(bytes, { workers, shared, eightWide } = {}) {
    if (!(bytes instanceof Uint8Array)) throw new TypeError('a blob must be a Uint8Array (a Buffer is one)');
    const size = workers ?? defaultSize();
    if (!Number.isInteger(size) || size < 1 || size > 256) throw new RangeError(`workers must be a whole number in 1..256, got ${size}`);
    if (eightWide !== undefined && typeof eightWide !== 'boolean') throw new TypeError(`eightWide must be a boolean, got ${typeof eightWide}`);
    const share = shared !== false && canShare();
    const blob = shareable(bytes, share);
    const threads = [];
    try {
      for (let i = 0; i < size; i++) threads.push(new Thread(await startWorker()));
      await Promise.all(threads.map((t) => t.call({ kind: 'load', blob, fourWide: eightWide === false })));
    } catch (error) {
      for (const t of threads) t.stop();
      throw error;
    }
    return new MeshqPool(threads, share);
  }

  /** How many workers answer. */
  get size() {
    return this.#threads.length;
  }

  /** Whether queries and answers live in shared memory (no copies between threads). */
  get shared() {
    return this.#share;
  }

  /** Stops the workers; batches still running and later calls reject. */
  terminate() {
    for (const t of this.#threads) t.stop();
    this.#threads = [];
  }

  /**
   * Answers `request` (a batch of `count` queries of `kind`) on every worker. In shared
   * memory the workers take pieces (of at least `minPiece` queries, or a quarter of a share
   * for a small batch) from one shared cursor as they go and write their answers in place; copied, each worker gets one contiguous share
   * of `input` (values `stride` per query) and `copyBack(result, from)` places its answers.
   * Resolves to the total count (hits, or points found).
   */
  async #answer(kind, count, input, stride, minPiece, request, copyBack) {
    const threads = this.#threads;
    if (threads.length === 0) throw new Error('this pool was terminated');
    if (count === 0) return 0;
    let jobs;
    if (this.#share) {
      const cursor = new Int32Array(new SharedArrayBuffer(4));
      // A smaller batch takes smaller pieces: at least four per worker, else the first worker
      // to start could take it all.
      const smallest = Math.min(minPiece, Math.ceil(count / (4 * threads.length) / PACKET) * PACKET);
      const shared = { total: count, cursor, workers: threads.length, minPiece: smallest };
      jobs = threads.map((thread) => thread.call({ kind, input, ...request, ...shared }));
    } else {
      const per = Math.ceil(count / threads.length);
      jobs = [];
      for (let w = 0, from = 0; w < threads.length && from < count; w++, from += per) {
        const to = Math.min(count, from + per);
        const share = input.slice(stride * from, stride * to);
        jobs.push(threads[w].call({ kind, input: share, ...request, out: null, from: 0, to: to - from })
          .then((result) => {
            copyBack(result, from);
            return result;
          }));
      }
    }
    const results = await Promise.all(jobs);
    return results.reduce((sum, r) => sum + r.count, 0);
  }

  /**
   * `MeshBvh.raycastBatch` on the pool: `rays` a `Float32Array` of 6 numbers per ray; `near`,
   * `far` and `side` as there. Resolves to `{ t, triangles, hits }`: a `Float32Array` and a
   * `Uint32Array` of one entry per ray (misses: `MISS_T`, `MISS_TRIANGLE`) and the number of
   * hits.
   */
  async raycastBatch(rays, near, far, side) {
    const n = checkQueries(rays, 6, 'rays');
    const input = shareable(rays, this.#share);
    const t = output(Float32Array, n, this.#share);
    const triangles = output(Uint32Array, n, this.#share);
    const hits = await this.#answer('raycast', n, input, 6, RAY_PIECE, { near, far, side, out: { t, triangles } },
      (result, from) => {
        t.set(result.t, from);
        triangles.set(result.triangles, from);
      });
    return { t, triangles, hits };
  }

  /**
   * `MeshBvh.raycastAnyBatch` on the pool. Resolves to `{ hits, count }`: a `Uint8Array` of
   * one flag per ray (1: something is hit) and how many rays hit.
   */
  async raycastAnyBatch(rays, near, far, side) {
    const n = checkQueries(rays, 6, 'rays');
    const input = shareable(rays, this.#share);
    const hits = output(Uint8Array, n, this.#share);
    const count = await this.#answer('any', n, input, 6, RAY_PIECE, { near, far, side, out: { hits } },
      (result, from) => hits.set(result.hits, from));
    return { hits, count };
  }

  /**
   * `MeshBvh.closestPointBatch` on the pool: `points` a `Float32Array` of 3 numbers per
   * point. Resolves to `{ closest, triangles, distances, found }` as that call fills them
   * (misses: `NaN` coordinates, `MISS_TRIANGLE`, `MISS_DISTANCE`).
   */
  async closestPointBatch(points, maxDistance) {
    const n = checkQueries(points, 3, 'points');
    const input = shareable(points, this.#share);
    const closest = output(Float32Array, 3 * n, this.#share);
    const triangles = output(Uint32Array, n, this.#share);
    const distances = output(Float32Array, n, this.#share);
    const found = await this.#answer('closest', n, input, 3, POINT_PIECE,
      { maxDistance, out: { closest, triangles, distances } },
      (result, from) => {
        closest.set(result.closest, 3 * from);
        triangles.set(result.triangles, from);
        distances.set(result.distances, from);
      });
    return { closest, triangles, distances, found };
  }
}

/** The number of queries in `values` (a `Float32Array` of `stride` numbers per query). */
function checkQueries(values, stride, what) {
  if (!(values instanceof Float32Array)) {
    throw new TypeError(`${what} must be a Float32Array, got ${values?.constructor?.name ?? typeof values}`);
  }
  if (values.length % stride !== 0) {
    throw new RangeError(`${what} hold ${values.length} numbers, not a multiple of ${stride}`);
  }
  return values.length / stride;
}
