#!/usr/bin/env bash
# Build times of the README's two commands, cold and warm: scripts/build_times.sh [LABEL] [COMMIT] [KEEP]
# In a fresh target directory (target-build-times/, removed first): a cold `cargo build --release -p ddirac-cli`,
# then `cargo test --workspace --release --no-run`, then both again after touching the library. Prints seconds.
# With COMMIT, that commit is built from a temporary worktree instead of this tree; with KEEP, the binary
# built is copied there (for scripts/compare_binaries.py).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="$PWD/target-build-times"
rm -rf "$CARGO_TARGET_DIR"
label=${1:-now}
commit=${2:-}
keep=${3:-}
if [ -n "$commit" ]; then
  tree=$(mktemp -d)
  git worktree add --detach "$tree" "$commit" >/dev/null 2>&1
  trap 'git worktree remove --force "$tree"' EXIT
  cd "$tree"
fi
time_of() { local start end; start=$(date +%s.%N); "$@" >/dev/null 2>&1; end=$(date +%s.%N); echo "$end - $start" | bc; }
echo "$label ($(git rev-parse --short HEAD)): load $(cut -d' ' -f1 /proc/loadavg) at start"
echo "cold main build: $(time_of cargo build --release -p ddirac-cli) s"
[ -n "$keep" ] && cp "$CARGO_TARGET_DIR/release/ddirac" "$keep"
echo "test build after the main build: $(time_of cargo test --workspace --release --no-run) s"
touch crates/ddirac/src/lib.rs
echo "main build, library touched: $(time_of cargo build --release -p ddirac-cli) s"
echo "test build, library touched: $(time_of cargo test --workspace --release --no-run) s"
echo "$label: load $(cut -d' ' -f1 /proc/loadavg) at end"
rm -rf "$CARGO_TARGET_DIR"
