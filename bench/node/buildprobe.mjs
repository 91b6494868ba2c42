import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { OBJLoader } from 'three/examples/jsm/loaders/OBJLoader.js';
import { mergeVertices } from 'three/examples/jsm/utils/BufferGeometryUtils.js';
import { MeshBVH } from 'three-mesh-bvh';
import meshq from '../../wasm/pkg-nodejs/meshq_wasm.js';
const root = fileURLToPath(new URL('../..', import.meta.url));
const group = new OBJLoader().parse(readFileSync(`${root}/assets/stanford-bunny.obj`, 'utf8'));
const loaded = group.children[0].geometry;
loaded.deleteAttribute('normal'); loaded.deleteAttribute('uv');
const geometry = mergeVertices(loaded);
const positions = geometry.getAttribute('position').array;
const index = geometry.index.array;
function time(f, runs) { f(); const t = []; for (let i = 0; i < runs; i++) { const t0 = performance.now(); f(); t.push(performance.now() - t0); } t.sort((a, b) => a - b); return t[Math.floor(t.length / 2)]; }
const N = Number(process.env.RUNS ?? 9);
for (let round = 0; round < 2; round++) {
  let b = null;
  const peer = time(() => new MeshBVH(geometry), N);
  const bal = time(() => { b?.free(); b = meshq.MeshBvh.build(positions, index); }, N);
  const fast = time(() => { b?.free(); b = meshq.MeshBvh.build(positions, index, { quality: 'fast' }); }, N);
  const blob = b.toBlob();
  const load = time(() => { b?.free(); b = meshq.MeshBvh.fromBlob(blob); }, N);
  console.log(`peer ${peer.toFixed(1)}  balanced ${bal.toFixed(1)} (${(peer/bal).toFixed(2)}x)  fast ${fast.toFixed(1)} (${(peer/fast).toFixed(2)}x)  fromBlob ${load.toFixed(1)}`);
}
