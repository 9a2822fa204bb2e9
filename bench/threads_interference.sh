#!/usr/bin/env bash
# Two threads against one, on a quiet machine and with another process holding a core (a busy
# shell loop), for the paper scene (inputs/default.nml with the grid, the solid and the tolerance
# below), A B interleaved over ROUNDS rounds. Prints one line per run (solve seconds from the
# file, FFT pairs, load average) and the medians of 2 threads / 1 thread.
#
#   bash bench/threads_interference.sh [N [ROUNDS [OTHER_VESLIDE]]]
#
# N: grid side (default 1024); ROUNDS: default 3; OTHER_VESLIDE: a second build to interleave
# with this one (e.g. an older commit's), labelled 'other'. docs/solver-scaling.md has the results.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source scripts/env.sh     # .venv/bin on PATH, the HDF5 that setup.sh found (serial), library prefixes
n=${1:-1024}; rounds=${2:-3}; other=${3:-}
fpm build --profile release >/dev/null
this=$(fpm run --profile release veslide --runner echo 2>/dev/null | tail -1)
work=$(mktemp -d)
busy=''
trap '[ -n "$busy" ] && kill "$busy" 2>/dev/null; rm -rf "$work"' EXIT
# the paper scene with solid KIND (elastic: the relaxed solid) on THREADS threads
scene() {
    local kind=$1 threads=$2 mat
    if [ "$kind" = elastic ]; then
        mat="&material model = 'elastic', young_pa = 9.090909090909091e6, poisson = 0.5 /"
    else
        mat="&material model = 'one_term', einf_pa = 1.0e8, ratio = 11.0, tau_s = 0.01, poisson = 0.5 /"
    fi
    cat <<NML
&grid nx = $n, ny = $n, lx_m = 0.01 /
&surface kind = 'self_affine', seed = 1, hurst = 0.8, k_low = 1.0, k_roll = 1.0, k_cut = 64.0, rms_slope = 0.025, scale_to = 'realised' /
$mat
&load mean_pressure_pa = 32.0e3 /
&motion speed_m_s = 0.13 /
&solver method = 'auto', tolerance = 1.0e-8, threads = $threads /
&output file = '$work/out.h5', fields = .false., overwrite = .true. /
NML
}
builds=(this); [ -n "$other" ] && builds+=(other)
results=$work/results.txt
for state in quiet busy; do
    if [ "$state" = busy ]; then sh -c 'while :; do :; done' & busy=$!; sleep 2; fi
    for r in $(seq "$rounds"); do
        for kind in elastic visco; do
            for t in 1 2; do
                scene "$kind" "$t" > "$work/in.nml"
                for b in "${builds[@]}"; do
                    exe=$this; [ "$b" = other ] && exe=$other
                    load=$(cut -d' ' -f1 /proc/loadavg)
                    OMP_NUM_THREADS=$t "$exe" --quiet "$work/in.nml" > /dev/null
                    line=$(python - "$work/out.h5" <<'PY'
import sys, h5py
s = h5py.File(sys.argv[1])["scalars"]
print(f"{s['solve_seconds'][()]:.3f} {s['operator_applications'][()]}")
PY
)
                    echo "$state $r $kind t$t $b $line $load" | tee -a "$results"
                done
            done
        done
    done
    if [ -n "$busy" ]; then kill "$busy"; busy=''; fi
done
python - "$results" <<'PY'
import collections, statistics, sys
d = collections.defaultdict(list)
for line in open(sys.argv[1]):
    state, r, kind, t, b, sec, pairs, load = line.split()
    d[(state, kind, b, t)].append(float(sec))
print("| machine | solid | build | 1 thread [s] | 2 threads [s] | 2 / 1 (medians) |")
print("|---|---|---|---|---|---|")
for (state, kind, b, t) in sorted(d):
    if t != "t1":
        continue
    one, two = d[(state, kind, b, "t1")], d[(state, kind, b, "t2")]
    print(f"| {state} | {kind} | {b} | {', '.join(f'{x:.2f}' for x in one)} | "
          f"{', '.join(f'{x:.2f}' for x in two)} | {statistics.median(two) / statistics.median(one):.2f} |")
PY
