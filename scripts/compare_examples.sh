#!/usr/bin/env bash
# Runs every shipped example (examples/*.toml) with two builds of `ddirac` and compares their
# trajectory.csv byte for byte; where they differ, prints the largest relative difference and its column.
#
#   scripts/compare_examples.sh OLD_BINARY NEW_BINARY
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1
new=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
for spec in examples/*.toml; do
  name=$(basename "$spec" .toml)
  "$old" run "$spec" --out "$work/$name/old" --quiet
  "$new" run "$spec" --out "$work/$name/new" --quiet
  if cmp -s "$work/$name/old/trajectory.csv" "$work/$name/new/trajectory.csv"; then
    echo "$name: identical"
    continue
  fi
  status=1
  python3 - "$work/$name" "$name" <<'PY'
import csv, sys
directory, name = sys.argv[1], sys.argv[2]
read = lambda which: list(csv.reader(open(f"{directory}/{which}/trajectory.csv")))
old, new = read("old"), read("new")
worst, where = 0.0, None
for a, b in zip(old[1:], new[1:]):
    for column, x, y in zip(old[0], a, b):
        try:
            x, y = float(x), float(y)
        except ValueError:
            continue
        if x != y:
            d = abs(x - y) / max(abs(x), abs(y))
            if d > worst:
                worst, where = d, column
print(f"{name}: differs ({len(old)} and {len(new)} lines), largest relative difference {worst:.2e} in `{where}`")
PY
done
exit $status
