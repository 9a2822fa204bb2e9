#!/usr/bin/env bash
# The paper's figure set from its namelists: runs every study in inputs/paper/ (recording each
# one's wall time, the machine's 1-minute load before and after, and the thread count in
# results/paper/runtimes.txt), then draws the figures into docs/figures/paper/.
#   bash postproc/make_figures.sh            all studies, then the figures
#   bash postproc/make_figures.sh --plot     only redraw from existing results
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
export PATH="$PWD/.venv/bin:$PATH"
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
mkdir -p results/paper docs/figures/paper
if [ "${1:-}" != "--plot" ]; then
    fpm build --profile release >/dev/null
    : > results/paper/runtimes.txt
    for nml in inputs/paper/*.nml; do
        load0=$(cut -d' ' -f1 /proc/loadavg)
        t0=$(date +%s.%N)
        fpm run --profile release veslide -- "$nml" --quiet
        t1=$(date +%s.%N)
        load1=$(cut -d' ' -f1 /proc/loadavg)
        printf '%s %.1f s, load %s -> %s, OMP_NUM_THREADS=%s\n' "$(basename "$nml" .nml)" "$(echo "$t1 - $t0" | bc)" \
            "$load0" "$load1" "$OMP_NUM_THREADS" | tee -a results/paper/runtimes.txt
    done
fi
python postproc/make_figures.py results/paper docs/figures/paper
