#!/usr/bin/env bash
# The test command: the Rust workspace's tests, then the Python package built from this tree
# (`pip install .`, maturin as the build backend) and its pytest suite.
#
# The Python part installs into a virtual environment of its own, never into the `python3` first on
# PATH: the active one when `VIRTUAL_ENV` is set, else `.venv` in the repository (made on first use;
# `DDIRAC_TEST_VENV=DIR` chooses another directory).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== cargo test --workspace --release (the first time it compiles the library, the command line and"
echo "   the tests: about 10 minutes on an idle 2-core machine; then only what changed)"
cargo test --workspace --release

if [ -n "${VIRTUAL_ENV:-}" ]; then
    venv="$VIRTUAL_ENV"
else
    venv="${DDIRAC_TEST_VENV:-.venv}"
    if [ ! -x "$venv/bin/python" ]; then
        echo "== making the virtual environment $venv for the Python tests (python3 -m venv)"
        if ! python3 -m venv "$venv"; then
            echo "error: python3 -m venv $venv failed; install the venv module (on Debian and Ubuntu: python3-venv)," >&2
            echo "       or activate a virtual environment of your own and run scripts/test.sh again" >&2
            exit 1
        fi
    fi
fi
py="$(cd "$venv" && pwd)/bin/python"

# pandas and Dask (`distributed`) for the ensemble tests: a DataFrame of members, a LocalCluster;
# Matplotlib and MkDocs for the guide's code blocks and its build (python/tests/test_docs.py); mypy for
# the public API's annotations (test_issue_35_type_annotations.py).
echo "== the Python tests' dependencies (pytest, NumPy, SymPy, pandas, Dask, Matplotlib, MkDocs, mypy) into $venv"
"$py" -m pip install --quiet --upgrade pip
"$py" -m pip install --quiet pytest numpy sympy pandas "dask[distributed]" matplotlib "mkdocs>=1.6,<2" mypy
echo "== building and installing the Python package into $venv "
echo "   (pip install .: maturin compiles the extension module, about 5 minutes on an idle 2-core machine)"
"$py" -m pip install --quiet .
# From another directory, so that the installed package is imported, not `python/ddirac`.
echo "== pytest (python/tests)"
venv_dir="$(cd "$venv" && pwd)"
cd python/tests && DDIRAC_TEST_VENV_USED="$venv_dir" "$py" -m pytest -q

echo "== the user guide: mkdocs build --strict (into site/)"
cd ../.. && "$py" -m mkdocs build --strict --quiet
