#!/usr/bin/env bash
# CI check of the MPI programs: the distributed grid's building blocks on 1-4 ranks; a small study
# on 2 and on 3 ranks (uneven shares), joined by rank 0, must equal the serial run (every cell of
# /summary and /ensemble but timings), leave no rank file behind, and refuse to replace the joined
# file without --overwrite; single cases on a grid distributed over 2 and 3 ranks must equal the
# serial run (fields and scalars to 1e-10, the same iteration count); `--output PATH` (relative
# to the caller) writes a study and a single case there, and a bad option is refused in one line.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh" --mpi          # once here, not in each of the builds below
export VESLIDE_SETUP_DONE=mpi
source "$root/scripts/env.sh"
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
for np in 2 3 5; do      # 5 ranks: more ranks than the 4 chains, one rank has none
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
# one case on a grid distributed over 2 and 3 ranks (uneven slabs) against the serial run: every
# field and scalar to 1e-10 relative, the same iteration count; a viscoelastic anisotropic case
# with tensors and patches, an elastic one (bccg), a measured topography read by rows, the
# metric splitting pdr with its inner bccg, and an adhesive one in motion (gcg's splitting, on
# more than 1e4 cells: its inner steps keep the conjugacy through a few clipped cells, 13 times
# here, a decision each rank takes from the same global sums)
python - "$work/topo.h5" <<'PY'
import sys
import h5py
import numpy as np
x, y = np.meshgrid(np.arange(40), np.arange(36), indexing="ij")
h = 1e-6 * (np.cos(2 * np.pi * x / 40) * np.cos(2 * np.pi * 2 * y / 36) + 0.3 * np.sin(2 * np.pi * 3 * (x + y) / 40))
with h5py.File(sys.argv[1], "w") as f:
    d = f.create_dataset("heights", data=np.zeros((40, 40)))
    d[...] = np.pad(h, ((0, 0), (0, 4)), mode="wrap").T[:40, :40]
    d.attrs["length_m"] = 0.004
PY
cases=(
"&grid nx = 48, ny = 40, lx_m = 0.012, ly_m = 0.01 / &surface kind = 'self_affine', seed = 5, k_cut = 12, eccentricity = 0.5, alpha_deg = 30 / &material model = 'one_term' / &motion speed_m_s = 0.05, direction_deg = 20 / &solver fft_planner = 'estimate' / &analysis anisotropy = .true., patches = .true. /"
"&grid nx = 40, ny = 44, lx_m = 0.01, ly_m = 0.011 / &surface kind = 'self_affine', seed = 2, k_cut = 10 / &material model = 'elastic' / &solver fft_planner = 'estimate' / &analysis patches = .true. /"
"&grid lx_m = 0 / &surface kind = 'file', file = '$work/topo.h5', dataset = 'heights' / &material model = 'one_term' / &motion speed_m_s = 0.02 / &solver fft_planner = 'estimate' /"
"&grid nx = 44, ny = 48, lx_m = 0.011, ly_m = 0.012 / &surface kind = 'self_affine', seed = 7, k_cut = 11, eccentricity = 0.4, alpha_deg = 60 / &material model = 'one_term' / &motion speed_m_s = 0.01 / &solver method = 'pdr', fft_planner = 'estimate' /"
"&grid nx = 128, ny = 100, lx_m = 0.0128, ly_m = 0.01 / &surface kind = 'self_affine', seed = 3, k_cut = 16 / &material model = 'one_term' / &motion speed_m_s = 0.13 / &adhesion law = 'exponential', energy_j_m2 = 0.05, range_m = 2e-6 / &solver fft_planner = 'estimate' /"
)
for k in "${!cases[@]}"; do
    printf '%s\n&output file = "%s", fields = .true. /\n' "${cases[$k]}" "$work/case$k-serial.h5" | tr '"' "'" > "$work/case$k-serial.nml"
    printf '%s\n&output file = "%s", fields = .true. /\n' "${cases[$k]}" "$work/case$k-mpi.h5" | tr '"' "'" > "$work/case$k-mpi.nml"
    (cd "$root" && OMP_NUM_THREADS=1 "$serial" "$work/case$k-serial.nml" --quiet)
    for np in 2 3; do
        rm -f "$work/case$k-mpi.h5"
        bash "$root/mpi/run.sh" -n "$np" "$work/case$k-mpi.nml" --quiet
        python - "$work/case$k-serial.h5" "$work/case$k-mpi.h5" "$np" "$k" <<'PY'
import sys
import h5py
import numpy as np
# (Polonsky-Keer adds a single corrected point from a stored influence column on one process and
# by an FFT pair on a distributed grid: the same iterate, another FFT count)
skip = ("seconds", "memory", "processes", "residual", "penetration", "complementarity", "negative_pressure",
        "load_error", "operator_applications")
worst, where = 0.0, ""
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    assert a["/scalars/iterations"][()] == b["/scalars/iterations"][()], "iteration counts differ"
    assert sorted(a["/fields"]) == sorted(b["/fields"]) and sorted(a["/scalars"]) == sorted(b["/scalars"])
    for name in a["/scalars"]:
        if any(s in name for s in skip):
            continue
        x, y = float(a["/scalars"][name][()]), float(b["/scalars"][name][()])
        d = abs(x - y) / max(abs(x), 1e-300)
        if d > worst:
            worst, where = d, name
    for name in a["/fields"]:
        x, y = a["/fields"][name][()], b["/fields"][name][()]
        d = np.max(np.abs(x - y)) / max(np.max(np.abs(x)), 1e-300)
        if d > worst:
            worst, where = d, name
ok = worst < 1e-10
print("mpi check, case %s on %s ranks: largest relative difference %.1e (%s): %s" % (sys.argv[4], sys.argv[3], worst,
      where, "ok" if ok else "FAILED"))
sys.exit(0 if ok else 1)
PY
    done
done
if bash "$root/mpi/run.sh" -n 2 "$work/study.nml" --quiet 2>"$work/err.txt"; then
    echo "mpi check: an existing study file was replaced without --overwrite"; exit 1
fi
grep -q "exists" "$work/err.txt" || { echo "mpi check: refusal without a reason: $(cat "$work/err.txt")"; exit 1; }
echo "mpi check: existing file refused in one line: ok"
# --output: the file written instead of &output file, a relative path the caller's (as for veslide);
# &output file (mpi.h5, kept from above) untouched
before=$(stat -c %Y "$work/mpi.h5")
mkdir "$work/here"
(cd "$work/here" && bash "$root/mpi/run.sh" -n 2 ../study.nml --output study-o.h5 --quiet)
[ -f "$work/here/study-o.h5" ] && [ "$(stat -c %Y "$work/mpi.h5")" = "$before" ] ||
    { echo "mpi check: --output of a study not written where asked"; exit 1; }
cp "$work/here/study-o.h5" "$work/mpi.h5.o"
compare_study() {
    python - "$1" "$2" "$3" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    for table in ("/summary", "/ensemble"):
        x, y = a[table][()], b[table][()]
        for name in x.dtype.names:
            if "seconds" in name or "memory_peak" in name:
                continue
            assert np.array_equal(x[name], y[name]) if x.dtype[name].kind == "i" else \
                np.allclose(x[name], y[name], rtol=1e-9, atol=0), table + " " + name
print("mpi check, %s: ok" % sys.argv[3])
PY
}
compare_study "$work/serial.h5" "$work/mpi.h5.o" "--output of a study on 2 ranks equals the serial run"
(cd "$work/here" && bash "$root/mpi/run.sh" -n 3 ../case0-mpi.nml -o case-o.h5 --quiet)
[ -f "$work/here/case-o.h5" ] || { echo "mpi check: --output of a single case not written where asked"; exit 1; }
python - "$work/case0-serial.h5" "$work/here/case-o.h5" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    for name in a["/fields"]:
        x, y = a["/fields"][name][()], b["/fields"][name][()]
        assert np.max(np.abs(x - y)) <= 1e-10 * np.max(np.abs(x)), name
print("mpi check, --output of a case on 3 ranks equals the serial run: ok")
PY
for bad in "--output" "--outptu x.h5"; do
    # shellcheck disable=SC2086
    if (cd "$work/here" && bash "$root/mpi/run.sh" -n 2 ../study.nml $bad 2>"$work/err.txt" >/dev/null); then
        echo "mpi check: '$bad' was accepted"; exit 1
    fi
    # (one line of the program's, then mpirun's own report of the exit status)
    [ "$(grep -c "^veslide-batch: " "$work/err.txt")" -eq 1 ] && head -1 "$work/err.txt" | grep -q "^veslide-batch: " ||
        { echo "mpi check: '$bad' not refused in one line:"; cat "$work/err.txt"; exit 1; }
done
echo "mpi check: a missing --output name and an unknown option refused in one line: ok"
# measured plans (fft_planner 'measure') repeat bit for bit: a distributed case on 3 ranks (uneven
# shares), a serial run of another grid, the distributed case again, all on one fresh wisdom file.
# A distributed run keeps its wisdom in FILE-mpi (once it replaced the serial wisdom with its own,
# the serial run planned anew, and its file then lacked the MPI plans); and the first run plans
# again from the first process's gathered wisdom, the others' own forgotten, as every later run
# plans (before, its other processes kept what they had measured themselves: 3 of 6 first runs
# differed from the second in their last bits)
export VESLIDE_FFTW_WISDOM="$work/wisdom"
rm -f "$work/wisdom" "$work/wisdom-mpi"
printf '%s\n' "&grid nx = 48, ny = 40 / &surface k_cut = 10 / &material model = 'one_term' / &motion speed_m_s = 0.05 /" \
    "&output file = '$work/w1.h5', fields = .true. /" > "$work/w1.nml"
sed "s#w1.h5#w2.h5#" "$work/w1.nml" > "$work/w2.nml"
printf '%s\n' "&grid nx = 32, ny = 36 / &surface k_cut = 8 / &output file = '$work/w3.h5' /" > "$work/w3.nml"
bash "$root/mpi/run.sh" -n 3 "$work/w1.nml" --quiet
(cd "$root" && OMP_NUM_THREADS=1 "$serial" "$work/w3.nml" --quiet)
bash "$root/mpi/run.sh" -n 3 "$work/w2.nml" --quiet
unset VESLIDE_FFTW_WISDOM
python - "$work/w1.h5" "$work/w2.h5" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    for g in ("/scalars", "/fields"):
        for name in a[g]:
            if "seconds" in name or "memory_peak" in name:
                continue
            assert np.asarray(a[g][name][()]).tobytes() == np.asarray(b[g][name][()]).tobytes(), g + "/" + name
print("mpi check, a distributed case with measured plans repeats bit for bit after a serial run: ok")
PY
# the same for a study on 2 ranks (each rank solves its own cases with serial plans): rank 0 plans
# the study's grid before the others plan from its wisdom (before, each rank measured its own on
# the first run: 1 of 6 first runs of a 96 x 80 study equalled the second)
export VESLIDE_FFTW_WISDOM="$work/wisdom-study"
rm -f "$work/wisdom-study" "$work/wisdom-study-mpi"
printf '%s\n' "&grid nx = 48, ny = 40 / &surface k_cut = 10 / &material model = 'one_term' /" \
    "&sweep speeds_m_s = 0.01, 0.1, n_seeds = 2 / &output file = '$work/ws1.h5', fields = .true. /" > "$work/ws1.nml"
sed "s#ws1.h5#ws2.h5#" "$work/ws1.nml" > "$work/ws2.nml"
bash "$root/mpi/run.sh" -n 2 "$work/ws1.nml" --quiet
bash "$root/mpi/run.sh" -n 2 "$work/ws2.nml" --quiet
unset VESLIDE_FFTW_WISDOM
python - "$work/ws1.h5" "$work/ws2.h5" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    for case in a["/cases"]:
        for g in ("scalars", "fields"):
            for name in a["/cases"][case][g]:
                if "seconds" in name or "memory_peak" in name:
                    continue
                x, y = a["/cases"][case][g][name][()], b["/cases"][case][g][name][()]
                assert np.asarray(x).tobytes() == np.asarray(y).tobytes(), case + "/" + g + "/" + name
print("mpi check, a study with measured plans repeats bit for bit from its first run: ok")
PY
# an output that cannot be written is an I/O error, exit status 3, as for veslide: a case and a study
for nml in "$work/w1.nml" "$work/study.nml"; do
    st=0
    bash "$root/mpi/run.sh" -n 2 "$nml" --output /proc/veslide-check.h5 --quiet >/dev/null 2>&1 || st=$?
    [ "$st" -eq 3 ] || { echo "mpi check: an output that cannot be written exited with $st, not 3 ($nml)"; exit 1; }
done
echo "mpi check: an output that cannot be written exits with 3 (a case and a study): ok"
