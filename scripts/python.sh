#!/usr/bin/env bash
# The Python package: builds the extension module into the project's virtual environment
# (target/py-venv, made by scripts/setup.sh) and runs its tests, a two-worker local Dask
# cluster among them. MESHQ_PY_PROFILE picks the cargo profile (default: release; CI passes
# `test`, optimised without link-time optimisation, which builds faster).
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/py-venv
if [ ! -x "$venv/bin/maturin" ]; then
  echo "[python] $venv is missing or incomplete: run scripts/setup.sh first" >&2
  exit 1
fi
profile=${MESHQ_PY_PROFILE:-release}
(cd python && VIRTUAL_ENV="$PWD/../$venv" "../$venv/bin/maturin" develop --locked --profile "$profile" --quiet)
cd python
# -p no:cacheprovider: nothing written into the source tree.
"../$venv/bin/python" -m pytest -q -p no:cacheprovider "$@"
