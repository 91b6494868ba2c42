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

# System packages, in the background while cargo compiles: QEMU runs the firmware, Chromium
# and its driver run the browser tests. Skipped when the commands are already there.
apt_packages=()
command -v qemu-system-arm >/dev/null || apt_packages+=(qemu-system-arm)
command -v chromium >/dev/null || apt_packages+=(chromium)
command -v chromedriver >/dev/null || apt_packages+=(chromium-driver)
apt_pid=
apt_log=target/setup-apt.log
if [ ${#apt_packages[@]} -gt 0 ]; then
  if [ "$(id -u)" -eq 0 ]; then sudo=(); elif command -v sudo >/dev/null; then sudo=(sudo -n); else
    echo "[setup] need root or sudo to install: ${apt_packages[*]}" >&2
    exit 1
  fi
  log "apt: installing ${apt_packages[*]} in the background (log: $apt_log)"
  mkdir -p target
  (
    export DEBIAN_FRONTEND=noninteractive
    "${sudo[@]}" apt-get update -qq &&
      "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${apt_packages[@]}"
  ) >"$apt_log" 2>&1 </dev/null &
  apt_pid=$!
else
  log "apt packages (qemu-system-arm, chromium, chromium-driver): present"
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
for component in rustfmt clippy llvm-tools; do
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

# WebAssembly tools at pinned versions. wasm-bindgen must equal the version in Cargo.lock
# (wasm-pack otherwise installs its own); its lockfile pins a crate the registry no longer
# serves, so it installs without --locked.
WASM_BINDGEN_VERSION=0.2.130
WASM_PACK_VERSION=0.15.1
if wasm-bindgen --version 2>/dev/null | grep -q " $WASM_BINDGEN_VERSION\$"; then
  log "wasm-bindgen-cli $WASM_BINDGEN_VERSION: present"
else
  log "wasm-bindgen-cli $WASM_BINDGEN_VERSION: installing (a few minutes)"
  cargo install wasm-bindgen-cli --version "$WASM_BINDGEN_VERSION"
fi
if wasm-pack --version 2>/dev/null | grep -q " $WASM_PACK_VERSION\$"; then
  log "wasm-pack $WASM_PACK_VERSION: present"
else
  log "wasm-pack $WASM_PACK_VERSION: installing (a few minutes)"
  cargo install wasm-pack --version "$WASM_PACK_VERSION" --locked
fi

# npm packages from the committed lockfiles: the demo (three.js; playwright-core and npm
# binaryen's wasm-opt for the build and tests) and the Node benchmark (three-mesh-bvh).
for dir in web bench/node; do
  if [ -f "$dir/node_modules/.package-lock.json" ] &&
    [ "$dir/node_modules/.package-lock.json" -nt "$dir/package-lock.json" ]; then
    log "npm packages in $dir: present"
  else
    log "npm packages in $dir: installing"
    (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error)
  fi
done

# Python: a virtual environment in target/py-venv (ignored by git) with the packages pinned in
# python/requirements.lock (maturin builds the extension module; numpy, trimesh, embreex and
# dask are what the package and its tests use). Reinstalled only when the lock file changes.
py_venv=target/py-venv
py_stamp=$py_venv/.requirements.lock
if [ -x "$py_venv/bin/python" ] && cmp -s python/requirements.lock "$py_stamp"; then
  log "python packages in $py_venv: present"
else
  command -v python3 >/dev/null || {
    echo "[setup] python3 (3.11 or later) is required for the Python package" >&2
    exit 1
  }
  log "python packages: installing into $py_venv (python/requirements.lock)"
  [ -x "$py_venv/bin/python" ] || python3 -m venv "$py_venv"
  "$py_venv/bin/python" -m pip install --quiet --disable-pip-version-check --no-input \
    -r python/requirements.lock
  cp python/requirements.lock "$py_stamp"
fi

if [ -n "$apt_pid" ]; then
  log "apt: waiting for the background install"
  if ! wait "$apt_pid"; then
    cat "$apt_log" >&2
    echo "[setup] apt-get failed" >&2
    exit 1
  fi
  log "apt: done"
fi
