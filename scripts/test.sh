#!/usr/bin/env bash
# Every check, as CI runs it: install what is missing, then formatting, lints, docs, the
# bare-metal and WebAssembly builds of the core, all tests, and a compile of the benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh

step() { printf '\n== %s\n' "$*"; }

step "format"
cargo fmt --all -- --check

step "clippy (all targets, warnings are errors)"
cargo clippy --locked --workspace --all-targets -- -D warnings

step "docs (warnings are errors)"
RUSTDOCFLAGS="-D warnings" cargo doc --locked --workspace --no-deps

step "no_std core for Cortex-M4F and WebAssembly"
cargo build --locked -p meshq --target thumbv7em-none-eabihf
cargo build --locked -p meshq --target wasm32-unknown-unknown
cargo clippy --locked -p meshq --target thumbv7em-none-eabihf -- -D warnings

step "tests (optimised test profile)"
cargo test --locked --workspace

step "benchmarks compile"
cargo bench --locked --workspace --no-run
