#!/usr/bin/env bash
# Fuzzes blob parsing and queries, then the command's mesh loaders:
# `scripts/fuzz.sh [SECONDS] [extra libFuzzer flags...]` runs each target for SECONDS.
# Blob seeds are small valid blobs written by fuzz/make-seeds and the findings kept in
# fuzz/seeds/blob_parse; mesh seeds are the small OBJ, PLY and STL files in fuzz/seeds/mesh_load.
# Needs a nightly toolchain and cargo-fuzz (scripts/setup.sh installs it when nightly exists).
# No sanitizer: the code is all safe Rust (unsafe is forbidden), so AddressSanitizer has nothing
# to add and halves the executions per second. The mesh loaders run under a 256 MB allocation
# cap, so an allocation sized by a declared count (not by the input's bytes) is reported as a
# finding.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds=${1:-60}
shift || true
corpus=../target/fuzz-corpus/blob_parse
mkdir -p "$corpus"
# Unoptimised and against the core alone: the seeds are a few tiny meshes, and an optimised
# build (which the fuzz targets cannot share: they are built with coverage) took half a minute
# longer.
cargo +nightly run --quiet -p meshq-fuzz-seeds -- "$corpus"
cp seeds/blob_parse/* "$corpus"/
cargo +nightly fuzz run --sanitizer none blob_parse "$corpus" -- -max_total_time="$seconds" -max_len=8192 "$@"
meshes=../target/fuzz-corpus/mesh_load
mkdir -p "$meshes"
cp seeds/mesh_load/* "$meshes"/
cargo +nightly fuzz run --sanitizer none mesh_load "$meshes" -- -max_total_time="$seconds" \
  -max_len=4096 -malloc_limit_mb=256 -rss_limit_mb=1024 "$@"
