#!/usr/bin/env bash
# CI check of the MPI batch driver: a small study on 2 and on 3 ranks (uneven shares), joined by
# rank 0, must equal the serial run (every cell of /summary and /ensemble but timings), leave no
# rank file behind, and refuse to replace the joined file without --overwrite.
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
# the distributed grid: FFTW's MPI transforms, halos, ordered sums on 1 to 4 ranks (uneven shares)
mpirun_=(mpirun --oversubscribe); [ "$(id -u)" -eq 0 ] && mpirun_+=(--allow-run-as-root)
for np in 1 2 3 4; do
    OMP_NUM_THREADS=1 bash "$root/mpi/build.sh" test --runner "${mpirun_[*]} -n $np" 2>&1 | grep -E "FAIL|checks on"
done
(cd "$root" && fpm build --profile release >/dev/null)
serial=$(cd "$root" && fpm run --profile release veslide --runner echo 2>/dev/null | tail -1)
(cd "$root" && OMP_NUM_THREADS=1 "$serial" "$work/serial.nml" --quiet)
for np in 2 3; do
    rm -f "$work/mpi.h5"
    bash "$root/mpi/run.sh" -n "$np" "$work/study.nml" --quiet
    if ls "$work"/mpi.h5.rank* >/dev/null 2>&1; then echo "mpi check: rank files left behind"; exit 1; fi
    python - "$work/serial.h5" "$work/mpi.h5" "$np" <<'PY'
import sys
import h5py
import numpy as np
skip = ("seconds", "iterations", "operator_applications", "residual", "penetration", "complementarity",
        "negative_pressure", "load_error", "memory_peak")
worst = 0.0
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    nrows = len(a["/summary"])
    for table in ("/summary", "/ensemble"):
        x, y = a[table][()], b[table][()]
        assert x.dtype == y.dtype and len(x) == len(y), table + ": columns or rows differ"
        for name in x.dtype.names:
            if any(s in name for s in skip):
                continue
            if x.dtype[name].kind == "i":
                assert np.array_equal(x[name], y[name]), table + " " + name
            else:
                d = np.max(np.abs(x[name] - y[name]) / np.maximum(np.abs(x[name]), 1e-300))
                worst = max(worst, d)
ok = worst < 1e-9
print("mpi check, %s ranks: %d cases, largest relative difference %.1e: %s" % (sys.argv[3], nrows, worst,
      "ok" if ok else "FAILED"))
sys.exit(0 if ok else 1)
PY
done
if bash "$root/mpi/run.sh" -n 2 "$work/study.nml" --quiet 2>"$work/err.txt"; then
    echo "mpi check: an existing study file was replaced without --overwrite"; exit 1
fi
grep -q "exists" "$work/err.txt" || { echo "mpi check: refusal without a reason: $(cat "$work/err.txt")"; exit 1; }
echo "mpi check: existing file refused in one line: ok"
