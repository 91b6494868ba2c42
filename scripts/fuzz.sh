#!/usr/bin/env bash
# Fuzzes blob parsing and queries: `scripts/fuzz.sh [SECONDS] [extra libFuzzer flags...]`.
# Seeds are small valid blobs written by fuzz/src/bin/make_seeds.rs; needs a nightly toolchain
# and cargo-fuzz (scripts/setup.sh installs it when nightly exists). No sanitizer: the code is
# all safe Rust (unsafe is forbidden), so AddressSanitizer has nothing to add and halves the
# executions per second.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds=${1:-60}
shift || true
corpus=../target/fuzz-corpus/blob_parse
mkdir -p "$corpus"
cargo +nightly run --quiet --release --bin make_seeds -- "$corpus"
cargo +nightly fuzz run --sanitizer none blob_parse "$corpus" -- -max_total_time="$seconds" -max_len=8192 "$@"
