#!/usr/bin/env bash
# Builds the `meshq` command with profile-guided optimisation (PGO), for the last few per cent
# of ray and closest-point speed on the machine that will run it.
#
# An instrumented build answers the bundled bunny's workloads (its own ray and point files,
# made with seed 7, not the benchmarks' seed 1): closest and any hit, one ray per call and
# batched, random rays and a camera, and closest points. rustup's llvm-profdata (the
# llvm-tools component, which scripts/setup.sh installs) merges what it recorded, and a second
# build lays out and inlines the code by those counts. The code is the same: every answer is
# the same bits as any other build's. Paths the training does not run (other structures,
# remeshing, baking) are built as rarely taken, so use this build for ray and point queries.
#
# RUSTFLAGS pass through to both builds (RUSTFLAGS="-C target-cpu=native" ./scripts/pgo.sh);
# the command lands in $MESHQ_PGO_DIR/release/meshq (default target/pgo), the training build
# and its profiles in $MESHQ_PGO_DIR-train.
set -euo pipefail
cd "$(dirname "$0")/.."

out=${MESHQ_PGO_DIR:-target/pgo}
train=$out-train
flags=${RUSTFLAGS:-}
host=$(rustc -vV | sed -n 's/^host: //p')
profdata=$(rustc --print sysroot)/lib/rustlib/$host/bin/llvm-profdata
if [ ! -x "$profdata" ]; then
  echo "[pgo] llvm-profdata is missing: run scripts/setup.sh (rustup component add llvm-tools)" >&2
  exit 1
fi

profiles=$PWD/$train/profiles
work=$train/work
rm -rf "$profiles" "$work"
mkdir -p "$profiles" "$work"

echo "[pgo] instrumented build ($train)"
RUSTFLAGS="$flags -Cprofile-generate=$profiles" CARGO_TARGET_DIR=$train \
  cargo build --quiet --locked --release -p meshq-cli
meshq=$train/release/meshq
mesh=assets/stanford-bunny.obj

echo "[pgo] training on $mesh"
"$meshq" workload "$mesh" --seed 7 --count 300000 -o "$work/random.rays" >/dev/null
"$meshq" workload "$mesh" --seed 7 --kind camera-rays --image 640x640 -o "$work/camera.rays" >/dev/null
"$meshq" workload "$mesh" --seed 7 --kind points --count 100000 -o "$work/points.bin" >/dev/null
for rays in random camera; do
  for mode in "--per-ray" "--per-ray --any" "" "--any"; do
    # shellcheck disable=SC2086 # the mode is zero, one or two flags
    "$meshq" raycast "$mesh" --rays "$work/$rays.rays" --out "$work/hits.bin" $mode >/dev/null
  done
done
"$meshq" closest "$mesh" --points "$work/points.bin" --out "$work/closest.bin" >/dev/null

"$profdata" merge -o "$train/meshq.profdata" "$profiles"

echo "[pgo] optimised build ($out)"
RUSTFLAGS="$flags -Cprofile-use=$PWD/$train/meshq.profdata" CARGO_TARGET_DIR=$out \
  cargo build --quiet --locked --release -p meshq-cli
echo "[pgo] built $out/release/meshq"
