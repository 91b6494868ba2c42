#!/usr/bin/env bash
# The main job: install what is missing, build the meshq command, bake the bundled Stanford
# bunny into a blob, inspect it, and raycast it (and query closest points) with generated
# workloads, printing the figures. Outputs land in target/main-job/.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh

out=target/main-job
mkdir -p "$out"
cargo build --release --locked -p meshq-cli
meshq=target/release/meshq
bunny=assets/stanford-bunny.obj

echo; echo "== bake"
"$meshq" bake "$bunny" -o "$out/bunny.meshq"
echo; echo "== inspect"
"$meshq" inspect "$out/bunny.meshq"
echo; echo "== workloads (DESIGN.md: 1M random rays, 1024x1024 camera rays, 100k points)"
"$meshq" workload "$bunny" --kind random-rays --count 1000000 -o "$out/random-rays.bin"
"$meshq" workload "$bunny" --kind camera-rays -o "$out/camera-rays.bin"
"$meshq" workload "$bunny" --kind points --count 100000 -o "$out/points.bin"
echo; echo "== raycast the blob"
"$meshq" raycast "$out/bunny.meshq" --rays "$out/random-rays.bin" --out "$out/random-hits.bin"
"$meshq" raycast "$out/bunny.meshq" --rays "$out/camera-rays.bin" --out "$out/camera-hits.bin"
"$meshq" raycast "$out/bunny.meshq" --rays "$out/random-rays.bin" --out "$out/random-any.bin" --any
echo; echo "== closest points"
"$meshq" closest "$out/bunny.meshq" --points "$out/points.bin" --out "$out/closest.bin"
echo
echo "outputs in $out/ (hits: float32 t + uint32 triangle per ray)"
echo; echo "== browser demo (WebAssembly package + the bunny blob baked above)"
MESHQ_BIN=$meshq ./scripts/build-web.sh
echo "open the URL below; Ctrl-C stops the server"
exec node web/serve.mjs
