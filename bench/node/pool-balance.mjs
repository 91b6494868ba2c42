// How meshq-wasm/pool shares a batch between two workers when one of them runs at half speed
// (a core shared with a busy process), as on machines with fast and slow cores. Linux only:
// it pins each worker thread to a core with `taskset` and starts the busy process itself.
//
//   node bench/node/pool-balance.mjs [--json]
//
// Compared, on the same rays and points: one worker; two workers in shared memory (they take
// the batch in pieces from a shared counter); two workers with copies (one equal share each).
// Each is timed with both cores free, then with the second worker's core shared. Build the
// package and the bunny's blob first (scripts/build-web.sh). Environment: MESHQ_BENCH_RAYS
// (default 1,000,000), MESHQ_BENCH_POINTS (default 200,000).
import { execFileSync, spawn } from 'node:child_process';
import { readdirSync, readFileSync } from 'node:fs';
import { availableParallelism } from 'node:os';
import { fileURLToPath } from 'node:url';
import meshq from '../../wasm/pkg/node/meshq_wasm.js';
import { MeshqPool } from '../../wasm/pkg/node/pool.mjs';

const RAYS = Number(process.env.MESHQ_BENCH_RAYS ?? 1_000_000);
const POINTS = Number(process.env.MESHQ_BENCH_POINTS ?? 200_000);
const json = process.argv.includes('--json');
const log = (...a) => { if (!json) console.log(...a); };
if (process.platform !== 'linux') throw new Error('pool-balance.mjs pins threads with taskset: Linux only');
if (availableParallelism() < 2) {
  console.log('pool-balance: one core here, nothing to balance');
  process.exit(0);
}

const root = fileURLToPath(new URL('../..', import.meta.url));
const blob = readFileSync(`${root}/web/assets/bunny.meshq`);
const bvh = meshq.MeshBvh.fromBlob(blob);
const rays = meshq.randomRays(bvh.bounds(), 1, RAYS);
const points = meshq.queryPoints(bvh.bounds(), 2, POINTS);
const workloads = {
  'random rays': (pool) => pool.raycastBatch(rays),
  'closest points': (pool) => pool.closestPointBatch(points, Infinity),
};

/** CPU time (clock ticks) used so far by each thread of this process, by thread id. */
function threadTimes() {
  const times = {};
  for (const tid of readdirSync('/proc/self/task')) {
    const stat = readFileSync(`/proc/self/task/${tid}/stat`, 'utf8');
    // utime is the 14th field; the name (2nd) may hold spaces, so count from its ')'.
    times[tid] = Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[11]);
  }
  return times;
}

/** The ids of `pool`'s worker threads: the threads that worked while it answered. */
async function workerThreads(pool) {
  const before = threadTimes();
  for (let i = 0; i < 3; i++) await pool.raycastBatch(rays);
  const after = threadTimes();
  return Object.keys(after)
    .filter((tid) => tid !== String(process.pid))
    .sort((a, b) => (after[b] - (before[b] ?? 0)) - (after[a] - (before[a] ?? 0)))
    .slice(0, pool.size);
}

const pin = (tid, core) => execFileSync('taskset', ['-p', '-c', String(core), tid], { stdio: 'ignore' });
pin(String(process.pid), 0);
const pools = {
  'one worker': await MeshqPool.fromBlob(blob, { workers: 1 }),
  'two, shared (pieces)': await MeshqPool.fromBlob(blob, { workers: 2 }),
  'two, copied (equal shares)': await MeshqPool.fromBlob(blob, { workers: 2, shared: false }),
};
if (!pools['two, shared (pieces)'].shared) throw new Error('no SharedArrayBuffer here');
// The answers first: every pool gives the single-thread ones.
{
  const t = new Float32Array(RAYS);
  const want = new Uint32Array(RAYS);
  bvh.raycastBatch(rays, 0, Infinity, t, want);
  for (const [name, pool] of Object.entries(pools)) {
    const got = await pool.raycastBatch(rays);
    if (!got.triangles.every((x, i) => x === want[i])) throw new Error(`${name}: other answers`);
  }
}
for (const pool of Object.values(pools)) {
  const tids = await workerThreads(pool);
  tids.forEach((tid, k) => pin(tid, k % 2));
}

/** Median ms of 5 interleaved rounds of every pool on `workload`. */
async function timeAll(workload) {
  const times = Object.fromEntries(Object.keys(pools).map((name) => [name, []]));
  for (let round = 0; round < 5; round++) {
    for (const [name, pool] of Object.entries(pools)) {
      const t0 = performance.now();
      await workload(pool);
      times[name].push(performance.now() - t0);
    }
  }
  const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
  return Object.fromEntries(Object.entries(times).map(([name, v]) => [name, median(v)]));
}

const results = [];
for (const [workload, run] of Object.entries(workloads)) {
  for (const busy of [false, true]) {
    // The busy process shares core 1 with the second worker of each pool.
    const hog = busy ? spawn('taskset', ['-c', '1', 'sh', '-c', 'while :; do :; done'], { stdio: 'ignore' }) : null;
    // Never leave it running, whatever happens here.
    const stop = () => hog?.kill('SIGKILL');
    process.on('exit', stop);
    let ms;
    try {
      if (hog) await new Promise((r) => setTimeout(r, 300));
      ms = await timeAll(run);
    } finally {
      stop();
      process.off('exit', stop);
    }
    const one = ms['one worker'];
    log(`${workload}, ${busy ? 'second core shared with a busy process' : 'both cores free'}:`);
    for (const [name, t] of Object.entries(ms)) {
      log(`  ${name.padEnd(28)} ${t.toFixed(1).padStart(7)} ms  ${(one / t).toFixed(2)}× one worker`);
      results.push({ workload, busy, pool: name, ms: t, speedup: one / t });
    }
  }
}
if (json) console.log(JSON.stringify({ rays: RAYS, points: POINTS, results }, null, 2));
for (const pool of Object.values(pools)) pool.terminate();
bvh.free();
