#!/usr/bin/env bash
# The firmware check: bake the bunny and spot blobs with the meshq command, build the Cortex-M4F
# firmware around each, run both in QEMU (each exits 0 only when its digest equals the golden
# file's), prove the query path panic-free, and print the memory each part needs.
# MESHQ_CLI_PROFILE picks the cargo profile the meshq command is built with (default release).
set -euo pipefail
cd "$(dirname "$0")/.."

profile=${MESHQ_CLI_PROFILE:-release}
case "$profile" in dev | test) profile_dir=debug ;; *) profile_dir=$profile ;; esac
cargo build --locked --quiet -p meshq-cli --profile "$profile"
meshq=$PWD/target/$profile_dir/meshq

blobs=$PWD/target/firmware-blobs
mkdir -p "$blobs"
for stem in spot stanford-bunny; do
  "$meshq" bake "assets/$stem.obj" -o "$blobs/$stem.meshq"
done

tools=$(rustc --print sysroot)/lib/rustlib/x86_64-unknown-linux-gnu/bin
qemu=(qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic
  -semihosting-config enable=on,target=native -kernel)
elf=target/thumbv7em-none-eabihf/release/meshq-firmware

cd firmware
export MESHQ_BLOB_DIR=$blobs
cargo fmt --check
cargo clippy --locked --release --features spot -- -D warnings
cargo clippy --locked --release --no-default-features --features panic-free,spot -- -D warnings

for mesh in spot bunny; do
  echo; echo "== firmware with the $mesh blob, in QEMU"
  cargo build --locked --release --features "$mesh"
  status=0
  timeout 300 "${qemu[@]}" "$elf" </dev/null | tee "../target/firmware-$mesh.log" || status=$?
  if [ "$status" -ne 0 ]; then
    echo "firmware ($mesh) failed with exit status $status" >&2
    exit 1
  fi
done

echo; echo "== panic-free proof: the panic handler calls an undefined symbol"
cargo build --locked --release --no-default-features --features panic-free,spot
timeout 300 "${qemu[@]}" "$elf" </dev/null
echo "linked (no panic reachable from validation and queries) and exited 0 in QEMU"

# Memory of the panic-free build (no formatting code at all): flash without the blob and the
# golden file text, static RAM, heap.
read -r text rodata vectors data bss < <("$tools/llvm-size" -A "$elf" | awk '
  $1==".text"{t=$2} $1==".rodata"{r=$2} $1==".vector_table"{v=$2} $1==".data"{d=$2} $1==".bss"{b=$2}
  END{print t, r, v, d, b}')
blob_bytes=$(stat -c %s "$blobs/spot.meshq")
golden_bytes=$(stat -c %s ../tests/golden/parity.txt)
code=$((vectors + text + rodata - blob_bytes - golden_bytes))
if "$tools/llvm-nm" "$elf" | grep -qE '__rust_alloc|__rg_alloc|__rdl_alloc|__rust_no_alloc_shim'; then
  echo "an allocator is linked into the firmware" >&2
  exit 1
fi
stack=$(grep -oE '(validation|queries) [0-9]+' ../target/firmware-bunny.log | awk '$2>m{m=$2} END{print m+0}')
echo
echo "== memory (panic-free build; stack from the bunny run)"
echo "flash, code without blob and golden text: $code bytes (.text $text, vector table $vectors, constants $((rodata - blob_bytes - golden_bytes)))"
echo "flash, spot blob: $blob_bytes bytes; bunny blob: $(stat -c %s "$blobs/stanford-bunny.meshq") bytes"
echo "static RAM (.data + .bss): $((data + bss)) bytes"
echo "stack high-water mark, validation and queries: $stack bytes"
echo "heap: 0 bytes (no allocator linked)"
if [ "$code" -gt 24576 ] || [ "$stack" -gt 2048 ]; then
  echo "over budget: code must be <= 24 KiB and stack <= 2 KiB" >&2
  exit 1
fi
