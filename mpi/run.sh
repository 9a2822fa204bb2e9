#!/usr/bin/env bash
# Build veslide-batch with the MPI compiler wrapper (mpi/build.sh, which first finds or installs
# what MPI needs) and run one case or a study on N ranks:
#   bash mpi/run.sh -n 4 FILE.nml [--output PATH] [--overwrite] [--quiet]
# The options are veslide-batch's (veslide's meanings); relative paths are the caller's.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
np=2
if [ "${1:-}" = "-n" ]; then np=$2; shift 2; fi
[ $# -ge 1 ] || { echo "usage: bash mpi/run.sh [-n N] FILE.nml [--output PATH] [--overwrite] [--quiet]" >&2; exit 2; }
exe=$(bash "$root/mpi/build.sh")
source "$root/scripts/env.sh"
extra=()
[ "$(id -u)" -eq 0 ] && extra=(--allow-run-as-root)
OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} exec mpirun "${extra[@]}" --oversubscribe -n "$np" "$exe" "$@"
