// Timing and the peer's ray loop, shared by the browser page (bench.js) and the Node
// benchmark (bench/node/bench.mjs), so that both time the same way. No imports: the caller
// hands over its own `three` (the page's import map, or the Node benchmark's node_modules).

/** Median wall time in ms of `runs` calls of `f`, after one warm-up call (builds, loads). */
export function median(f, runs) {
  f();
  const times = [];
  for (let i = 0; i < runs; i++) {
    const t0 = performance.now();
    f();
    times.push(performance.now() - t0);
  }
  times.sort((a, b) => a - b);
  return times[Math.floor(times.length / 2)];
}

/**
 * Best wall times in ms of `ours` and `theirs` over `rounds` rounds, after one warm-up call of
 * each: every round times one call of each, back to back, so that a slow spell of a shared
 * machine falls on both sides alike (timed apart, one side's runs could land in it alone).
 */
export function paired(ours, theirs, rounds = 5) {
  ours();
  theirs();
  let [best, peerBest] = [Infinity, Infinity];
  for (let i = 0; i < rounds; i++) {
    let t0 = performance.now();
    ours();
    best = Math.min(best, performance.now() - t0);
    t0 = performance.now();
    theirs();
    peerBest = Math.min(peerBest, performance.now() - t0);
  }
  return [best, peerBest];
}

/** `paired` for an `ours` that returns a promise (a worker pool's batch). */
export async function pairedAsync(ours, theirs, rounds = 5) {
  await ours();
  theirs();
  let [best, peerBest] = [Infinity, Infinity];
  for (let i = 0; i < rounds; i++) {
    let t0 = performance.now();
    await ours();
    best = Math.min(best, performance.now() - t0);
    t0 = performance.now();
    theirs();
    peerBest = Math.min(peerBest, performance.now() - t0);
  }
  return [best, peerBest];
}

/**
 * three-mesh-bvh's `raycastFirst` (both faces) on the first `count` rays of `rays` (6 numbers
 * per ray: origin, direction), one `THREE.Ray` filled number by number as an app's loop would;
 * the number of hits. `THREE` is the caller's three.js module.
 */
export function peerFirstHits(THREE, peer, rays, count) {
  const ray = new THREE.Ray();
  let hits = 0;
  for (let k = 0; k < count; k++) {
    ray.origin.set(rays[6 * k], rays[6 * k + 1], rays[6 * k + 2]);
    ray.direction.set(rays[6 * k + 3], rays[6 * k + 4], rays[6 * k + 5]);
    if (peer.raycastFirst(ray, THREE.DoubleSide)) hits++;
  }
  return hits;
}
