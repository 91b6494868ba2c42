#!/usr/bin/env bash
# Assembles the demo in web/: the npm package meshq-wasm, packed by `npm pack` and installed
# into web/node_modules/meshq-wasm the way npm installs it (the demo's import map reads it
# from there, as any page using the package does), and the bunny baked by the meshq command
# at build time (web/assets/bunny.meshq). Both are build outputs, never committed.
# MESHQ_BIN: the meshq binary to bake with (default: build it in release).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/wasm.sh
mkdir -p target/npm
rm -f target/npm/meshq-wasm-*.tgz
tarball=$(cd wasm/pkg && npm pack --silent --pack-destination ../../target/npm | tail -1)
# A package without dependencies installs as its tarball unpacked; doing that directly keeps
# npm (and the registry) out of the demo build.
rm -rf web/node_modules/meshq-wasm && mkdir -p web/node_modules/meshq-wasm
tar -xzf "target/npm/$tarball" -C web/node_modules/meshq-wasm --strip-components=1
echo "meshq-wasm: target/npm/$tarball, unpacked into web/node_modules/meshq-wasm"
meshq=${MESHQ_BIN:-}
if [ -z "$meshq" ]; then
  cargo build --locked --quiet --release -p meshq-cli
  meshq=target/release/meshq
fi
mkdir -p web/assets
"$meshq" bake assets/stanford-bunny.obj -o web/assets/bunny.meshq
