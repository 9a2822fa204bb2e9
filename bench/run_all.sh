#!/usr/bin/env bash
# Runs every benchmark in sequence on an otherwise idle machine and writes results/bench-*.txt.
# Tamaas parity needs a venv with tamaas (see docs/benchmarks.md): TAMAAS_PYTHON=/path/to/python
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
source scripts/env.sh     # .venv/bin on PATH, the HDF5 that setup.sh found (serial), library prefixes
mkdir -p results
threads=${OMP_NUM_THREADS:-2}
fpm build --profile release >/dev/null
bench() { fpm run --profile release veslide-bench -- "$@"; }
OMP_NUM_THREADS=$threads bench solver 256 512 1024 | tee results/bench-solver.txt
if [ -n "${TAMAAS_PYTHON:-}" ]; then
    for n in 256 512 1024; do
        OMP_NUM_THREADS=1 "$TAMAAS_PYTHON" bench/tamaas_parity.py results/bench-solver-$n.h5 --tol 1e-10 --repeat 3
    done | tee results/bench-tamaas.txt
fi
OMP_NUM_THREADS=$threads bench kernels | tee results/bench-kernels.txt
OMP_NUM_THREADS=$threads bench accuracy 1024 | tee results/bench-accuracy.txt
OMP_NUM_THREADS=$threads bench hard 512 | tee results/bench-hard-512.txt
OMP_NUM_THREADS=1 bench prony 512 5 | tee results/bench-prony.txt
