#!/usr/bin/env bash
# Builds the `illume` Python module with maturin into a throw-away virtualenv and runs its
# pytest tests. Installs maturin, pytest and numpy there if missing (CI). The tests compare
# with the `render` binary: $RENDER, default $CARGO_TARGET_DIR/debug/render (cargo build -p render).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="$(mktemp -d)"
trap 'rm -rf "$venv"' EXIT
python3 -m venv --system-site-packages "$venv"
# shellcheck disable=SC1091
. "$venv/bin/activate"
if ! command -v maturin >/dev/null || ! python3 -c "import numpy, pytest" 2>/dev/null; then
  python3 -m pip install -q maturin pytest numpy
fi
(cd "$here" && maturin build -q -o "$venv/dist" 2>&1 | grep -v "^📦\|^🔗\|^🐍" || true)
python3 -m pip install -q --force-reinstall --no-deps "$venv"/dist/*.whl
root="$(cd "$here/../.." && pwd)"
export RENDER="${RENDER:-${CARGO_TARGET_DIR:-$root/target}/debug/render}"
python3 -m pytest -q "$here/tests"
