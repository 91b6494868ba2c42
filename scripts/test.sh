#!/usr/bin/env bash
# Every check, as CI runs it: install what is missing, then formatting, lints, docs, the
# bare-metal and WebAssembly builds of the core, all tests, the firmware in QEMU, and a compile
# of the benchmarks.
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

step "no_std core (with blobs) and workloads for Cortex-M4F and WebAssembly"
for target in thumbv7em-none-eabihf wasm32-unknown-unknown; do
  cargo build --locked -p meshq --target "$target"
  cargo build --locked -p meshq --features blob --target "$target"
  cargo build --locked -p meshq-workload --target "$target"
done
cargo clippy --locked -p meshq --features blob --target thumbv7em-none-eabihf -- -D warnings

step "tests (optimised test profile)"
cargo test --locked --workspace

step "firmware: Cortex-M4F in QEMU, parity with the golden file, panic-free proof, memory"
MESHQ_CLI_PROFILE=test ./scripts/firmware.sh

step "benchmarks compile"
cargo bench --locked --workspace --no-run

step "fuzz blob parsing briefly"
if rustup toolchain list | grep -q '^nightly' && cargo fuzz --version >/dev/null 2>&1; then
  ./scripts/fuzz.sh "${MESHQ_FUZZ_SECONDS:-45}"
else
  echo "skipped: no nightly toolchain"
fi
