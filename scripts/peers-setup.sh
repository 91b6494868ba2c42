#!/usr/bin/env bash
# Benchmark-only peers, never part of the product: a Python virtual environment in
# target/peers-venv with gpytoolbox (remeshing peer), embreex (Embree 4, the ray-casting
# reference), libigl (winding numbers and signed distance) and numpy. Each is skipped when already there.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/peers-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -c 'import gpytoolbox' 2>/dev/null || "$venv/bin/pip" install --quiet 'gpytoolbox==0.3.8'
"$venv/bin/python" -c 'import embreex' 2>/dev/null || "$venv/bin/pip" install --quiet 'embreex==4.4.0.post1'
"$venv/bin/python" -c 'import igl' 2>/dev/null || "$venv/bin/pip" install --quiet 'libigl==2.6.3'
echo "peers ready: $venv/bin/python bench/peers/remesh.py, $venv/bin/python bench/peers/embree.py"
