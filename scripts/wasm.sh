#!/usr/bin/env bash
# Builds the meshq-wasm package with wasm-pack for browsers (wasm/pkg-web, ES module) and Node
# (wasm/pkg-nodejs, CommonJS), optimised by wasm-opt from npm binaryen 132, adds the three.js
# drop-in to both, and reports the .wasm size. Needs scripts/setup.sh to have run.
set -euo pipefail
cd "$(dirname "$0")/.."

# wasm-opt from npm binaryen first on PATH (Debian's older one breaks wasm-bindgen output).
export PATH="$PWD/web/node_modules/.bin:$HOME/.cargo/bin:$PATH"

for target in web nodejs; do
  out=pkg-$target
  # --mode no-install: use the pinned wasm-bindgen on PATH, never a silent download.
  wasm-pack --quiet build wasm --release --target "$target" --out-dir "$out" \
    --weak-refs --mode no-install
  # wasm-pack's package.json lists only its own files; add the three.js drop-in.
  case $target in web) dropin=three.js ;; nodejs) dropin=three.mjs ;; esac
  cp wasm/js/three.js "wasm/$out/$dropin"
  cp wasm/js/three.d.ts "wasm/$out/${dropin%.*}.d.ts"
  node -e '
    const fs = require("fs");
    const [file, dropin, types] = process.argv.slice(1);
    const pkg = JSON.parse(fs.readFileSync(file, "utf8"));
    pkg.name = "meshq-wasm";
    pkg.files = [...new Set([...(pkg.files || []), dropin, types])];
    pkg.peerDependencies = { three: ">=0.150.0" };
    pkg.peerDependenciesMeta = { three: { optional: true } };
    fs.writeFileSync(file, JSON.stringify(pkg, null, 2) + "\n");
  ' "wasm/$out/package.json" "$dropin" "${dropin%.*}.d.ts"
done

# The drop-in imports 'three' as a peer dependency; in this repository Node resolves it from
# the demo's node_modules.
ln -sfn ../web/node_modules wasm/node_modules

wasm=wasm/pkg-web/meshq_wasm_bg.wasm
bytes=$(stat -c %s "$wasm")
gzipped=$(gzip -9c "$wasm" | wc -c)
echo "meshq-wasm: $wasm is $bytes bytes ($gzipped gzipped)"
