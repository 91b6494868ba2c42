#!/usr/bin/env bash
# Installs what the project needs and is missing, idempotently: each step is skipped when
# its tool is already present. Safe to run on a fresh machine, in CI (CI=true, no stdin) and
# again and again on a developer machine.
set -euo pipefail
cd "$(dirname "$0")/.."

log() { printf '[setup] %s\n' "$*"; }

if ! command -v cargo >/dev/null || ! command -v rustup >/dev/null; then
  echo "[setup] rustup and cargo are required (https://rustup.rs); install them first" >&2
  exit 1
fi

installed_targets=$(rustup target list --installed)
for target in wasm32-unknown-unknown thumbv7em-none-eabihf; do
  if grep -qx "$target" <<<"$installed_targets"; then
    log "rust target $target: present"
  else
    log "rust target $target: installing"
    rustup target add "$target"
  fi
done

installed_components=$(rustup component list --installed)
for component in rustfmt clippy; do
  if grep -q "^$component" <<<"$installed_components"; then
    log "rust component $component: present"
  else
    log "rust component $component: installing"
    rustup component add "$component"
  fi
done

# cargo-fuzz, only where a nightly toolchain exists (fuzzing needs it; nothing else does).
CARGO_FUZZ_VERSION=0.13.2
if rustup toolchain list | grep -q '^nightly'; then
  if cargo fuzz --version 2>/dev/null | grep -q " $CARGO_FUZZ_VERSION\$"; then
    log "cargo-fuzz $CARGO_FUZZ_VERSION: present"
  else
    log "cargo-fuzz $CARGO_FUZZ_VERSION: installing (about 2 minutes)"
    cargo install cargo-fuzz --version "$CARGO_FUZZ_VERSION" --locked
  fi
else
  log "no nightly toolchain: fuzzing will be skipped"
fi
