#!/usr/bin/env bash
# The test command: the Rust workspace's tests, then the Python package built from this tree
# (`pip install .`, maturin as the build backend) and its pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."

cargo test --workspace --release

# pandas and Dask (`distributed`) for the ensemble tests: a DataFrame of members, a LocalCluster.
python3 -m pip install --quiet pytest numpy sympy pandas "dask[distributed]"
python3 -m pip install --quiet .
# From another directory, so that the installed package is imported, not `python/ddirac`.
cd python/tests && python3 -m pytest -q
