// A page's first calls: the package imported and started (its module fetched, compiled and
// instantiated: `await init()`), the blob named by `?blob=` fetched, then `MeshBvh.fromBlob`
// timed five times in a row. The result, `[start ms, call 1 ms, …, call 5 ms]`, goes to
// `window.firstLoads` and the page's text. On a first visit V8 runs each function in its
// baseline code until it is hot; a browser that kept the module's compiled code (a returning
// visitor's, where the site lets it cache) starts from that code instead.
const CALLS = 5;
const log = document.getElementById('log');
const blobUrl = new URLSearchParams(location.search).get('blob') ?? '../assets/bunny.meshq';

const t0 = performance.now();
const meshq = await import('meshq-wasm');
await meshq.default();
const start = performance.now() - t0;
const bytes = new Uint8Array(await (await fetch(blobUrl)).arrayBuffer());
const calls = [];
for (let i = 0; i < CALLS; i++) {
  const t = performance.now();
  meshq.MeshBvh.fromBlob(bytes).free();
  calls.push(performance.now() - t);
}
window.firstLoads = [start, ...calls];
log.textContent = `start ${start.toFixed(1)} ms; fromBlob ${calls.map((c) => c.toFixed(1)).join(', ')} ms`;
