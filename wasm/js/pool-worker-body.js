// The body of meshq-wasm/pool's worker (assemble.mjs puts a browser or a Node prologue in
// front of it, which imports MeshBvh, defines `ready`, `post` and the message listener that
// calls `handle`). A worker loads one blob and answers its share of each batch with the same
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

/** The result of `message` and the buffers to hand back with it. */
function answer(message) {
  const { kind, input, from, to, out } = message;
  if (kind === 'load') {
    bvh?.free();
    bvh = null;
    bvh = MeshBvh.fromBlob(message.blob);
    if (message.fourWide) bvh.fourWideNodes();
    return [true, []];
  }
  if (bvh === null) throw new Error('no blob loaded');
  const n = to - from;
  if (kind === 'raycast') {
    const t = out ? out.t.subarray(from, to) : new Float32Array(n);
    const triangles = out ? out.triangles.subarray(from, to) : new Uint32Array(n);
    const hits = bvh.raycastBatch(input.subarray(6 * from, 6 * to), message.near, message.far, t, triangles, message.side);
    return out ? [{ hits }, []] : [{ hits, t, triangles }, [t.buffer, triangles.buffer]];
  }
  if (kind === 'any') {
    const hits = out ? out.hits.subarray(from, to) : new Uint8Array(n);
    const count = bvh.raycastAnyBatch(input.subarray(6 * from, 6 * to), message.near, message.far, hits, message.side);
    return out ? [{ count }, []] : [{ count, hits }, [hits.buffer]];
  }
  if (kind === 'closest') {
    const closest = out ? out.closest.subarray(3 * from, 3 * to) : new Float32Array(3 * n);
    const triangles = out ? out.triangles.subarray(from, to) : new Uint32Array(n);
    const distances = out ? out.distances.subarray(from, to) : new Float32Array(n);
    const found = bvh.closestPointBatch(input.subarray(3 * from, 3 * to), message.maxDistance, closest, triangles, distances);
    return out ? [{ found }, []]
      : [{ found, closest, triangles, distances }, [closest.buffer, triangles.buffer, distances.buffer]];
  }
  throw new Error(`unknown request ${kind}`);
}
