// Types of meshq-wasm's ES-module entry for Node (node/index.mjs).
export * from './meshq_wasm.js';

/** Resolves at once: in Node the WebAssembly module is ready when imported. The argument a
 *  browser may pass (where to fetch the .wasm from) is accepted and ignored. */
export default function init(moduleOrPath?: unknown): Promise<unknown>;

/** Returns at once: in Node the WebAssembly module is ready when imported. */
export function initSync(module?: unknown): unknown;
