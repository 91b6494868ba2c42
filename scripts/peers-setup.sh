#!/usr/bin/env bash
# Benchmark-only peers, never part of the product: a Python virtual environment in
# target/peers-venv with gpytoolbox (remeshing peer) and numpy. Skipped when already there.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/peers-venv
if ! "$venv/bin/python" -c 'import gpytoolbox' 2>/dev/null; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet 'gpytoolbox==0.3.8'
fi
echo "peers ready: $venv/bin/python bench/peers/remesh.py"
