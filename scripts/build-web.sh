#!/usr/bin/env bash
# Assembles the demo in web/: the WebAssembly package (wasm/pkg-web → web/pkg) and the bunny
# baked by the meshq command at build time (web/assets/bunny.meshq). Both are build outputs,
# never committed. MESHQ_BIN: the meshq binary to bake with (default: build it in release).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/wasm.sh
rm -rf web/pkg && cp -r wasm/pkg-web web/pkg
meshq=${MESHQ_BIN:-}
if [ -z "$meshq" ]; then
  cargo build --locked --quiet --release -p meshq-cli
  meshq=target/release/meshq
fi
mkdir -p web/assets
"$meshq" bake assets/stanford-bunny.obj -o web/assets/bunny.meshq
