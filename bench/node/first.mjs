// The first calls in a fresh Node process, where an app that loads one mesh lives: V8 runs a
// module's functions in its baseline compiler (Liftoff) until they are hot enough for the
// optimising one, and WebAssembly memory is touched for the first time. Each sample is a new
// process that times the module's instantiation, then one operation five times in a row; the
// report is the median over the processes of each call. `node bench/node/first.mjs [processes]`
// (default 7); MESHQ_BENCH_MESH names another OBJ file than the bundled bunny. Build the package
// first: scripts/wasm.sh.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = fileURLToPath(new URL('.', import.meta.url));
// The children run from this directory: a mesh path given relative to ours is made absolute.
const env = { ...process.env };
if (env.MESHQ_BENCH_MESH) {
  env.MESHQ_BENCH_MESH = resolve(env.MESHQ_BENCH_MESH);
  process.env.MESHQ_BENCH_MESH = env.MESHQ_BENCH_MESH;
}
const meshName = env.MESHQ_BENCH_MESH ? basename(env.MESHQ_BENCH_MESH) : 'bunny';
const processes = Number(process.argv[2] ?? 7);
const CALLS = 5;

// One child: prints the JSON of [instantiation ms, call ms × CALLS] for `op`.
const child = `
import { readFileSync } from 'node:fs';
const op = process.argv[2], blobPath = process.argv[3];
const { geometry, index, positions } = await import(${JSON.stringify(join(here, 'bunny.mjs'))});
const t0 = performance.now();
const meshq = (await import(${JSON.stringify(join(here, '../../wasm/pkg/node/meshq_wasm.js'))})).default;
const { MeshBVH } = await import('three-mesh-bvh');
const ready = performance.now() - t0;
const blob = new Uint8Array(readFileSync(blobPath));
const serialized = op === 'deserialize' ? MeshBVH.serialize(new MeshBVH(geometry.clone())) : null;
const run = {
  fromBlob: () => meshq.MeshBvh.fromBlob(blob).free(),
  build: () => meshq.MeshBvh.build(positions, index).free(),
  peerBuild: () => new MeshBVH(geometry),
  deserialize: () => MeshBVH.deserialize(serialized, geometry),
}[op];
const times = [];
for (let i = 0; i < ${CALLS}; i++) { const t = performance.now(); run(); times.push(performance.now() - t); }
console.log(JSON.stringify([ready, ...times]));
`;

const dir = mkdtempSync(join(tmpdir(), 'meshq-first-'));
// The child lives here, beside node_modules, so that it resolves 'three-mesh-bvh'.
const script = join(here, `.first-child-${process.pid}.mjs`);
try {
  writeFileSync(script, child);
  const meshq = (await import('../../wasm/pkg/node/meshq_wasm.js')).default;
  const { index, positions } = await import('./bunny.mjs');
  const triangles = index.length / 3;
  const bvh = meshq.MeshBvh.build(positions, index);
  const blobPath = join(dir, 'bunny.meshq');
  writeFileSync(blobPath, bvh.toBlob());
  bvh.free();
  const median = (v) => v.slice().sort((a, b) => a - b)[v.length >> 1];
  const rows = [
    ['meshq `MeshBvh.fromBlob` (validated)', 'fromBlob'],
    ['meshq `MeshBvh.build` (default)', 'build'],
    ['three-mesh-bvh `new MeshBVH` (default)', 'peerBuild'],
    ['three-mesh-bvh `MeshBVH.deserialize` (no validation)', 'deserialize'],
  ];
  const bytes = readFileSync(blobPath).length;
  console.log(`${meshName} (${triangles} triangles, a ${bytes}-byte blob), ${processes} fresh processes each;`);
  console.log(`medians in ms of the modules' import, then of calls 1–${CALLS}:`);
  for (const [label, op] of rows) {
    const samples = [];
    for (let p = 0; p < processes; p++) {
      const out = execFileSync(process.execPath, [script, op, blobPath], { cwd: here, env, encoding: 'utf8' });
      samples.push(JSON.parse(out.trim().split('\n').pop()));
    }
    const cols = samples[0].map((_, k) => median(samples.map((s) => s[k])).toFixed(1));
    console.log(`${label.padEnd(52)} import ${cols[0].padStart(5)} | ${cols.slice(1).map((c) => c.padStart(5)).join(' ')}`);
  }
} finally {
  rmSync(script, { force: true });
  rmSync(dir, { recursive: true, force: true });
}
