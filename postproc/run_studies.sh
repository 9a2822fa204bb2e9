#!/usr/bin/env bash
# The studies behind docs/reproduction.md that are not figures of the paper: runs every input of
# inputs/studies/STUDY/ one after the other (recording each one's wall time and the machine's
# load in results/studies/STUDY/runtimes.txt), then draws the study's tables and figure.
#   bash postproc/run_studies.sh band     figure-2 band study (zeta1 = 1..8)
#   bash postproc/run_studies.sh cells    fast limit against alpha for cells of L0 .. 8 L0
#   bash postproc/run_studies.sh cellspeed   the same at v tau/L0 = 0.1, 1, 10 (L0 and 4 L0)
#   bash postproc/run_studies.sh persson_s   Persson's theory with S(q) = 1/2 + P^2/2, figure-4 scene
#   bash postproc/run_studies.sh STUDY --plot    only redraw from existing results
# OMP_NUM_THREADS defaults to 1 here (the numbers in the docs were measured so). VESLIDE_EXE=PATH
# runs that program (e.g. the GPU build's, `bash gpu/build.sh`) instead of this checkout's release build.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
study="${1:?usage: run_studies.sh band|cells|cellspeed|persson_s [--plot]}"
[ -d "inputs/studies/$study" ] || { echo "no inputs/studies/$study" >&2; exit 1; }
bash scripts/setup.sh
source scripts/env.sh     # .venv/bin on PATH, the HDF5 that setup.sh found (serial), library prefixes
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"
mkdir -p "results/studies/$study" docs/figures/studies
if [ "${2:-}" != "--plot" ]; then
    if [ -n "${VESLIDE_EXE:-}" ]; then
        exe=$VESLIDE_EXE
    else
        fpm build --profile release >/dev/null
        exe=$(fpm run --profile release veslide --runner echo 2>/dev/null | tail -1)
    fi
    log="results/studies/$study/runtimes.txt"
    : > "$log"
    for nml in "inputs/studies/$study"/*.nml; do
        load0=$(cut -d' ' -f1 /proc/loadavg)
        t0=$(date +%s.%N)
        "$exe" "$nml" --quiet
        t1=$(date +%s.%N)
        load1=$(cut -d' ' -f1 /proc/loadavg)
        printf '%s %.1f s, load %s -> %s, OMP_NUM_THREADS=%s\n' "$(basename "$nml" .nml)" \
            "$(echo "$t1 - $t0" | bc)" "$load0" "$load1" "$OMP_NUM_THREADS" | tee -a "$log"
    done
fi
mode="$study"
[ "$study" = persson_s ] && mode=persson     # its tables: boundary elements against the theory
python postproc/study_tables.py "$mode" "results/studies/$study" docs/figures/studies
