// The npm package as a user gets it: `npm pack wasm/pkg` makes the tarball, a fresh directory
// outside the repository installs it (with three) through npm, and then
// - Node imports it as an ES module (`import init, { MeshBvh } from 'meshq-wasm'`), requires it
//   as CommonJS, and runs the three.js drop-in (`meshq-wasm/three`) against three's own raycast;
// - the demo, copied there with the bunny blob, runs in headless Chromium with its import map
//   unchanged (three and meshq-wasm from that directory's node_modules), picks the bunny, and
//   imports `meshq-wasm/three` through the same map.
// Run after scripts/build-web.sh (which bakes web/assets/bunny.meshq): node web/tests/pack.mjs
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium, startServer } from './browser.mjs';

const root = fileURLToPath(new URL('../..', import.meta.url));
const scratch = mkdtempSync(join(tmpdir(), 'meshq-pack-'));
const npm = (args, cwd) => execFileSync('npm', args, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

// Never hang CI.
const watchdog = setTimeout(() => {
  console.error('pack: timed out');
  process.exit(1);
}, 240000);

// 1. The tarball, and what is in it.
const packed = JSON.parse(npm(['pack', '--json', '--pack-destination', scratch], join(root, 'wasm/pkg')));
const { filename, files } = packed[0];
const paths = files.map((f) => f.path).sort();
for (const needed of ['package.json', 'README.md', 'web/meshq_wasm.js', 'web/meshq_wasm_bg.wasm', 'web/meshq_wasm.d.ts',
  'web/three.js', 'web/three.d.ts', 'web/three-augment.d.ts', 'node/meshq_wasm.js', 'node/meshq_wasm_bg.wasm',
  'node/index.mjs', 'node/index.d.mts', 'node/three.mjs', 'node/three.d.mts', 'web/pool.js', 'web/pool-worker.js',
  'node/pool.mjs', 'node/pool-worker.mjs']) {
  assert.ok(paths.includes(needed), `tarball lacks ${needed}`);
}
assert.ok(paths.every((p) => /^(package\.json|README\.md|web\/|node\/)/.test(p)), `unexpected files: ${paths}`);
console.log(`npm pack: ${filename}, ${files.length} files`);

// 2. A fresh directory installs it through npm (three from the registry or npm's cache).
const app = join(scratch, 'app');
mkdirSync(app);
writeFileSync(join(app, 'package.json'), JSON.stringify({ name: 'meshq-pack-test', private: true, type: 'module' }));
npm(['install', '--no-audit', '--no-fund', '--prefer-offline', join(scratch, filename), 'three@0.187.0'], app);

// 3. Node: ES module, CommonJS and the drop-in, each checked against an answer known without
// meshq (a unit square at z = 0; three's own raycast).
writeFileSync(join(app, 'esm.mjs'), `
import assert from 'node:assert/strict';
import init, { MeshBvh } from 'meshq-wasm';
await init();
const bvh = MeshBvh.build(new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]), new Uint32Array([0, 1, 2, 0, 2, 3]));
const hit = bvh.raycast([0.75, 0.25, 2], [0, 0, -2]);
assert.equal(hit.triangle, 0);
assert.equal(hit.t, 1);
assert.equal(hit.distance, 2);
assert.equal(MeshBvh.fromBlob(bvh.toBlob()).raycast({ x: 0.25, y: 0.75, z: 1 }, [0, 0, -1]).triangle, 1);
console.log('esm ok');
`);
writeFileSync(join(app, 'cjs.cjs'), `
const assert = require('node:assert/strict');
const { MeshBvh } = require('meshq-wasm');
const bvh = MeshBvh.build([0, 0, 0, 1, 0, 0, 0, 1, 0]);
assert.equal(bvh.raycast([0.2, 0.2, 1], [0, 0, -1]).t, 1);
assert.equal(bvh.raycast([2, 2, 1], [0, 0, -1]), null);
assert.equal(MeshBvh.MISS_T, Infinity);
console.log('cjs ok');
`);
writeFileSync(join(app, 'three.mjs'), `
import assert from 'node:assert/strict';
import * as THREE from 'three';
import { acceleratedRaycast, computeBoundsTree } from 'meshq-wasm/three';
const geometry = new THREE.TorusKnotGeometry(1, 0.3, 64, 16);
geometry.computeBoundsTree = computeBoundsTree;
geometry.computeBoundsTree();
const fast = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ side: THREE.DoubleSide }));
fast.raycast = acceleratedRaycast;
const brute = new THREE.Mesh(geometry, fast.material);
const raycaster = new THREE.Raycaster();
let hits = 0;
for (let i = 0; i < 200; i++) {
  const a = (i / 200) * Math.PI * 2;
  raycaster.set(new THREE.Vector3(3 * Math.cos(a), 0.3 * Math.sin(3 * a), 3 * Math.sin(a)),
    new THREE.Vector3(-Math.cos(a), 0.1, -Math.sin(a)).normalize());
  // Equal but for 'object', the mesh each was cast against.
  const want = raycaster.intersectObject(brute).map(({ object, ...rest }) => rest);
  const got = raycaster.intersectObject(fast);
  assert.ok(got.every((h) => h.object === fast));
  assert.deepStrictEqual(got.map(({ object, ...rest }) => rest), want);
  hits += want.length;
}
assert.ok(hits > 200, 'rays hit');
console.log('three ok');
`);
for (const script of ['esm.mjs', 'cjs.cjs', 'three.mjs']) {
  const out = execFileSync(process.execPath, [script], { cwd: app, encoding: 'utf8' });
  assert.match(out, /ok/);
}
console.log('Node: import, require and the three.js drop-in work from the installed tarball');

// 4. The demo, with its import map unchanged, served from the fresh directory.
for (const file of ['index.html', 'main.js', 'collide.js', 'style.css', 'serve.mjs']) {
  copyFileSync(join(root, 'web', file), join(app, file));
}
mkdirSync(join(app, 'assets'));
copyFileSync(join(root, 'web/assets/bunny.meshq'), join(app, 'assets/bunny.meshq'));
const { url, server } = await startServer(app, 'pack');

let browser = null;
const errors = [];
try {
  browser = await launchChromium();
  const page = await browser.newPage({ viewport: { width: 900, height: 600 } });
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  const served = [];
  page.on('response', (r) => served.push(new URL(r.url()).pathname));
  await page.goto(url);
  await page.waitForFunction(() => window.meshqDemo?.ready || window.meshqDemo?.error, null, { timeout: 60000 });
  assert.equal(await page.evaluate(() => window.meshqDemo.error), undefined);
  assert.equal(await page.textContent('#stat-triangles'), '69,451');
  assert.ok(served.includes('/node_modules/meshq-wasm/web/meshq_wasm_bg.wasm'), 'the .wasm came from the installed package');
  const box = await page.locator('#view').boundingBox();
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => window.meshqDemo.lastHit !== null);
  // The drop-in through the same import map: a sphere's hit equals three's own.
  const same = await page.evaluate(async () => {
    const THREE = await import('three');
    const { acceleratedRaycast, computeBoundsTree } = await import('meshq-wasm/three');
    const geometry = new THREE.SphereGeometry(1, 32, 16);
    geometry.computeBoundsTree = computeBoundsTree;
    geometry.computeBoundsTree();
    const fast = new THREE.Mesh(geometry);
    fast.raycast = acceleratedRaycast;
    const raycaster = new THREE.Raycaster(new THREE.Vector3(0.1, 0.2, 5), new THREE.Vector3(0, 0, -1));
    const a = raycaster.intersectObject(fast).map((h) => [h.distance, h.faceIndex]);
    const b = raycaster.intersectObject(new THREE.Mesh(geometry)).map((h) => [h.distance, h.faceIndex]);
    return JSON.stringify(a) === JSON.stringify(b) && a.length === 1;
  });
  assert.ok(same, 'meshq-wasm/three in the browser equals three');
  // The worker pool through the same map: Web Workers loading the blob (copied: this page is
  // not cross-origin isolated) answer as one thread does.
  const pooled = await page.evaluate(async () => {
    const { MeshBvh, randomRays } = await import('meshq-wasm');
    const { MeshqPool } = await import('meshq-wasm/pool');
    const bytes = new Uint8Array(await (await fetch('assets/bunny.meshq')).arrayBuffer());
    const bvh = MeshBvh.fromBlob(bytes);
    const rays = randomRays(bvh.bounds(), 5, 20000);
    const t = new Float32Array(20000);
    const triangles = new Uint32Array(20000);
    const hits = bvh.raycastBatch(rays, 0, Infinity, t, triangles);
    const pool = await MeshqPool.fromBlob(bytes, { workers: 2 });
    const got = await pool.raycastBatch(rays);
    const { size, shared } = pool;
    pool.terminate();
    const same = got.hits === hits && got.t.every((x, i) => Object.is(x, t[i])) && got.triangles.every((x, i) => x === triangles[i]);
    return { same, hits, shared, size };
  });
  assert.ok(pooled.same && pooled.hits > 5000 && pooled.size === 2 && !pooled.shared, JSON.stringify(pooled));
  // The same page served cross-origin isolated: the pool shares memory with its workers, which
  // take the batch in pieces (Atomics on a SharedArrayBuffer), and answers as one thread does.
  await page.goto(new URL('?isolated', url).href);
  await page.waitForFunction(() => window.meshqDemo?.ready || window.meshqDemo?.error, null, { timeout: 60000 });
  const isolated = await page.evaluate(async () => {
    const { MeshBvh, randomRays, queryPoints } = await import('meshq-wasm');
    const { MeshqPool } = await import('meshq-wasm/pool');
    const bytes = new Uint8Array(await (await fetch('assets/bunny.meshq')).arrayBuffer());
    const bvh = MeshBvh.fromBlob(bytes);
    const n = 50003;
    const rays = randomRays(bvh.bounds(), 6, n);
    const t = new Float32Array(n);
    const triangles = new Uint32Array(n);
    const hits = bvh.raycastBatch(rays, 0, Infinity, t, triangles);
    const points = queryPoints(bvh.bounds(), 7, 20000);
    const distances = new Float32Array(20000);
    const closestTriangles = new Uint32Array(20000);
    const found = bvh.closestPointBatch(points, 0.05, new Float32Array(60000), closestTriangles, distances);
    const pool = await MeshqPool.fromBlob(bytes, { workers: 2 });
    const got = await pool.raycastBatch(rays);
    const near = await pool.closestPointBatch(points, 0.05);
    const { size, shared } = pool;
    pool.terminate();
    const same = got.hits === hits && got.t.every((x, i) => Object.is(x, t[i])) && got.triangles.every((x, i) => x === triangles[i])
      && near.found === found && near.distances.every((x, i) => Object.is(x, distances[i]))
      && near.triangles.every((x, i) => x === closestTriangles[i]);
    return { same, hits, found, shared, size, isolated: globalThis.crossOriginIsolated };
  });
  assert.ok(isolated.same && isolated.hits > 10000 && isolated.found > 0 && isolated.size === 2 && isolated.shared
    && isolated.isolated, JSON.stringify(isolated));
  assert.deepEqual(errors, [], 'no console errors');
  console.log('browser: the demo, meshq-wasm/three and meshq-wasm/pool (2 Web Workers, copied and shared) run from the installed tarball through the import map');
} finally {
  await browser?.close();
  server.kill();
  clearTimeout(watchdog);
}
rmSync(scratch, { recursive: true, force: true });
console.log('pack: the tarball installs and works in Node and in Chromium');
