// The body of meshq-wasm/pool's worker (assemble.mjs puts a browser or a Node prologue in
// front of it, which imports MeshBvh, defines `ready`, `post` and the message listener that
// calls `handle`). A worker loads one blob and answers pieces of each batch with the same
// batch call as on one thread.

let bvh = null;

/** Answers one message from the pool, or reports its error by name and message. */
async function handle(message) {
  await ready;
  try {
    const [result, transfer] = answer(message);
    post({ id: message.id, result }, transfer);
  } catch (error) {
    post({ id: message.id, error: { name: error?.name ?? 'Error', message: String(error?.message ?? error) } }, []);
  }
}

/**
 * The result of `message` and the buffers to hand back with it. A batch in shared memory
 * comes with a `cursor` that every worker of the pool shares: each takes its next piece from
 * it until none is left, so a faster worker answers more of them. Otherwise the message names
 * its queries (`from` to `to`).
 */
function answer(message) {
  if (message.kind === 'load') {
    bvh?.free();
    bvh = null;
    bvh = MeshBvh.fromBlob(message.blob);
    if (message.fourWide) bvh.fourWideNodes();
    return [true, []];
  }
  if (bvh === null) throw new Error('no blob loaded');
  if (message.cursor) {
    let count = 0;
    for (let piece = take(message); piece !== null; piece = take(message)) {
      count += answerRange(message, piece[0], piece[1]).count;
    }
    return [{ count }, []];
  }
  const result = answerRange(message, message.from, message.to);
  return [result, message.out ? [] : Object.values(result).filter((v) => ArrayBuffer.isView(v)).map((v) => v.buffer)];
}

/**
 * The next piece `[from, to)` of a shared batch, or `null` when none is left: a share of what
 * is left (`1 / (2 · workers)` of it, as guided scheduling takes), never under `minPiece`
 * queries, in whole packets of 8 rays (the whole batch for a pool of one). Pieces start
 * large, so that each batch call orders many points together, and end small, so that the
 * workers finish together.
 */
function take({ cursor, total, workers, minPiece }) {
  for (;;) {
    const from = Atomics.load(cursor, 0);
    if (from >= total) return null;
    const left = total - from;
    // One worker has no one to share with: it takes the whole batch.
    const share = workers === 1 ? left : Math.ceil(left / (2 * workers) / 8) * 8;
    const size = Math.min(left, Math.max(minPiece, share));
    if (Atomics.compareExchange(cursor, 0, from, from + size) === from) return [from, from + size];
  }
}

/**
 * Queries `from` to `to` of `message`'s batch: `{ count }` (hits, or points found) with the
 * answers written into `message.out` where the batch has one, else `{ count }` and new arrays
 * holding the answers.
 */
function answerRange(message, from, to) {
  const { kind, input, out } = message;
  const n = to - from;
  if (kind === 'raycast') {
    const t = out ? out.t.subarray(from, to) : new Float32Array(n);
    const triangles = out ? out.triangles.subarray(from, to) : new Uint32Array(n);
    const count = bvh.raycastBatch(input.subarray(6 * from, 6 * to), message.near, message.far, t, triangles, message.side);
    return out ? { count } : { count, t, triangles };
  }
  if (kind === 'any') {
    const hits = out ? out.hits.subarray(from, to) : new Uint8Array(n);
    const count = bvh.raycastAnyBatch(input.subarray(6 * from, 6 * to), message.near, message.far, hits, message.side);
    return out ? { count } : { count, hits };
  }
  if (kind === 'closest') {
    const closest = out ? out.closest.subarray(3 * from, 3 * to) : new Float32Array(3 * n);
    const triangles = out ? out.triangles.subarray(from, to) : new Uint32Array(n);
    const distances = out ? out.distances.subarray(from, to) : new Float32Array(n);
    const count = bvh.closestPointBatch(input.subarray(3 * from, 3 * to), message.maxDistance, closest, triangles, distances);
    return out ? { count } : { count, closest, triangles, distances };
  }
  throw new Error(`unknown request ${kind}`);
}
