#!/usr/bin/env bash
# The set-up where Debian's package tools are absent, tried for real (docs/install.md):
#   bash scripts/check_setup.sh
# Runs in a private mount namespace (unshare -m: root and overlayfs needed, else it says SKIPPED and
# exits 0): /usr and this checkout are overlays whose changes vanish with the namespace, so
# nothing on the machine or in the checkout changes (the builds it makes are thrown away too).
#  1. dpkg, dpkg-query, apt-get, apt and update-alternatives removed: scripts/setup.sh must pass
#     without them, and ./dev.sh run build and run inputs/default.nml.
#  2. FFTW, LAPACK/BLAS and HDF5 also copied to prefixes under /opt/apps (include/, lib/; HDF5's
#     h5fc in bin/), as a cluster's modules hold them, and removed from /usr: scripts/setup.sh must
#     refuse with one line for each of the three; pass with VESLIDE_FFTW_DIR, VESLIDE_LAPACK_DIR
#     and VESLIDE_HDF5_DIR; pass with FFTW and LAPACK given as FPM_FFLAGS/FPM_CFLAGS/FPM_LDFLAGS and
#     HDF5 found from the h5fc on PATH alone; then ./dev.sh run must build against the prefixes and
#     run inputs/default.nml (ldd shows the libraries loaded from /opt/apps). LD_LIBRARY_PATH is
#     set to the three lib directories, as `module load` does.
# Before these, 0: with apt-get present (a stub that records its arguments) and fftw3.f03 hidden,
# scripts/setup.sh must ask apt-get for libfftw3-dev alone.
# About half a minute when the checkout's release build is current (step 2 rebuilds: other flags).
#   bash scripts/check_setup.sh --fresh   also, between 1 and 2, the README's commands in a fresh
#                                         clone of this checkout's HEAD (.venv from PyPI, both
#                                         builds, ./dev.sh test): about 5 minutes more
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if [ "${1:-}" != --inside ]; then
    if [ "$(id -u)" -ne 0 ] || ! command -v unshare >/dev/null 2>&1 || ! unshare -m true 2>/dev/null; then
        echo "check_setup: SKIPPED (needs root and unshare -m for a private mount namespace)"; exit 0
    fi
    bash "$root/scripts/setup.sh"                    # the .venv and libraries it starts from
    exec unshare -m --propagation private bash "$root/scripts/check_setup.sh" --inside "$@"
fi
fresh=0
[ "${2:-}" = --fresh ] && fresh=1

start=$(date +%s)
say() { echo "check_setup [$(($(date +%s) - start)) s]: $*"; }
fail() { echo "check_setup: FAILED: $*"; exit 1; }
scratch=$(mktemp -d)
trap 'umount -l "$root" /usr /opt 2>/dev/null || true; rm -rf "$scratch"' EXIT
overlay() {                                         # overlay DIR NAME: DIR's changes go to scratch
    mkdir -p "$scratch/$2/up" "$scratch/$2/work"
    mount -t overlay overlay -o "lowerdir=$1,upperdir=$scratch/$2/up,workdir=$scratch/$2/work" "$1"
}
if ! overlay /usr usr 2>/dev/null || ! overlay "$root" checkout 2>/dev/null; then
    echo "check_setup: SKIPPED (no overlayfs here)"; exit 0
fi
cd "$root"
# FFTW's wisdom (measured plans) kept in the scratch directory: the machine's own wisdom file is
# left alone, and the runs below share their plans, so their results can be compared
export VESLIDE_FFTW_WISDOM="$scratch/fftw-wisdom"
lib=/usr/lib/x86_64-linux-gnu
[ -d "$lib" ] || lib=/usr/lib64

# 0. apt-get installs only what is missing: FFTW's Fortran header hidden, apt-get a stub that
#    records what it is asked for (and installs nothing)
mv /usr/include/fftw3.f03 "$scratch/"
mv /usr/bin/apt-get "$scratch/apt-get.real"
printf '#!/bin/sh\necho "$*" >> %s/apt-get.log\n' "$scratch" > /usr/bin/apt-get
chmod +x /usr/bin/apt-get
if bash scripts/setup.sh 2>"$scratch/refused.txt" >/dev/null; then fail "scripts/setup.sh passed without fftw3.f03"; fi
sed 's/^/    apt-get /' "$scratch/apt-get.log"
grep -q -x -- "install -y -qq --no-install-recommends libfftw3-dev" "$scratch/apt-get.log" &&
    [ "$(grep -c "^veslide setup: " "$scratch/refused.txt")" = 2 ] || fail "not asked for libfftw3-dev alone"
mv "$scratch/fftw3.f03" /usr/include/
say "0. fftw3.f03 missing: apt-get asked for libfftw3-dev alone, then one line naming FFTW"

# 1. no Debian package tools
rm -f /usr/bin/dpkg /usr/bin/dpkg-* /usr/bin/apt /usr/bin/apt-* /usr/bin/update-alternatives \
      /usr/sbin/dpkg-* /usr/sbin/update-alternatives
for t in dpkg dpkg-query apt-get apt update-alternatives; do
    ! command -v "$t" >/dev/null 2>&1 || fail "$t still visible"
done
say "1. dpkg, dpkg-query, apt-get, apt, update-alternatives: command not found"
bash scripts/setup.sh || fail "scripts/setup.sh without dpkg/apt-get"
say "1. scripts/setup.sh: passed"
./dev.sh run --quiet --output "$scratch/default.h5" >"$scratch/run.log" 2>&1 ||
    { cat "$scratch/run.log"; fail "./dev.sh run without dpkg/apt-get"; }
[ -f "$scratch/default.h5" ] || fail "./dev.sh run wrote no result"
say "1. ./dev.sh run (inputs/default.nml): passed, $(du -h "$scratch/default.h5" | cut -f1) written"
bash mpi/build.sh >/dev/null || fail "bash mpi/build.sh without dpkg/apt-get"
say "1. bash mpi/build.sh (scripts/setup.sh --mpi, then the MPI build): passed"
if [ "$fresh" = 1 ]; then
    git clone -q "$root" "$scratch/fresh"
    say "1f. a fresh clone of $(git -C "$scratch/fresh" rev-parse --short HEAD) in $scratch/fresh"
    (
        cd "$scratch/fresh"
        t0=$(date +%s)
        echo '$ ./dev.sh run'
        ./dev.sh run 2>&1 | grep -v -E '^\[|^ \+ |done\.$'
        echo "($(($(date +%s) - t0)) s)"
        t0=$(date +%s)
        echo '$ ./dev.sh test'
        ./dev.sh test 2>&1 | grep -E '^(veslide setup|fortran:|python:|[0-9]+ passed)'
        echo "($(($(date +%s) - t0)) s)"
        echo '$ source .venv/bin/activate; command -v fpm python veslide veslide-bench'
        # shellcheck disable=SC1091
        source .venv/bin/activate
        command -v fpm python veslide veslide-bench
        echo '$ veslide --memory inputs/default.nml --processes 4'
        veslide --memory inputs/default.nml --processes 4
        t0=$(date +%s)
        echo '$ bash mpi/run.sh -n 2 inputs/default.nml --output mpi-default.h5 --quiet'
        bash mpi/run.sh -n 2 inputs/default.nml --output mpi-default.h5 --quiet
        echo "(exit status $?, $(($(date +%s) - t0)) s; mpi-default.h5: $(du -h mpi-default.h5 | cut -f1))"
    ) 2>&1 | sed 's/^/    /' || fail "the README's commands in a fresh clone"
    say "1f. the README's commands in a fresh clone without dpkg/apt-get: passed"
fi

# 2. the libraries at prefixes, as a cluster's modules hold them, and none in /usr
mount -t tmpfs tmpfs /opt
fftw=/opt/apps/fftw/3.3.10; lapack=/opt/apps/lapack/3.11.0; hdf5=/opt/apps/hdf5/1.10.8
mkdir -p "$fftw/include" "$fftw/lib" "$lapack/lib" "$hdf5/include" "$hdf5/lib" "$hdf5/bin"
cp -a /usr/include/fftw3.h /usr/include/fftw3.f03 "$fftw/include/"
cp -a "$lib"/libfftw3.so* "$fftw/lib/"
for l in lapack blas; do
    cp -L "$lib/lib$l.so.3" "$lapack/lib/"
    ln -s "lib$l.so.3" "$lapack/lib/lib$l.so"
done
cp -a /usr/include/hdf5/serial/. "$hdf5/include/"
cp -a "$lib"/libhdf5_serial*.so.* "$hdf5/lib/"
for f in "$lib"/hdf5/serial/*.so; do              # the development names, as HDF5 installs them
    ln -s "$(basename "$(readlink -f "$f")")" "$hdf5/lib/$(basename "$f")"
done
cp -L /usr/bin/h5fc "$hdf5/bin/h5fc"
rm -rf /usr/include/fftw3* /usr/include/hdf5 "$lib"/libfftw3* "$lib"/liblapack* "$lib"/libblas* \
       "$lib"/lapack "$lib"/blas "$lib"/libhdf5* "$lib"/hdf5 "$lib"/pkgconfig/{fftw3,hdf5,lapack,blas}*.pc \
       /usr/bin/h5*
say "2. FFTW, LAPACK/BLAS, HDF5 copied to /opt/apps/{fftw,lapack,hdf5}/VERSION and removed from /usr"
if bash scripts/setup.sh 2>"$scratch/refused.txt"; then fail "scripts/setup.sh passed without the libraries"; fi
sed "s/^/    /" "$scratch/refused.txt"
for what in "FFTW 3" "LAPACK and BLAS" "HDF5's Fortran library"; do
    [ "$(grep -c "^veslide setup: $what" "$scratch/refused.txt")" = 1 ] || fail "no one line for $what"
done
say "2a. scripts/setup.sh without them: refused, one line each for FFTW, LAPACK, HDF5"
# what `module load` sets besides: the copied Debian libraries carry no RUNPATH of their own, so
# liblapack finds libblas, and libhdf5_fortran libhdf5, through LD_LIBRARY_PATH (the build records
# the prefixes' lib directories for the libraries it links itself)
export LD_LIBRARY_PATH="$fftw/lib:$lapack/lib:$hdf5/lib"
VESLIDE_FFTW_DIR=$fftw VESLIDE_LAPACK_DIR=$lapack VESLIDE_HDF5_DIR=$hdf5 bash scripts/setup.sh ||
    fail "scripts/setup.sh with VESLIDE_FFTW_DIR, VESLIDE_LAPACK_DIR, VESLIDE_HDF5_DIR"
say "2b. scripts/setup.sh with VESLIDE_FFTW_DIR, VESLIDE_LAPACK_DIR, VESLIDE_HDF5_DIR: passed"
export FPM_FFLAGS="-I$fftw/include" FPM_CFLAGS="-I$fftw/include"
export FPM_LDFLAGS="-L$fftw/lib -Wl,-rpath,$fftw/lib -L$lapack/lib -Wl,-rpath,$lapack/lib"
export PATH="$hdf5/bin:$PATH"
bash scripts/setup.sh || fail "scripts/setup.sh with FPM_* flags and h5fc on PATH"
say "2c. scripts/setup.sh with FPM_FFLAGS, FPM_CFLAGS, FPM_LDFLAGS and h5fc on PATH: passed"
./dev.sh run --quiet --output "$scratch/prefix.h5" >"$scratch/run.log" 2>&1 ||
    { cat "$scratch/run.log"; fail "./dev.sh run with the libraries at prefixes"; }
[ -f "$scratch/prefix.h5" ] || fail "./dev.sh run wrote no result"
ldd .venv/bin/veslide | grep -E "fftw|lapack|blas|hdf5" | sed 's/ (0x.*//; s/^\s*/    /'
! ldd .venv/bin/veslide | grep -E "fftw|lapack|blas|hdf5" | grep -v -q "=> /opt/apps/" ||
    fail "a library not loaded from /opt/apps"
say "2c. ./dev.sh run (inputs/default.nml) built against /opt/apps: passed"
.venv/bin/python - "$scratch/default.h5" "$scratch/prefix.h5" <<'PY' || fail "the two runs differ"
import sys
import h5py
with h5py.File(sys.argv[1]) as a, h5py.File(sys.argv[2]) as b:
    x, y = (f["/scalars/contact_area_fraction"][()] for f in (a, b))
    print("    contact area fraction %.12f (Debian's libraries) and %.12f (the prefixes)" % (x, y))
    sys.exit(0 if abs(x - y) <= 1e-12 * abs(x) else 1)   # the same libraries: equal but for plans
PY
say "passed"
