// What the browser benchmarks read from their command line and environment, checked: a bad
// value stops them with one line naming it, before a browser starts.

/** Ends the process with `message` on one line. */
export function fail(message) {
  console.error(`error: ${message}`);
  process.exit(2);
}

/** `text` (or `fallback` when it is undefined) as a whole number ≥ 1, or a failure naming `name`. */
export function positiveInteger(name, text, fallback) {
  if (text === undefined) return fallback;
  const n = Number(text);
  if (!Number.isSafeInteger(n) || n < 1) fail(`${name} must be a whole number of 1 or more, not "${text}"`);
  return n;
}

/** The mesh the Node benchmark loads (the bundled bunny, or MESHQ_BENCH_MESH), or a failure. */
export async function loadMesh() {
  try {
    return await import('../node/bunny.mjs');
  } catch (e) {
    return fail(`cannot load the mesh ${process.env.MESHQ_BENCH_MESH ?? 'assets/stanford-bunny.obj'}: ${e.message.split('\n')[0]}`);
  }
}
