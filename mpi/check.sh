#!/usr/bin/env bash
# CI check of the MPI batch driver: a small study on 2 ranks, joined, must equal the serial run.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export PATH="$root/.venv/bin:$PATH"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/study.nml" <<NML
&grid nx = 32, ny = 32, lx_m = 0.01 /
&surface kind = 'self_affine', seed = 3, k_cut = 8, eccentricity = 0.6 /
&material model = 'one_term' /
&solver fft_planner = 'estimate' /
&sweep speeds_m_s = 0.01, 0.1, 1.0, alphas_deg = 0, 45, n_seeds = 2 /
&output file = '$work/mpi.h5', fields = .false. /
NML
sed "s#$work/mpi.h5#$work/serial.h5#" "$work/study.nml" > "$work/serial.nml"
(cd "$root" && fpm build --profile release >/dev/null)
serial=$(cd "$root" && fpm run --profile release veslide --runner echo 2>/dev/null | tail -1)
(cd "$root" && OMP_NUM_THREADS=1 "$serial" "$work/serial.nml" --quiet)
bash "$root/mpi/run.sh" -n 2 "$work/study.nml" > "$work/log.txt"
python - "$work/serial.h5" "$work/mpi.h5" <<'PY'
import sys
import h5py
import numpy as np
a = h5py.File(sys.argv[1])["/summary"][()]
b = h5py.File(sys.argv[2])["/summary"][()]
ea = h5py.File(sys.argv[1])["/ensemble"][()]
eb = h5py.File(sys.argv[2])["/ensemble"][()]
d = np.max(np.abs(a["friction_coefficient"] - b["friction_coefficient"]) / np.abs(a["friction_coefficient"]))
e = np.max(np.abs(ea["mean_contact_area_fraction"] - eb["mean_contact_area_fraction"]))
ok = len(a) == len(b) == 12 and d < 1e-8 and e < 1e-12
print("mpi check: %d cases, friction rel. diff %.1e, ensemble area diff %.1e: %s" % (len(b), d, e, "ok" if ok else "FAILED"))
sys.exit(0 if ok else 1)
PY
