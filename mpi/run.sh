#!/usr/bin/env bash
# Build veslide-batch with the MPI compiler wrapper and run a study on N ranks; rank 0 joins the
# rank files into the study file:   bash mpi/run.sh -n 4 STUDY.nml [--overwrite] [--quiet]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
export PATH="$root/.venv/bin:$PATH"
np=2
if [ "${1:-}" = "-n" ]; then np=$2; shift 2; fi
[ $# -ge 1 ] || { echo "usage: bash mpi/run.sh [-n N] STUDY.nml [--overwrite] [--quiet]" >&2; exit 2; }
nml=$(realpath "$1"); shift
exe=$(bash "$root/mpi/build.sh")
extra=()
[ "$(id -u)" -eq 0 ] && extra=(--allow-run-as-root)
OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} exec mpirun "${extra[@]}" --oversubscribe -n "$np" "$exe" "$nml" "$@"
