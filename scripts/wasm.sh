#!/usr/bin/env bash
# Builds the npm package meshq-wasm in wasm/pkg: wasm-pack builds the crate for browsers
# (wasm/pkg-web, ES module) and Node (wasm/pkg-nodejs, CommonJS), optimised by wasm-opt from
# npm binaryen 132; wasm/js/assemble.mjs puts both, the three.js drop-in, the typings and the
# package README into one package whose `exports` pick the right build. `npm pack wasm/pkg`
# makes the tarball. Reports the .wasm size. Needs scripts/setup.sh to have run.
set -euo pipefail
cd "$(dirname "$0")/.."

# wasm-opt from npm binaryen first on PATH (Debian's older one breaks wasm-bindgen output).
export PATH="$PWD/web/node_modules/.bin:$HOME/.cargo/bin:$PATH"

for target in web nodejs; do
  # --mode no-install: use the pinned wasm-bindgen on PATH, never a silent download.
  wasm-pack --quiet build wasm --release --target "$target" --out-dir "pkg-$target" \
    --weak-refs --mode no-install
done

version=$(cargo metadata --locked --no-deps --format-version 1 |
  node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>console.log(JSON.parse(s).packages.find(p=>p.name==="meshq-wasm").version))')
node wasm/js/assemble.mjs "$version"

# The drop-in imports 'three' as a peer dependency; in this repository Node resolves it from
# the demo's node_modules.
ln -sfn ../web/node_modules wasm/node_modules

wasm=wasm/pkg/web/meshq_wasm_bg.wasm
bytes=$(stat -c %s "$wasm")
gzipped=$(gzip -9c "$wasm" | wc -c)
echo "meshq-wasm $version: $wasm is $bytes bytes ($gzipped gzipped)"
