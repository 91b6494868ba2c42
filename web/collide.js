// The demo's collision mode: a second copy of the mesh that the user drags (and turns with a
// slider); on every move meshq finds the triangle pairs where the two meet and the segments
// where they cross, and the page highlights those triangles and draws the curve.
import * as THREE from 'three';
import { MeshBvh } from 'meshq-wasm';

const $ = (id) => document.getElementById(id);

/** Triangles (by index, deduplicated) of a triangle soup `positions`, as a new geometry. */
function trianglesGeometry(positions, indices) {
  const unique = [...new Set(indices)];
  const out = new Float32Array(unique.length * 9);
  unique.forEach((t, i) => out.set(positions.subarray(9 * t, 9 * t + 9), 9 * i));
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(out, 3));
  return g;
}

/**
 * Sets up the mode. `view` gives what it needs of the page: `scene`, `camera`, `controls`,
 * `canvas`, `pointerRay(event)`, `current()` (the shown mesh: `{ bvh, positions, centre,
 * radius }` or null) and `demo` (the object tests read).
 */
export function setUpCollide(view) {
  const { scene, camera, controls, canvas, demo } = view;
  const mover = new THREE.Group();
  const moverMesh = new THREE.Mesh(new THREE.BufferGeometry(),
    new THREE.MeshStandardMaterial({ color: 0x88aadd, roughness: 0.8, flatShading: true, transparent: true, opacity: 0.85 }));
  const highlight = new THREE.MeshBasicMaterial({ color: 0xff3355, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: -2 });
  const hitA = new THREE.Mesh(new THREE.BufferGeometry(), highlight);
  const hitB = new THREE.Mesh(new THREE.BufferGeometry(), highlight);
  const curve = new THREE.LineSegments(new THREE.BufferGeometry(),
    new THREE.LineBasicMaterial({ color: 0xffee33, depthTest: false }));
  curve.renderOrder = 2;
  mover.add(moverMesh, hitB);
  for (const o of [mover, hitA, curve]) {
    o.visible = false;
    scene.add(o);
  }

  // Both copies are answered by one BVH over the shown mesh (built once per mesh when the
  // shown structure is not a BVH).
  let tree = null;
  let dirty = false;
  let drag = null;

  function enabled() {
    return $('collide').checked && view.current() !== null;
  }

  function treeOf(shown) {
    if (tree?.shown === shown) return tree.bvh;
    tree?.owned?.free();
    const owned = shown.bvh.structure === 'bvh' ? null
      : MeshBvh.build(shown.bvh.vertexPositions(), shown.bvh.indices(), { structure: 'bvh' });
    tree = { shown, owned, bvh: owned ?? shown.bvh };
    return tree.bvh;
  }

  /** Column-major placement of the dragged copy, in f32 (what meshq computes with). */
  function placement() {
    mover.rotation.y = THREE.MathUtils.degToRad(Number($('collide-turn').value));
    mover.updateMatrix();
    return Float32Array.from(mover.matrix.elements);
  }

  /** Runs the two queries for the current placement and redraws. */
  function update() {
    dirty = false;
    const shown = view.current();
    if (!enabled()) return;
    const bvh = treeOf(shown);
    const matrix = placement();
    const t0 = performance.now();
    const found = bvh.intersectingPairs(bvh, matrix, 200000);
    const segments = bvh.intersectionSegments(bvh, matrix);
    const ms = performance.now() - t0;
    const firsts = [];
    const seconds = [];
    for (let i = 0; i < found.pairs.length; i += 2) {
      firsts.push(found.pairs[i]);
      seconds.push(found.pairs[i + 1]);
    }
    for (const [mesh, tris] of [[hitA, firsts], [hitB, seconds]]) {
      mesh.geometry.dispose();
      mesh.geometry = trianglesGeometry(shown.positions, tris);
      mesh.visible = tris.length > 0;
    }
    curve.geometry.dispose();
    curve.geometry = new THREE.BufferGeometry();
    curve.geometry.setAttribute('position', new THREE.BufferAttribute(segments, 3));
    curve.visible = segments.length > 0;
    $('collide-pairs').textContent = found.total.toLocaleString('en');
    $('collide-segments').textContent = (segments.length / 6).toLocaleString('en');
    $('collide-time').textContent = `${ms.toFixed(1)} ms`;
    // Where the copy's centre shows on the canvas (CSS pixels), for tests that drag it.
    const anchor = shown.centre.clone().applyMatrix4(mover.matrix).project(camera);
    demo.collide = {
      anchor: [(anchor.x + 1) / 2 * canvas.clientWidth, (1 - anchor.y) / 2 * canvas.clientHeight],
      matrix: Array.from(matrix),
      pairs: found.total,
      overflowed: found.overflowed,
      segments: segments.length / 6,
      ms,
      updates: (demo.collide?.updates ?? 0) + 1,
    };
  }

  /** Shows or hides the mode; on showing, places the copy beside the mesh, overlapping it. */
  function toggle() {
    const shown = view.current();
    const on = enabled();
    mover.visible = on;
    for (const o of [hitA, curve]) o.visible = on && o.visible;
    if (!on) {
      demo.collide = null;
      return;
    }
    moverMesh.geometry = shown.mesh.geometry;
    mover.position.set(-shown.radius * 0.6, shown.radius * 0.15, 0);
    dirty = true;
  }
  $('collide').addEventListener('change', toggle);
  $('collide-turn').addEventListener('input', () => { dirty = true; });

  /** Where the pointer's ray meets the dragged copy, by a meshq raycast in its own frame. */
  function hitMover(event) {
    const ray = view.pointerRay(event).clone();
    const inverse = mover.matrix.clone().invert();
    ray.applyMatrix4(inverse);
    const bvh = treeOf(view.current());
    const hit = bvh.raycast(Float32Array.from(ray.origin.toArray()),
      Float32Array.from(ray.direction.toArray()), 0, Infinity);
    return hit && new THREE.Vector3(hit.point.x, hit.point.y, hit.point.z).applyMatrix4(mover.matrix);
  }

  // Dragging the copy moves it in the plane through the grabbed point facing the camera; the
  // orbit controls pause meanwhile.
  canvas.addEventListener('pointerdown', (event) => {
    if (!enabled()) return;
    const at = hitMover(event);
    if (!at) return;
    const normal = camera.getWorldDirection(new THREE.Vector3());
    drag = { plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, at), from: at, start: mover.position.clone() };
    controls.enabled = false;
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!drag) return;
    const to = view.pointerRay(event).intersectPlane(drag.plane, new THREE.Vector3());
    if (!to) return;
    mover.position.copy(drag.start).add(to.sub(drag.from));
    dirty = true;
  });
  const release = () => {
    if (!drag) return;
    drag = null;
    controls.enabled = true;
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);

  return {
    /** True while the copy is being dragged (the page then skips its own click handling). */
    dragging: () => drag !== null,
    /** Called when another mesh is shown. */
    meshChanged: () => { toggle(); },
    /**
     * Called once per frame: answers at most once per frame, however fast the pointer. True
     * when it changed the scene.
     */
    frame: () => {
      if (!dirty) return false;
      update();
      return true;
    },
  };
}
