#!/usr/bin/env bash
# On the GPU machine, from the repository root with gpu/dist packed by gpu/pack.sh, in stages, each
# with a time limit, inside a budget of VESLIDE_REMOTE_BUDGET seconds (default 540: the whole within
# 10 minutes); a stage that no longer fits is skipped and said so, and VESLIDE_REMOTE_FROM=K
# starts at stage K (the summary numbers them). Logs go to $OUT (default
# gpu-out/), at most 8 files, summary.txt first.
#   bash gpu/remote.sh [all]       the device checks (gpu/check.sh) and the benchmark (veslide-bench
#       gpu). In order: the suite 'device'; the paper scene at 4096^2, 8192^2, 16384^2 with the CPU
#       path at 4096^2 in the same run; at 32768^2; the other suites and compute-sanitizer's
#       memcheck (gpu/check.sh); pdr's lean layout at 4096^2 and 8192^2 (VESLIDE_DEVICE_LEAN=1:
#       cuFFT's work area in u, the device memory veslide --memory's refusal counts on); the
#       per-pass profile at 4096^2, 8192^2; the adhesive solver (gcg) on the example input's scene
#       at 1024^2, on the device and on the CPU. Files: summary.txt, device.log, bench.log (with
#       big.log and lean.log appended to bench-gpu.csv), profile.log, suites.log.
#   bash gpu/remote.sh adhesion    the adhesive solver on the card first: the suite 'device' (its
#       passes against their CPU twins, the adhesive scenes and the 29 adhesive hard cases against
#       the CPU); veslide-bench adhesion (the paper scene with and without adhesion, interleaved)
#       on the device and the CPU at 1024^2 (three rounds), on the device at 2048^2 (three);
#       memcheck of the gcg passes and of the adhesive scenes; the suite 'solver-gcg' with 'auto';
#       one round at 4096^2 with each pass profiled; at 2048^2 on the device and the CPU; at
#       8192^2 on the device and at 4096^2 (three rounds) at the tolerance 5e-10 (1e-10 is below
#       the gradient's round-off there). Files: summary.txt, device.log, adhesion.log, suites.log.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=${OUT:-gpu-out}; mkdir -p "$out"
dist=gpu/dist
cudalib=""
for d in /usr/local/cuda/targets/x86_64-linux/lib /usr/local/cuda/lib64 /usr/lib/x86_64-linux-gnu \
         $(ls -d /opt/*/.venv/lib/python3*/site-packages/nvidia/cu13/lib 2>/dev/null); do
    if [ -e "$d/libcufft.so.12" ] && [ -e "$d/libcudart.so.13" ]; then cudalib=$d; break; fi
done
if [ -z "$cudalib" ]; then
    f=$(find /usr /opt -name libcufft.so.12 2>/dev/null | head -1)
    [ -n "$f" ] && cudalib=$(dirname "$f")
fi
export LD_LIBRARY_PATH="$PWD/$dist/lib${cudalib:+:$cudalib}"
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-$(nproc)} OMP_WAIT_POLICY=passive
export VESLIDE_FFTW_WISDOM=none
budget=${VESLIDE_REMOTE_BUDGET:-540}
start=$(date +%s)
summary="$out/summary.txt"
{
    echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GB", $2/1e6}' /proc/meminfo); CUDA libraries: ${cudalib:-NOT FOUND}"
    nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.sm,clocks.mem --format=csv 2>&1
    ldd "$dist/bin/veslide-tests" | grep -E "not found|cufft|cudart|veslide_device"
} > "$summary"
# stage NAME LIMIT LOG COMMAND...: run when at least LIMIT/2 seconds of the budget are left (and
# the stage's number is VESLIDE_REMOTE_FROM or later: a second session goes on where one stopped)
from=${VESLIDE_REMOTE_FROM:-1}
count=0
stage() {
    local name=$1 limit=$2 log=$3; shift 3
    count=$((count + 1)); name="$count. $name"
    if [ "$count" -lt "$from" ]; then echo "$name: skipped (VESLIDE_REMOTE_FROM=$from)" >> "$summary"; return; fi
    local left=$((budget - ($(date +%s) - start)))
    if [ "$left" -lt $((limit / 2)) ]; then
        echo "$name: skipped ($left s of the budget left)" >> "$summary"; return
    fi
    [ "$limit" -gt "$left" ] && limit=$left
    local t0; t0=$(date +%s)
    timeout "$limit" "$@" >> "$log" 2>&1
    local rc=$?
    echo "$name: rc $rc in $(($(date +%s) - t0)) s$([ $rc -eq 124 ] && echo ' (timed out)')" >> "$summary"
}
bin=$dist/bin
plan=${1:-all}
if [ "$plan" = adhesion ]; then
    stage "device suite" 150 "$out/device.log" "$bin/veslide-tests" device
    stage "adhesion bench at 1024, device and CPU" 100 "$out/adhesion.log" "$bin/veslide-bench" adhesion both 3 1024
    stage "adhesion bench at 2048, device" 40 "$out/adhesion.log" "$bin/veslide-bench" adhesion gpu 3 2048
    for t in passes-gcg adhesive-scenes-against-cpu; do
        if command -v compute-sanitizer >/dev/null 2>&1; then
            echo "## memcheck $t" >> "$out/suites.log"
            stage "memcheck $t" 80 "$out/suites.log" compute-sanitizer --tool memcheck --error-exitcode 3 \
                "$bin/veslide-tests" device "$t"
        else
            count=$((count + 1))                     # (the stages keep their numbers)
            echo "$count. memcheck $t: compute-sanitizer not found" >> "$summary"
        fi
    done
    stage "suite solver-gcg (auto)" 60 "$out/suites.log" "$bin/veslide-tests" solver-gcg
    VESLIDE_DEVICE_PROFILE=1 stage "adhesion bench at 4096, device, one round, profiled" 90 "$out/adhesion.log" \
        "$bin/veslide-bench" adhesion gpu 1 4096
    stage "adhesion bench at 2048, device and CPU, one round" 120 "$out/adhesion.log" \
        "$bin/veslide-bench" adhesion both 1 2048
    # (the default tolerance 1e-10 is below the gradient's round-off from 4096^2 up: docs/validity.md (10))
    VESLIDE_BENCH_TOLERANCE=5e-10 stage "adhesion bench at 8192, device, one round, tolerance 5e-10" 120 \
        "$out/adhesion.log" "$bin/veslide-bench" adhesion gpu 1 8192
    VESLIDE_BENCH_TOLERANCE=5e-10 stage "adhesion bench at 4096, device, three rounds, tolerance 5e-10" 60 \
        "$out/adhesion.log" "$bin/veslide-bench" adhesion gpu 3 4096
    echo "total: $(($(date +%s) - start)) s" >> "$summary"
    cat "$summary"
    grep -E "passed|failed|FAIL" "$out/device.log" | tail -5
    grep -E "^\||^paper" "$out/adhesion.log" | grep -v -- "---" | cut -c1-300
    grep -E "ERROR SUMMARY|passed|failed" "$out/suites.log" | tail -6
    exit 0
fi
stage "device suite" 120 "$out/device.log" "$bin/veslide-tests" device
VESLIDE_BENCH_CPU=4096 VESLIDE_BENCH_CSV="$out/bench-gpu.csv" stage "benchmark 4096..16384 and the CPU at 4096" \
    200 "$out/bench.log" "$bin/veslide-bench" gpu 4096 8192 16384
VESLIDE_BENCH_CPU=none VESLIDE_BENCH_CSV=/tmp/big.csv stage "benchmark 32768" 120 "$out/bench.log" \
    "$bin/veslide-bench" gpu 32768
stage "the other suites and memcheck (gpu/check.sh)" 150 "$out/suites.log" bash gpu/check.sh "$bin"
echo "## pdr's lean layout (VESLIDE_DEVICE_LEAN=1)" >> "$out/bench.log"
VESLIDE_DEVICE_LEAN=1 VESLIDE_BENCH_CPU=none VESLIDE_BENCH_CSV=/tmp/lean.csv \
    stage "pdr's lean layout at 4096, 8192 (VESLIDE_DEVICE_LEAN=1)" 60 "$out/bench.log" "$bin/veslide-bench" gpu 4096 8192
VESLIDE_DEVICE_PROFILE=1 VESLIDE_BENCH_CPU=none VESLIDE_BENCH_CSV=/tmp/profile.csv \
    stage "profile at 4096, 8192" 60 "$out/profile.log" "$bin/veslide-bench" gpu 4096 8192
# the adhesive solver (gcg): the example input's scene at 1024^2 on the device and on the CPU
sed -e 's/nx = 256, ny = 256/nx = 1024, ny = 1024/' -e "s|file = .*|file = '/tmp/adh.h5', fields = .false.|" \
    inputs/adhesion/sliding.nml > /tmp/adh1024.nml
for d in gpu cpu; do
    echo "## gcg, inputs/adhesion/sliding.nml at 1024^2, --device $d" >> "$out/bench.log"
    stage "gcg at 1024^2 on the $d" 90 "$out/bench.log" "$bin/veslide" --overwrite --device "$d" /tmp/adh1024.nml
done
tail -n +2 /tmp/big.csv >> "$out/bench-gpu.csv" 2>/dev/null
{ echo "# lean layout (VESLIDE_DEVICE_LEAN=1)"; tail -n +2 /tmp/lean.csv; } >> "$out/bench-gpu.csv" 2>/dev/null
echo "total: $(($(date +%s) - start)) s" >> "$summary"
cat "$summary"
grep -E "passed|failed|FAIL" "$out/device.log" | tail -5
tail -5 "$out/suites.log"
grep -E "^\||^device:|lean|^## gcg|solver gcg|friction coef|time: " "$out/bench.log" 2>/dev/null | cut -c1-240
