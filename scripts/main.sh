#!/usr/bin/env bash
# The main job: install what is missing, then load the bundled Stanford bunny, build its BVH
# with each preset and cast the DESIGN.md workloads, printing build times and rays/s.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
cargo run --release --locked -p meshq-bench --example bunny
