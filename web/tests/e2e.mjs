// End to end in real headless Chromium (Debian's chromium, driven by playwright-core): open
// the demo, wait for the bunny blob, click the canvas centre, check that the displayed hit
// equals the native answer for that exact ray (the meshq command, run on the same blob), load
// the collision mode (pairs and curve equal to `meshq check`, before and after a drag), another
// blob through the file input, run the benchmark button, remesh it (equal to the native
// command bit for bit), and save screenshots.
// Run after scripts/build-web.sh: node web/tests/e2e.mjs (MESHQ_BIN: the native meshq binary).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import http from 'node:http';
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium, startServer } from './browser.mjs';

const root = fileURLToPath(new URL('../..', import.meta.url));
const meshq = process.env.MESHQ_BIN ?? join(root, 'target/release/meshq');
const out = join(root, 'target/e2e');
mkdirSync(out, { recursive: true });
const scratch = mkdtempSync(join(tmpdir(), 'meshq-e2e-'));

// Our server, on a port the OS picks, checked to be ours.
const { url, server } = await startServer(join(root, 'web'), 'e2e');

// Odd request paths get an answer, never a crash: `//` (once fatal), a malformed escape, a
// climb out of the folder.
const status = (path) => new Promise((resolve, reject) => {
  const { hostname, port } = new URL(url);
  http.get({ hostname, port, path }, (r) => { r.resume(); resolve(r.statusCode); }).on('error', reject);
});
assert.deepEqual(
  [await status('//'), await status('/%E0%A4%A'), await status('/../../etc/passwd'), await status('/')],
  [200, 400, 404, 200],
  'odd paths',
);

// Never hang CI, and say where time went: each step has a budget of its own, sized for a
// cold Chromium on a machine whose other core is busy, and its time is printed as it ends.
let watchdog = null;
let current = null;
const stepTimes = [];
function step(name, budgetSeconds) {
  endStep();
  current = { name, started: performance.now() };
  watchdog = setTimeout(() => {
    console.error(`e2e: step "${name}" took more than its ${budgetSeconds} s`);
    server.kill();
    process.exit(1);
  }, budgetSeconds * 1000);
}
function endStep() {
  clearTimeout(watchdog);
  if (current === null) return;
  const seconds = (performance.now() - current.started) / 1000;
  stepTimes.push(`${current.name} ${seconds.toFixed(1)} s`);
  console.log(`  [${seconds.toFixed(1)} s] ${current.name}`);
  current = null;
}

// launch() gives the browser a fresh temporary profile (--user-data-dir) of its own.
let browser = null;
const errors = [];
try {
  step('start Chromium and load the demo with the bunny blob', 150);
  browser = await launchChromium();
  const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  await page.waitForFunction(() => window.meshqDemo?.ready || window.meshqDemo?.error, null, { timeout: 60000 });
  assert.equal(await page.evaluate(() => window.meshqDemo.error), undefined);
  assert.equal(await page.textContent('#stat-triangles'), '69,451');

  step('centre click against the native answer', 60);
  // Click the canvas centre: the camera looks at the bunny's centre, so this hits it.
  const box = await page.locator('#view').boundingBox();
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => window.meshqDemo.lastRay !== null);
  const { lastRay, lastHit } = await page.evaluate(() => window.meshqDemo);
  assert.ok(lastHit, 'the centre ray hits the bunny');
  const shownTriangle = Number(await page.textContent('#hit-triangle'));
  const shownDistance = await page.textContent('#hit-distance');

  // The native answer for the same f32 ray, from the same blob.
  const rays = join(scratch, 'ray.bin');
  const hits = join(scratch, 'hit.bin');
  const native = (ray) => {
    writeFileSync(rays, Buffer.from(Float32Array.from([...ray.origin, ...ray.direction]).buffer));
    execFileSync(meshq, ['raycast', join(root, 'web/assets/bunny.meshq'), '--rays', rays, '--out', hits]);
    const record = readFileSync(hits);
    return [record.readFloatLE(0), record.readUInt32LE(4)];
  };
  const [nativeT, nativeTriangle] = native(lastRay);
  assert.equal(shownTriangle, nativeTriangle, 'displayed triangle = native');
  assert.equal(lastHit.triangle, nativeTriangle);
  assert.equal(Math.fround(lastHit.t), nativeT, 't bits = native');
  // The distance shown is Euclidean: t times the length of the f32 direction, in doubles.
  const [dx, dy, dz] = lastRay.direction;
  const nativeDistance = nativeT * Math.sqrt(dx * dx + dy * dy + dz * dz);
  assert.equal(lastHit.distance, nativeDistance, 'distance = native t · |direction|');
  assert.equal(shownDistance, nativeDistance.toPrecision(9), 'displayed distance = native');
  console.log(`centre click: triangle ${shownTriangle}, distance ${shownDistance} — equal to native`);

  step('BVH boxes and the benchmark button (1M rays)', 180);
  // The BVH view and the benchmark button.
  await page.check('#bvh-show');
  assert.match(await page.textContent('#bvh-level-text'), /level \d+: \d+ boxes/);
  await page.click('#bench');
  await page.waitForFunction(() => window.meshqDemo.bench !== null, null, { timeout: 120000 });
  const bench = await page.evaluate(() => window.meshqDemo.bench);
  assert.equal(bench.rays, 1000000);
  assert.ok(bench.hits > 300000, `benchmark hits: ${bench.hits}`);
  console.log(`benchmark button: ${(bench.raysPerSecond / 1e6).toFixed(2)} M rays/s in headless Chromium`);
  await page.screenshot({ path: join(out, 'demo-bunny.png') });

  step('k-d tree, octree and grid: build, draw, pick', 240);
  // The structure selector: each structure built in the page draws its cells and picks the
  // triangle the native BVH picks, at the same distance bits.
  for (const structure of ['kdtree', 'octree', 'grid']) {
    await page.selectOption('#structure', structure);
    await page.waitForFunction((s) => window.meshqDemo.structure === s, structure, { timeout: 120000 });
    assert.match(await page.textContent('#bvh-level-text'), /level \d+: [1-9]\d* boxes/, structure);
    await page.mouse.click(box.x + box.width / 2 + 7, box.y + box.height / 2 - 5);
    await page.waitForFunction(() => window.meshqDemo.lastHit !== null);
    const picked = await page.evaluate(() => window.meshqDemo);
    const [t, triangle] = native(picked.lastRay);
    assert.equal(picked.lastHit.triangle, triangle, `${structure}: triangle = native`);
    assert.equal(Math.fround(picked.lastHit.t), t, `${structure}: t bits = native`);
    await page.screenshot({ path: join(out, `demo-bunny-${structure}.png`) });
    console.log(`${structure}: ${await page.textContent('#bvh-level-text')}, pick equal to native`);
  }

  step('collision mode against meshq check, before and after a drag', 180);
  // Collision mode: a second copy of the bunny beside the first; the pairs where they meet and
  // the crossing segments equal the native check's for the same f32 placement, before and
  // after dragging the copy with the mouse.
  const nativeCheck = (matrix) => {
    const bunny = join(root, 'assets/stanford-bunny.obj');
    const report = JSON.parse(execFileSync(meshq, ['check', bunny, '--against', bunny,
      '--transform', matrix.map(String).join(','), '--json']));
    return report.against;
  };
  await page.check('#collide');
  await page.waitForFunction(() => window.meshqDemo.collide?.updates >= 1, null, { timeout: 60000 });
  const placed = await page.evaluate(() => window.meshqDemo.collide);
  let against = nativeCheck(placed.matrix);
  assert.ok(placed.pairs > 0, 'the copy overlaps the bunny');
  assert.equal(placed.pairs, against.intersecting_pairs, 'pairs = native');
  assert.equal(placed.segments, against.crossing_pairs, 'segments = native');
  assert.equal(await page.textContent('#collide-pairs'), placed.pairs.toLocaleString('en'));
  await page.screenshot({ path: join(out, 'demo-collide.png') });
  const [ax, ay] = placed.anchor;
  await page.mouse.move(box.x + ax, box.y + ay);
  await page.mouse.down();
  for (let step = 1; step <= 5; step++) await page.mouse.move(box.x + ax + 12 * step, box.y + ay + 4 * step);
  await page.mouse.up();
  await page.waitForFunction((n) => window.meshqDemo.collide.updates > n, placed.updates, { timeout: 60000 });
  const dragged = await page.evaluate(() => window.meshqDemo.collide);
  assert.ok(dragged.matrix[12] > placed.matrix[12], 'the drag moved the copy right');
  against = nativeCheck(dragged.matrix);
  assert.equal(dragged.pairs, against.intersecting_pairs, 'pairs after the drag = native');
  assert.equal(dragged.segments, against.crossing_pairs, 'segments after the drag = native');
  await page.screenshot({ path: join(out, 'demo-collide-dragged.png') });
  console.log(`collide mode: ${placed.pairs} pairs, dragged: ${dragged.pairs} pairs (${dragged.ms.toFixed(1)} ms), equal to native`);
  await page.uncheck('#collide');

  step('another blob through the file input', 90);
  // Another blob through the file input: spot, baked by the command.
  const spot = join(scratch, 'spot.meshq');
  execFileSync(meshq, ['bake', join(root, 'assets/spot.obj'), '-o', spot]);
  await page.setInputFiles('#file', spot);
  await page.waitForFunction(() => window.meshqDemo.source === 'spot.meshq');
  assert.equal(await page.textContent('#stat-triangles'), '5,856');
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => window.meshqDemo.lastHit !== null);
  await page.screenshot({ path: join(out, 'demo-spot.png') });

  step('remesh button against the native command', 180);
  // The remesh button on spot: the result equals the native command's, bit for bit.
  await page.click('#remesh');
  await page.waitForFunction(() => window.meshqDemo.remesh || window.meshqDemo.remeshError, null, { timeout: 120000 });
  const remeshed = await page.evaluate(() => window.meshqDemo.remesh);
  assert.ok(remeshed, await page.evaluate(() => window.meshqDemo.remeshError));
  const ply = join(scratch, 'spot-remeshed.ply');
  const summary = JSON.parse(execFileSync(meshq, ['remesh', join(root, 'assets/spot.obj'), '-o', ply, '--json']));
  const bytes = readFileSync(ply);
  const body = bytes.indexOf('end_header\n') + 'end_header\n'.length;
  const vertices = Number(/element vertex (\d+)/.exec(bytes.toString('latin1', 0, body))[1]);
  const triangles = Number(/element face (\d+)/.exec(bytes.toString('latin1', 0, body))[1]);
  const nativePositions = new Float32Array(bytes.buffer.slice(bytes.byteOffset + body, bytes.byteOffset + body + vertices * 12));
  const nativeIndices = [];
  for (let t = 0, at = body + vertices * 12; t < triangles; t++, at += 13) {
    nativeIndices.push(bytes.readUInt32LE(at + 1), bytes.readUInt32LE(at + 5), bytes.readUInt32LE(at + 9));
  }
  assert.equal(remeshed.triangles, summary.after.triangles, 'remeshed triangles = native');
  assert.deepEqual(remeshed.indices, nativeIndices, 'remeshed indices = native');
  assert.deepEqual(remeshed.positions, Array.from(nativePositions), 'remeshed positions = native, bit for bit');
  assert.equal(remeshed.after.valence6Percent, Math.fround(summary.after.valence_6_percent));
  assert.match(await page.textContent('#remesh-figures'), /valence 6/);
  assert.match(await page.textContent('#remesh-histogram'), /interior valences/);
  await page.check('#remesh-before');
  await page.screenshot({ path: join(out, 'demo-spot-before-remesh.png') });
  await page.uncheck('#remesh-before');
  await page.screenshot({ path: join(out, 'demo-spot-remeshed.png') });
  console.log(`remesh button: ${remeshed.triangles} triangles in ${(remeshed.ms / 1000).toFixed(2)} s, equal to native`);
  endStep();
  assert.deepEqual(errors, [], 'no console errors');
  console.log(`end to end in Chromium: ok (screenshots in ${out})`);
} finally {
  endStep();
  if (stepTimes.length > 0) console.log(`e2e steps: ${stepTimes.join('; ')}`);
  await browser?.close();
  server.kill();
  rmSync(scratch, { recursive: true, force: true });
}
