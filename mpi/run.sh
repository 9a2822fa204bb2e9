#!/usr/bin/env bash
# Build veslide-batch with the MPI compiler wrapper and run a study on N ranks, then join the
# rank files:   bash mpi/run.sh -n 4 STUDY.nml [--overwrite]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
export PATH="$root/.venv/bin:$PATH"
np=2
if [ "${1:-}" = "-n" ]; then np=$2; shift 2; fi
[ $# -ge 1 ] || { echo "usage: bash mpi/run.sh [-n N] STUDY.nml [--overwrite]" >&2; exit 2; }
nml=$(realpath "$1"); shift
(cd "$root/mpi" && fpm build --profile release --compiler mpif90 >/dev/null)
exe=$(cd "$root/mpi" && fpm run --profile release --compiler mpif90 --runner echo 2>/dev/null | tail -1)
extra=()
[ "$(id -u)" -eq 0 ] && extra=(--allow-run-as-root)
OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} mpirun "${extra[@]}" --oversubscribe -n "$np" "$root/mpi/$exe" "$nml" "$@"
out=$(python - "$nml" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
m = re.search(r"&output[^/]*?\bfile\s*=\s*'([^']+)'", text, re.S)
name = m.group(1) if m else "veslide.h5"
print(name[:-3] if name.endswith(".h5") else name)
PY
)
python "$root/postproc/merge_ranks.py" "$out.h5" "$out".rank*.h5
