#!/usr/bin/env bash
# Every check, as CI runs it: install what is missing, then formatting, lints, docs, the
# bare-metal and WebAssembly builds of the core, all tests, the Python package's tests (with a
# two-worker Dask cluster), the WebAssembly tests in Node, the npm package installed from its
# tarball, its TypeScript typings, the three.js drop-in test, the demo in headless Chromium,
# short runs of the Node and browser benchmarks and fuzzing; beside them, at a lower priority,
# the AVX2 build's tests, the profile-guided build (compared with the test build at the end)
# and the firmware in QEMU. (Clippy with --all-targets type-checks the criterion benchmarks;
# `cargo bench` runs them.)
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh

# A clean clone has no incremental caches to reuse, so CI writes none; the optimised test build
# then also gets fewer, larger code units, which run the tests a little faster.
if [ "${CI:-}" = true ]; then export CARGO_INCREMENTAL=0; fi

# Each step's heading says how long the run has taken so far (CI's budget is 30 minutes) and
# how busy the two cores were since the last heading (both lanes: see below).
busy_ticks() { awk '/^cpu /{print $2+$3+$4+$7+$8+$9, $5+$6}' /proc/stat 2>/dev/null || echo "0 0"; }
read -r last_busy last_idle <<<"$(busy_ticks)"
step() {
  local busy idle cores=?
  read -r busy idle <<<"$(busy_ticks)"
  if [ $((busy + idle - last_busy - last_idle)) -gt 0 ]; then
    cores=$(awk -v b=$((busy - last_busy)) -v i=$((idle - last_idle)) -v n="$(nproc)" \
      'BEGIN{printf "%.1f", n * b / (b + i)}')
  fi
  last_busy=$busy last_idle=$idle
  printf '\n== %s (at %d min %02d s; cores busy since the last step: %s)\n' "$*" \
    $((SECONDS / 60)) $((SECONDS % 60)) "$cores"
}

# The side lane: checks that share no cargo target directory with the main lane below (the
# AVX2 build, the profile-guided build, the firmware), run beside it at a lower
# priority. The main lane's builds and tests keep both cores when they can use them; the side
# lane takes what they leave (linking, single-threaded tests, Node and the browser). Its log is
# printed where the main lane waits for it, at the end.
side_lane() {
  renice -n 10 -p "$BASHPID" >/dev/null || true

  step "side lane: the wide trees built for AVX2 (eight lanes in one instruction), against brute force"
  # The default x86-64 build runs eight lanes as two SSE halves; an AVX2 build takes the `wide`
  # crate's AVX path for them. Its answers must be the same, bit for bit: the wide-tree suites
  # and the query layer's again (tests/tests/lanes.rs, a binary of only those), built for
  # x86-64-v3, where the CPU has AVX2. The blob suites
  # run there too, and the core's blob unit tests without `std`: a build for SSSE3 without
  # `std` checksums blobs by byte shuffles (`crc_lanes`), not by tables. Naming the host as the
  # target keeps the flags off build scripts and proc macros; a target directory of its own
  # keeps this build from waiting on the main lane's.
  if grep -qw avx2 /proc/cpuinfo 2>/dev/null && [ "$(uname -m)" = x86_64 ]; then
    local host
    host=$(rustc -vV | sed -n 's/^host: //p')
    CARGO_TARGET_DIR=target/avx2 RUSTFLAGS="-C target-cpu=x86-64-v3" \
      cargo test --locked --target "$host" -p meshq-tests --test lanes
    CARGO_TARGET_DIR=target/avx2 RUSTFLAGS="-C target-cpu=x86-64-v3" \
      cargo test --locked --target "$host" -p meshq --features blob,alloc --lib blob::
  else
    echo "no AVX2 here: skipped"
  fi

  step "side lane: profile-guided build (scripts/pgo.sh), compared with the test build at the end"
  ./scripts/pgo.sh

  step "side lane: firmware, Cortex-M4F in QEMU, parity with the golden files (queries, remeshing), panic-free proofs, memory"
  # Baked by the profile-guided build: any build bakes the same bytes, which the golden digests
  # check.
  MESHQ_BIN=target/pgo/release/meshq ./scripts/firmware.sh

  step "side lane: done"
}
side_log=target/ci-side-lane.log
mkdir -p target
# Its own process group (job control on for the launch), so that an early failure of the main
# lane stops it whole.
set -m
side_lane >"$side_log" 2>&1 </dev/null &
side_pid=$!
set +m
trap 'kill -- -"$side_pid" 2>/dev/null || true' EXIT
echo "side lane started (log: $side_log)"

step "format"
cargo fmt --all -- --check

step "clippy (all targets, warnings are errors)"
cargo clippy --locked --workspace --all-targets -- -D warnings

step "docs (warnings are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --locked --workspace --no-deps
# The core alone, without the features the workspace turns on: its links must hold there too.
RUSTDOCFLAGS="-D warnings" cargo doc --locked -p meshq --no-deps --no-default-features

step "no_std core without features for Cortex-M4F and WebAssembly"
# With blobs and the workloads, both targets are built further down: the firmware and the
# WebAssembly package.
for target in thumbv7em-none-eabihf wasm32-unknown-unknown; do
  cargo build --locked -p meshq --target "$target"
done
cargo clippy --locked -p meshq --features blob --target thumbv7em-none-eabihf -- -D warnings

step "tests (optimised test profile)"
# meshq-bench holds only benchmarks and an example (clippy above type-checks them); leaving it
# out spares compiling its peers (obvhs, parry3d, criterion) optimised. meshq-python is tested
# from Python (its own step below), meshq-wasm on wasm32 (its tests are wasm-bindgen tests,
# none of which runs on the host).
cargo test --locked --workspace --exclude meshq-bench --exclude meshq-python --exclude meshq-wasm

step "Python package: the extension module in target/py-venv, its tests (brute force, trimesh, Embree, a two-worker Dask cluster)"
MESHQ_PY_PROFILE=python-test ./scripts/python.sh

step "WebAssembly: parity with the golden file and blob bytes, in Node"
cargo clippy --locked -p meshq-wasm --target wasm32-unknown-unknown --all-targets -- -D warnings
CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner \
  cargo test --locked -p meshq-wasm --target wasm32-unknown-unknown --tests

step "the npm package (wasm-pack for browsers and Node, one package) and the demo"
MESHQ_BIN=target/debug/meshq ./scripts/build-web.sh

step "demo end to end in headless Chromium: started in the background, beside the Node steps below"
# One browser and Node's single-threaded tests share the two cores; each e2e step has its own
# budget (web/tests/e2e.mjs), sized for that.
e2e_log=target/e2e-run.log
MESHQ_BIN=target/debug/meshq node web/tests/e2e.mjs >"$e2e_log" 2>&1 </dev/null &
e2e_pid=$!

step "npm pack: the tarball installed in a fresh directory, used from Node and through the demo's import map"
node web/tests/pack.mjs

step "TypeScript: the typings against the run-time API, tsc --noEmit (bundler, Node, beside three-mesh-bvh)"
node web/tests/types.mjs

step "worker pool (meshq-wasm/pool) in Node: 1-3 workers, shared and copied memory, equal to one thread"
node web/tests/pool.mjs

step "three.js drop-in against three's brute-force Raycaster, in Node"
# 4,000 rays against three's brute force here (run alone, it takes the DESIGN.md workload's
# 10,000): the reference is most of the step's time.
MESHQ_DROPIN_RAYS=4000 node web/tests/three-dropin.mjs

step "the Node package under misuse: bad arguments refused by name, nothing left borrowed"
node web/tests/misuse.mjs

step "the package's geometry functions against three.js's own math, in Node"
node web/tests/geometry.mjs

step "demo end to end in headless Chromium: its result"
e2e_status=0
wait "$e2e_pid" || e2e_status=$?
cat "$e2e_log"
if [ "$e2e_status" -ne 0 ]; then
  echo "demo end to end: failed (exit $e2e_status)" >&2
  exit "$e2e_status"
fi

step "Node benchmark runs (small counts; the real run is node bench/node/bench.mjs)"
MESHQ_BENCH_RAYS=20000 MESHQ_BENCH_SINGLE=5000 MESHQ_BENCH_POINTS=2000 node bench/node/bench.mjs
node bench/node/first.mjs 1
MESHQ_BENCH_RAYS=20000 MESHQ_BENCH_POINTS=4000 node bench/node/pool-balance.mjs

step "browser benchmark runs in headless Chromium (small counts; the real run is node bench/browser/bench.mjs)"
MESHQ_BENCH_RAYS=20000 MESHQ_BENCH_POINTS=2000 MESHQ_BENCH_ROUNDS=2 node bench/browser/bench.mjs
node bench/browser/first.mjs 1

step "fuzz blob parsing and the mesh loaders briefly (beside the side lane's last steps)"
if rustup toolchain list | grep -q '^nightly' && cargo fuzz --version >/dev/null 2>&1; then
  ./scripts/fuzz.sh "${MESHQ_FUZZ_SECONDS:-30}"
else
  echo "skipped: no nightly toolchain"
fi

step "the side lane: its result"
side_status=0
wait "$side_pid" || side_status=$?
trap - EXIT
cat "$side_log"
if [ "$side_status" -ne 0 ]; then
  echo "side lane: failed (exit $side_status)" >&2
  exit "$side_status"
fi

step "profile-guided build: the same answers, bit for bit, as the test build"
pgo_check=target/pgo-train/check
mkdir -p "$pgo_check"
target/debug/meshq workload assets/fandisk.obj --count 50000 -o "$pgo_check/random.rays" >/dev/null
target/debug/meshq workload assets/fandisk.obj --kind camera-rays --image 256x256 -o "$pgo_check/camera.rays" >/dev/null
target/debug/meshq workload assets/fandisk.obj --kind points --count 20000 -o "$pgo_check/points.bin" >/dev/null
for build in debug pgo/release; do
  for rays in random camera; do
    target/$build/meshq raycast assets/fandisk.obj --rays "$pgo_check/$rays.rays" \
      --out "$pgo_check/${build%%/*}-$rays.bin" --per-ray >/dev/null
  done
  target/$build/meshq closest assets/fandisk.obj --points "$pgo_check/points.bin" \
    --out "$pgo_check/${build%%/*}-closest.bin" >/dev/null
done
for what in random camera closest; do
  cmp "$pgo_check/debug-$what.bin" "$pgo_check/pgo-$what.bin"
done
echo "profile-guided build: every record equal"

step "all checks passed"
