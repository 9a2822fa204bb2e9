#!/usr/bin/env bash
# The paper's figure set from its namelists: runs every study in inputs/paper/ (recording each
# one's wall time, the machine's 1-minute load before and after, and the thread count in
# results/paper/runtimes.txt), then draws the figures into docs/figures/paper/ (PNG at 300 dpi,
# PDF and SVG of each).
#   bash postproc/make_figures.sh            all studies (~7 min on 1 idle thread), then the figures
#   bash postproc/make_figures.sh --plot     only redraw from existing results
#   bash postproc/make_figures.sh --quick    small versions of every study (inputs/quick/: 128^2,
#                                            2 seeds, 7 speeds) into results/quick/, every figure
#                                            into results/quick/figures/, in about a minute
# Each study prints a line per case (and the solver's state every 5 s) while it runs.
# VESLIDE_EXE=path uses that build of veslide instead of setting up and building this checkout
# (python and its packages then come from the PATH).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mode=all
case "${1:-}" in
    "") ;;
    --plot) mode=plot ;;
    --quick) mode=quick ;;
    *) echo "usage: bash postproc/make_figures.sh [--plot | --quick]" >&2; exit 2 ;;
esac
inputs=inputs/paper results=results/paper figures=docs/figures/paper
if [ "$mode" = quick ]; then
    inputs=inputs/quick results=results/quick figures=results/quick/figures
fi
if [ -z "${VESLIDE_EXE:-}" ]; then
    bash scripts/setup.sh
    source scripts/env.sh     # .venv/bin on PATH, the HDF5 that setup.sh found (serial), library prefixes
fi
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
mkdir -p "$results" "$figures"
start=$(date +%s.%N)
if [ "$mode" != plot ]; then
    if [ -z "${VESLIDE_EXE:-}" ]; then
        fpm build --profile release >/dev/null
        run() { fpm run --profile release veslide -- "$@"; }
    else
        run() { "$VESLIDE_EXE" "$@"; }
    fi
    : > "$results/runtimes.txt"
    studies=("$inputs"/*.nml)
    k=0
    for nml in "${studies[@]}"; do
        k=$((k + 1))
        echo "== study $k/${#studies[@]}: $nml"
        load0=$(cut -d' ' -f1 /proc/loadavg)
        t0=$(date +%s.%N)
        run "$nml"
        t1=$(date +%s.%N)
        load1=$(cut -d' ' -f1 /proc/loadavg)
        printf '%s %.1f s, load %s -> %s, OMP_NUM_THREADS=%s\n' "$(basename "$nml" .nml)" "$(echo "$t1 - $t0" | bc)" \
            "$load0" "$load1" "$OMP_NUM_THREADS" | tee -a "$results/runtimes.txt"
    done
fi
echo "== figures: $results -> $figures"
python postproc/make_figures.py "$results" "$figures"
printf '== done in %.0f s\n' "$(echo "$(date +%s.%N) - $start" | bc)"
