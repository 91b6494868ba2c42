// The meshq demo: the bundled bunny loaded as a prebuilt blob, click-to-pick, a closest-point
// probe, a structure selector (BVH, k-d tree, octree, grid) drawing its levels and cells,
// remeshing with the quality before and after, a collision mode (a dragged second copy, with
// the triangles where the two meet and the curve where they cross) and a batched benchmark.
// Everything geometric is answered by meshq (WebAssembly); three.js only draws.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { OBJLoader } from 'three/addons/loaders/OBJLoader.js';
import { PLYLoader } from 'three/addons/loaders/PLYLoader.js';
import { STLLoader } from 'three/addons/loaders/STLLoader.js';
import { mergeGeometries } from 'three/addons/utils/BufferGeometryUtils.js';
import init, { MeshBvh, randomRays, remesh } from 'meshq-wasm';
import { setUpCollide } from './collide.js';

const $ = (id) => document.getElementById(id);
const demo = { ready: false, source: null, triangles: 0, lastRay: null, lastHit: null, bench: null };
window.meshqDemo = demo;

const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2126);
const camera = new THREE.PerspectiveCamera(45, 1, 0.001, 100);
const controls = new OrbitControls(camera, canvas);
scene.add(new THREE.HemisphereLight(0xffffff, 0x334455, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
sun.position.set(1, 2, 1.5);
scene.add(sun);

const surface = new THREE.MeshStandardMaterial({ color: 0xc8b8a0, roughness: 0.8, flatShading: true });
const marker = new THREE.Mesh(new THREE.SphereGeometry(1, 16, 12), new THREE.MeshBasicMaterial({ color: 0xff3355 }));
const picked = new THREE.Mesh(new THREE.BufferGeometry(),
  new THREE.MeshBasicMaterial({ color: 0xff3355, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: -2 }));
const probe = new THREE.Mesh(new THREE.SphereGeometry(1, 12, 8), new THREE.MeshBasicMaterial({ color: 0x44bbff }));
const probeHit = new THREE.Mesh(new THREE.SphereGeometry(1, 12, 8), new THREE.MeshBasicMaterial({ color: 0x44ffaa }));
const probeLine = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x44ffaa }));
const boxes = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x66aaff, transparent: true, opacity: 0.7 }));
const wire = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x202020, transparent: true, opacity: 0.45 }));
for (const o of [marker, picked, probe, probeHit, probeLine, boxes, wire]) {
  o.visible = false;
  scene.add(o);
}

let state = null; // { bvh, mesh, positions, centre, radius }

// Frames are drawn on demand: after an input event, a camera move or a change to what is shown.
// An idle page then costs nothing, and a deep octree level (tens of thousands of boxes) is not
// redrawn sixty times a second while nothing moves.
let needsRender = true;
function invalidate() {
  needsRender = true;
}
for (const type of ['pointerdown', 'pointermove', 'pointerup', 'wheel', 'keydown', 'input', 'change', 'click', 'drop']) {
  window.addEventListener(type, invalidate, { capture: true, passive: true });
}
controls.addEventListener('change', invalidate);

function resize() {
  const { clientWidth: w, clientHeight: h } = canvas;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  invalidate();
}
window.addEventListener('resize', resize);

function format(x, digits = 6) {
  return Number(x).toPrecision(digits);
}

/** Shows a MeshBvh: display geometry from its triangles, camera framed on its bounds. */
function show(bvh, source, timeLabel, ms, blobBytes) {
  invalidate();
  if (state) {
    scene.remove(state.mesh);
    state.mesh.geometry.dispose();
    state.bvh.free();
  }
  const positions = bvh.trianglePositions();
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.computeVertexNormals();
  const mesh = new THREE.Mesh(geometry, surface);
  scene.add(mesh);
  const b = bvh.bounds();
  const centre = new THREE.Vector3((b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2);
  const radius = Math.hypot(b[3] - b[0], b[4] - b[1], b[5] - b[2]) / 2;
  state = { bvh, mesh, positions, centre, radius };
  updateWire();
  // The design workload's camera: 2.5 r in front of the centre, looking down -z.
  camera.position.set(centre.x, centre.y, centre.z + 2.5 * radius);
  camera.near = radius / 100;
  camera.far = radius * 20;
  camera.updateProjectionMatrix();
  controls.target.copy(centre);
  controls.update();
  for (const s of [marker, probe, probeHit]) s.scale.setScalar(radius * 0.012);
  for (const o of [marker, picked, probe, probeHit, probeLine]) o.visible = false;
  const slider = $('bvh-level');
  slider.max = String(Math.max(bvh.depth - 1, 0));
  slider.value = String(Math.min(10, bvh.depth - 1));
  updateBoxes();
  $('structure').value = bvh.structure;
  $('stat-structure').textContent = $('structure').selectedOptions[0]?.textContent ?? bvh.structure;
  $('stat-source').textContent = source;
  $('stat-triangles').textContent = bvh.triangleCount.toLocaleString('en');
  $('stat-nodes').textContent = bvh.nodeCount.toLocaleString('en');
  $('stat-time-label').textContent = timeLabel;
  $('stat-time').textContent = `${ms.toFixed(1)} ms`;
  $('stat-blob').textContent = `${(blobBytes ?? bvh.toBlob().length).toLocaleString('en')} bytes`;
  for (const id of ['hit-triangle', 'hit-distance', 'hit-normal', 'probe-distance', 'bench-result']) $(id).textContent = '—';
  Object.assign(demo, { source, structure: bvh.structure, triangles: bvh.triangleCount, lastRay: null, lastHit: null, bench: null });
  collide.meshChanged();
}

/** Shows the input or the remeshed mesh (after a remesh), with its wireframe if asked. */
function updateWire() {
  if (!state) return;
  invalidate();
  state.displayed ??= state.mesh.geometry;
  const input = remeshed !== null && $('remesh-before').checked;
  state.mesh.geometry = input ? remeshed.input : state.displayed;
  wire.geometry.dispose();
  wire.geometry = new THREE.WireframeGeometry(state.mesh.geometry);
  wire.visible = $('wireframe').checked;
}

function updateBoxes() {
  invalidate();
  const level = Number($('bvh-level').value);
  $('bvh-level-text').textContent = `level ${level}`;
  boxes.visible = $('bvh-show').checked && state !== null;
  if (!boxes.visible) return;
  const flat = state.bvh.levelBoxes(level);
  const n = flat.length / 6;
  const lines = new Float32Array(n * 72);
  // Corner k of a box takes max x where bit 0 is set, max y for bit 1, max z for bit 2. The
  // coordinates are written straight into the array: a deep octree level has tens of
  // thousands of boxes, and an array per corner made drawing it take seconds.
  const ends = [0, 1, 1, 3, 3, 2, 2, 0, 4, 5, 5, 7, 7, 6, 6, 4, 0, 4, 1, 5, 2, 6, 3, 7];
  let at = 0;
  for (let i = 0; i < n; i++) {
    const base = 6 * i;
    for (const k of ends) {
      lines[at++] = flat[base + (k & 1 ? 3 : 0)];
      lines[at++] = flat[base + 1 + (k & 2 ? 3 : 0)];
      lines[at++] = flat[base + 2 + (k & 4 ? 3 : 0)];
    }
  }
  boxes.geometry.dispose();
  boxes.geometry = new THREE.BufferGeometry();
  boxes.geometry.setAttribute('position', new THREE.BufferAttribute(lines, 3));
  $('bvh-level-text').textContent = `level ${level}: ${n} boxes`;
}
$('bvh-level').addEventListener('input', updateBoxes);

// Another structure over the same triangles (in the same order, so triangle ids and every
// answer stay the same); its cells are what "show level" draws.
$('structure').addEventListener('change', () => {
  if (!state) return;
  const structure = $('structure').value;
  $('status').textContent = `building a ${structure}…`;
  setTimeout(() => {
    const t0 = performance.now();
    const bvh = MeshBvh.build(state.positions.slice(), null, { structure });
    show(bvh, demo.source, `${structure} build time`, performance.now() - t0);
    $('status').textContent = `${structure} ready`;
  }, 20);
});
$('bvh-show').addEventListener('change', updateBoxes);

const raycaster = new THREE.Raycaster();
function pointerRay(event) {
  const rect = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2(
    ((event.clientX - rect.left) / rect.width) * 2 - 1,
    -((event.clientY - rect.top) / rect.height) * 2 + 1,
  );
  raycaster.setFromCamera(ndc, camera);
  return raycaster.ray;
}

/** Picks with meshq: marker, highlighted triangle, and the hit in the panel. */
function pick(event) {
  if (!state) return;
  const ray = pointerRay(event);
  const origin = Float32Array.from(ray.origin.toArray());
  const direction = Float32Array.from(ray.direction.toArray());
  const hit = state.bvh.raycast(origin, direction, 0, Infinity);
  demo.lastRay = { origin: Array.from(origin), direction: Array.from(direction) };
  demo.lastHit = hit && { triangle: hit.triangle, t: hit.t, distance: hit.distance };
  marker.visible = picked.visible = hit !== null;
  if (!hit) {
    $('hit-triangle').textContent = 'miss';
    $('hit-distance').textContent = '—';
    $('hit-normal').textContent = '—';
    return;
  }
  marker.position.set(hit.point.x, hit.point.y, hit.point.z);
  const corners = state.positions.slice(9 * hit.triangle, 9 * hit.triangle + 9);
  picked.geometry.dispose();
  picked.geometry = new THREE.BufferGeometry();
  picked.geometry.setAttribute('position', new THREE.BufferAttribute(corners, 3));
  $('hit-triangle').textContent = String(hit.triangle);
  $('hit-distance').textContent = format(hit.distance, 9);
  const n = hit.normal;
  $('hit-normal').textContent = `${format(n.x, 3)}, ${format(n.y, 3)}, ${format(n.z, 3)}`;
}

let down = null;
canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
canvas.addEventListener('pointerup', (e) => {
  if (down && !collide.dragging() && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 4) pick(e);
  down = null;
});

/** The closest-point probe: a point under the mouse, on the plane through the mesh centre
 *  facing the camera, joined to the nearest surface point. */
let pendingMove = null;
canvas.addEventListener('pointermove', (e) => { pendingMove = e; });
function updateProbe() {
  const event = pendingMove;
  pendingMove = null;
  if (!event || !state || !$('probe').checked) {
    if (!$('probe').checked) probe.visible = probeHit.visible = probeLine.visible = false;
    return;
  }
  const ray = pointerRay(event);
  const normal = camera.getWorldDirection(new THREE.Vector3());
  const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(normal, state.centre);
  const at = ray.intersectPlane(plane, new THREE.Vector3());
  if (!at) return;
  const near = state.bvh.closestPoint(Float32Array.from(at.toArray()));
  probe.visible = probeHit.visible = probeLine.visible = near !== null;
  if (!near) return;
  probe.position.copy(at);
  probeHit.position.set(near.point.x, near.point.y, near.point.z);
  probeLine.geometry.dispose();
  probeLine.geometry = new THREE.BufferGeometry().setFromPoints([probe.position, probeHit.position]);
  $('probe-distance').textContent = format(near.distance, 6);
}

/** Indexed display geometry of flat positions and indices. */
function indexedGeometry(positions, indices) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  g.setIndex(new THREE.BufferAttribute(indices, 1));
  g.computeVertexNormals();
  return g;
}

let remeshed = null; // { input: BufferGeometry of the mesh before, result }
$('remesh').addEventListener('click', () => {
  if (!state) return;
  $('status').textContent = 'remeshing…';
  setTimeout(() => {
    try {
      const positions = state.bvh.vertexPositions();
      const indices = state.bvh.indices();
      const input = indexedGeometry(positions, indices);
      const t0 = performance.now();
      const result = remesh(positions, indices, { targetRatio: Number($('remesh-ratio').value) });
      const ms = performance.now() - t0;
      const bvh = MeshBvh.build(result.positions, result.indices, { structure: $('structure').value });
      remeshed = null;
      show(bvh, `${demo.source} remeshed`, 'remesh time', ms);
      remeshed = { input, result };
      $('remesh-before').checked = false;
      updateWire();
      showFigures(result, ms);
      demo.remesh = {
        ms,
        triangles: result.after.triangles,
        positions: Array.from(result.positions),
        indices: Array.from(result.indices),
        before: { ...result.before, valences: Array.from(result.before.valences) },
        after: { ...result.after, valences: Array.from(result.after.valences) },
        distance: result.distance,
      };
      $('status').textContent = `remeshed in ${(ms / 1000).toFixed(2)} s`;
    } catch (error) {
      $('status').textContent = `could not remesh: ${error.message ?? error}`;
      demo.remeshError = String(error.message ?? error);
    }
  }, 20);
});
$('remesh-before').addEventListener('change', updateWire);
$('wireframe').addEventListener('change', updateWire);

/** The quality table and a valence histogram of interior vertices, before and after. */
function showFigures(result, ms) {
  const rows = [
    ['triangles', (q) => q.triangles.toLocaleString('en')],
    ['valence 6', (q) => `${q.valence6Percent.toFixed(1)} %`],
    ['min angle', (q) => `${q.minAngleOffBoundary.toFixed(1)}°`],
    ['angles < 30°', (q) => `${q.under30Percent.toFixed(2)} %`],
    ['edge CV', (q) => q.edgeCv.toFixed(3)],
  ];
  const cells = rows.map(([name, f]) => `<tr><th>${name}</th><td>${f(result.before)}</td><td>${f(result.after)}</td></tr>`);
  $('remesh-figures').innerHTML = `<tr><th></th><th>before</th><th>after</th></tr>${cells.join('')}`
    + `<tr><th>distance</th><td colspan="2">${result.distance.toExponential(2)} of the diagonal</td></tr>`
    + `<tr><th>time</th><td colspan="2">${(ms / 1000).toFixed(2)} s</td></tr>`;
  const bar = (n, total) => '█'.repeat(Math.round((40 * n) / Math.max(total, 1)));
  const total = (h) => h.reduce((a, b) => a + b, 0);
  const lines = [];
  for (let k = 3; k <= 12; k++) {
    const b = result.before.valences[k] ?? 0;
    const a = result.after.valences[k] ?? 0;
    lines.push(`${String(k).padStart(3)}${k === 12 ? '+' : ' '} before ${bar(b, total(result.before.valences)).padEnd(40)} after ${bar(a, total(result.after.valences))}`);
  }
  $('remesh-histogram').textContent = `interior valences\n${lines.join('\n')}`;
}

$('bench').addEventListener('click', () => {
  if (!state) return;
  const count = 1_000_000;
  $('bench-result').textContent = 'running…';
  setTimeout(() => {
    const rays = randomRays(state.bvh.bounds(), 1, count);
    const distances = new Float32Array(count);
    const triangles = new Uint32Array(count);
    const t0 = performance.now();
    const hits = state.bvh.raycastBatch(rays, 0, Infinity, distances, triangles);
    const seconds = (performance.now() - t0) / 1000;
    const rate = count / seconds;
    demo.bench = { rays: count, hits, seconds, raysPerSecond: rate };
    $('bench-result').textContent = `${(rate / 1e6).toFixed(2)} M rays/s (${hits.toLocaleString('en')} hits, ${seconds.toFixed(2)} s)`;
  }, 20);
});

async function loadFile(file) {
  const name = file.name.toLowerCase();
  const ext = name.slice(name.lastIndexOf('.'));
  $('status').textContent = `loading ${file.name}…`;
  try {
    if (['.meshq', '.blob', '.bin'].includes(ext)) {
      const bytes = new Uint8Array(await file.arrayBuffer());
      const t0 = performance.now();
      const bvh = MeshBvh.fromBlob(bytes);
      show(bvh, file.name, 'load time', performance.now() - t0, bytes.length);
    } else {
      let geometry;
      if (ext === '.obj') {
        const group = new OBJLoader().parse(await file.text());
        const parts = [];
        group.traverse((o) => {
          if (o.isMesh) parts.push(o.geometry.index ? o.geometry.toNonIndexed() : o.geometry);
        });
        for (const p of parts) for (const key of Object.keys(p.attributes)) if (key !== 'position') p.deleteAttribute(key);
        geometry = mergeGeometries(parts);
      } else if (ext === '.ply') {
        geometry = new PLYLoader().parse(await file.arrayBuffer());
      } else if (ext === '.stl') {
        geometry = new STLLoader().parse(await file.arrayBuffer());
      } else {
        throw new Error(`unsupported file type ${ext}: use .obj, .ply, .stl or a meshq blob`);
      }
      const positions = geometry.getAttribute('position').array;
      const index = geometry.index ? geometry.index.array : null;
      const t0 = performance.now();
      const bvh = MeshBvh.build(positions, index, { structure: $('structure').value });
      show(bvh, file.name, 'build time', performance.now() - t0);
    }
    $('status').textContent = `${file.name} loaded`;
  } catch (error) {
    $('status').textContent = `could not load ${file.name}: ${error.message ?? error}`;
  }
}

$('file').addEventListener('change', (e) => {
  if (e.target.files.length) loadFile(e.target.files[0]);
});
window.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
window.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
window.addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  if (e.dataTransfer.files.length) loadFile(e.dataTransfer.files[0]);
});

const collide = setUpCollide({
  scene, camera, controls, canvas, pointerRay, demo, current: () => state,
});

function frame() {
  updateProbe();
  if (collide.frame()) invalidate();
  controls.update();
  if (needsRender) {
    needsRender = false;
    renderer.render(scene, camera);
  }
  requestAnimationFrame(frame);
}

async function start() {
  resize();
  await init();
  const response = await fetch('assets/bunny.meshq');
  if (!response.ok) throw new Error(`assets/bunny.meshq: HTTP ${response.status} (run scripts/build-web.sh)`);
  const bytes = new Uint8Array(await response.arrayBuffer());
  const t0 = performance.now();
  const bvh = MeshBvh.fromBlob(bytes);
  show(bvh, 'stanford-bunny.meshq (prebuilt blob)', 'load time', performance.now() - t0, bytes.length);
  $('status').textContent = 'ready: click to pick, move the mouse to probe';
  demo.ready = true;
  requestAnimationFrame(frame);
}

start().catch((error) => {
  $('status').textContent = `failed: ${error.message ?? error}`;
  demo.error = String(error.message ?? error);
});
