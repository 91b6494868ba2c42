// meshq-wasm for Node as an ES module: the CommonJS build's exports, plus the `init()` a
// browser needs, which here resolves at once (Node loads the module synchronously), so the
// same `import init, { MeshBvh } from 'meshq-wasm'; await init();` runs in both.
import wasm from './meshq_wasm.js';

export * from './meshq_wasm.js';

/** Resolves at once: in Node the WebAssembly module is ready when imported. */
export default async function init() {
  return wasm;
}

/** Returns at once: in Node the WebAssembly module is ready when imported. */
export function initSync() {
  return wasm;
}
