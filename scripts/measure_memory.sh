#!/usr/bin/env bash
# Peak resident memory of `ddirac run` for a short and a long run of the charged particle
# (examples/charged_particle.toml, h = 0.2, every 1000th row written as CSV and NPY): rows are
# streamed and the library keeps no trajectory, so the two peaks should be about equal.
#
#   scripts/measure_memory.sh                 # 10^4 and 10^7 steps
#   SMALL=10000 LARGE=1000000 scripts/measure_memory.sh
#
# The peak is GNU time's "Maximum resident set size" (`/usr/bin/time -v`, Debian package `time`);
# without it, the script samples VmHWM (the kernel's high-water mark) from /proc/<pid>/status every
# 20 ms, which misses at most the growth of the last 20 ms of the run (PEAK_FROM_PROC=1 forces that).
set -euo pipefail
cd "$(dirname "$0")/.."

small=${SMALL:-10000}
large=${LARGE:-10000000}
spec=examples/charged_particle.toml

cargo build --release -p ddirac-cli --quiet
bin=${CARGO_TARGET_DIR:-target}/release/ddirac
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [ -z "${PEAK_FROM_PROC:-}" ] && /usr/bin/time -v true >/dev/null 2>&1; then
    gnu_time=1
    method="/usr/bin/time -v (Maximum resident set size)"
else
    gnu_time=
    method="VmHWM from /proc/<pid>/status, sampled every 20 ms"
fi

# peak_kib STEPS: runs the spec for STEPS steps; prints "<peak KiB> <wall seconds>".
peak_kib() {
    local steps=$1 out="$work/out-$1" started ended peak
    local args=(run "$spec" --quiet --format csv,npy --out "$out"
        --set "time.steps=$steps" --set "time.duration=$((steps / 5))" --set output.every=1000)
    started=$(date +%s.%N)
    if [ -n "$gnu_time" ]; then
        /usr/bin/time -v -o "$work/time-$steps" "$bin" "${args[@]}"
        peak=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time-$steps")
    else
        "$bin" "${args[@]}" &
        local pid=$! value
        peak=0
        while kill -0 "$pid" 2>/dev/null; do
            value=$(awk '/^VmHWM:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
            if [ -n "$value" ]; then peak=$value; fi
            sleep 0.02
        done
        wait "$pid"
    fi
    ended=$(date +%s.%N)
    test -s "$out/trajectory.csv" && test -s "$out/npy/t.npy" && test -s "$out/summary.json"
    echo "$peak $(awk -v a="$started" -v b="$ended" 'BEGIN {printf "%.2f", b - a}')"
}

read -r small_kib small_s < <(peak_kib "$small")
read -r large_kib large_s < <(peak_kib "$large")
echo "peak RSS by $method"
printf '%12s steps: %8s KiB  (%s s)\n' "$small" "$small_kib" "$small_s" "$large" "$large_kib" "$large_s"
awk -v a="$small_kib" -v b="$large_kib" 'BEGIN {printf "ratio large/small: %.3f\n", b / a}'
