#!/usr/bin/env bash
# What veslide needs, found by probing first; only what is missing is installed, and only with
# apt-get where there is one (Debian, Ubuntu). Elsewhere each missing piece gets one line saying
# what to provide and how to point the build at it (docs/install.md). Fast when nothing is missing.
#   bash scripts/setup.sh         the serial build (./dev.sh) and the Python tools
#   bash scripts/setup.sh --mpi   also the MPI build (mpi/build.sh runs this; nothing else needs MPI)
# A library counts as present when a tiny program using it compiles, links and runs with the
# compilers and flags the build uses: FPM_FC (gfortran), FPM_CC (gcc), FPM_FFLAGS, FPM_CFLAGS,
# FPM_LDFLAGS, extended by the prefixes VESLIDE_FFTW_DIR and VESLIDE_LAPACK_DIR (scripts/env.sh).
# HDF5 is looked for at VESLIDE_HDF5_DIR, then under pkg-config's names (Debian's hdf5-serial
# first), then beside the h5fc on PATH; the first that works is named to fpm by a pkg-config file
# of the project's own, .venv/veslide/pkgconfig/hdf5_hl_fortran.pc, so the serial build gets a
# serial HDF5 whatever the system's default 'hdf5' is. --mpi does the same for mpif90, mpirun,
# FFTW's MPI library and a parallel HDF5 (VESLIDE_HDF5_MPI_DIR, pkg-config's hdf5-openmpi,
# hdf5-mpich, hdf5-mpi, ..., h5pfc) into .venv/veslide/pkgconfig-mpi. Nothing system-wide is
# changed but by apt-get installing what is missing (no update-alternatives).
# Then the project-local Python venv .venv: fpm 0.12, the post-processing and test packages and
# this checkout's Python package (python/, editable).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
mpi=0
case "${1:-}" in
    --mpi) mpi=1 ;;
    "") ;;
    *) echo "usage: bash scripts/setup.sh [--mpi]" >&2; exit 2 ;;
esac
python3_=$(command -v python3 || true)      # the system's, looked up before .venv/bin is on PATH
# shellcheck source=scripts/env.sh
source scripts/env.sh
fc=${FPM_FC:-gfortran}
cc=${FPM_CC:-gcc}
read -ra fflags <<<"${FPM_FFLAGS:-}"
read -ra cflags <<<"${FPM_CFLAGS:-}"
read -ra ldflags <<<"${FPM_LDFLAGS:-}"
pcdir=$root/.venv/veslide/pkgconfig
pcdir_mpi=$root/.venv/veslide/pkgconfig-mpi
# pkg-config's search path without the project's own files (those are written from what it finds)
syspc=$(tr ':' '\n' <<<"${PKG_CONFIG_PATH:-}" | grep -v -x -F -e "$pcdir" -e "$pcdir_mpi" | paste -sd: || true)

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/omp.f90" <<'F'
program probe
    use omp_lib, only: omp_get_max_threads
    implicit none
    if (omp_get_max_threads() < 1) error stop 1
end program probe
F
cat > "$tmp/omp.c" <<'F'
#include <omp.h>
int main(void) { return omp_get_max_threads() < 1; }
F
cat > "$tmp/fftw.F90" <<'F'
program probe
    use, intrinsic :: iso_c_binding
    implicit none
#include "fftw3.f03"
    type(c_ptr) :: plan
    real(c_double) :: x(8)
    complex(c_double_complex) :: k(5)
    plan = fftw_plan_dft_r2c_1d(8, x, k, FFTW_ESTIMATE)
    x = 1
    call fftw_execute_dft_r2c(plan, x, k)
    call fftw_destroy_plan(plan)
    if (abs(real(k(1)) - 8) > 1e-12) error stop 1
end program probe
F
cat > "$tmp/fftw.c" <<'F'
#include <fftw3.h>
int main(void) { fftw_forget_wisdom(); return 0; }
F
cat > "$tmp/lapack.f90" <<'F'
program probe
    implicit none
    external :: dgesv
    double precision :: a(2, 2), b(2)
    integer :: ipiv(2), info
    a = reshape([2d0, 1d0, 1d0, 4d0], [2, 2]); b = [3d0, 5d0]
    call dgesv(2, 1, a, 2, ipiv, b, 2, info)
    if (info /= 0 .or. any(abs(b - 1d0) > 1d-12)) error stop 1
end program probe
F
cat > "$tmp/hdf5.f90" <<'F'
program probe
    use hdf5
    implicit none
    integer :: err
    call h5open_f(err); if (err /= 0) error stop 1
    call h5close_f(err)
end program probe
F
cat > "$tmp/mpi.f90" <<'F'
program probe
    use mpi_f08
    implicit none
    call MPI_Init(); call MPI_Finalize()
end program probe
F
cat > "$tmp/fftw_mpi.F90" <<'F'
program probe
    use, intrinsic :: iso_c_binding
    implicit none
#include "fftw3-mpi.f03"
    call fftw_mpi_init()
end program probe
F
cat > "$tmp/hdf5_mpi.f90" <<'F'
program probe
    use mpi_f08
    use hdf5
    implicit none
    integer :: err
    integer(hid_t) :: plist
    call MPI_Init()
    call h5open_f(err)
    call h5pcreate_f(H5P_FILE_ACCESS_F, plist, err)
    call h5pset_fapl_mpio_f(plist, MPI_COMM_WORLD%MPI_VAL, MPI_INFO_NULL%MPI_VAL, err)
    call MPI_Finalize()
end program probe
F

# probe run|link COMPILER SOURCE [FLAGS...]: build the probe (and run it); its output in $tmp/log
probe() {
    local mode=$1 compiler=$2 src=$3
    shift 3
    rm -f "$tmp/a.out"
    if ! command -v "$compiler" >/dev/null 2>&1; then
        echo "$compiler: command not found" > "$tmp/log"; return 1
    fi
    # (from the checkout's root, as fpm compiles: relative paths in the flags mean the same)
    "$compiler" "$tmp/$src" "$@" -o "$tmp/a.out" > "$tmp/log" 2>&1 || return 1
    [ "$mode" = link ] || (cd "$tmp" && ./a.out) >> "$tmp/log" 2>&1
}
# the first line of the last probe's output that says why it failed
why() {
    local line
    line=$(grep -m1 -iE "error|not found|undefined|cannot|no such" "$tmp/log" || tail -1 "$tmp/log")
    echo "${line:0:200}"
}

# HDF5: CFLAGS and LIBS for the Fortran library under a prefix (hdf5.mod, libhdf5_fortran)
hdf5_prefix() {
    local p=$1 d inc="" lib=""
    for d in "$p/include" "$p/include/shared" "$p/include/static" "$p/mod" "$p/lib" "$p/lib64"; do
        [ -e "$d/hdf5.mod" ] && { inc=$d; break; }
    done
    [ -n "$inc" ] || inc=$(dirname "$(find "$p" -maxdepth 4 -name hdf5.mod -print -quit 2>/dev/null)" 2>/dev/null)
    for d in "$p/lib64" "$p/lib" "$p/lib/x86_64-linux-gnu"; do
        compgen -G "$d/libhdf5_fortran.*" >/dev/null && { lib=$d; break; }
    done
    [ -n "$inc" ] && [ "$inc" != . ] && [ -n "$lib" ] || return 1
    h5_cflags="-I$inc"
    h5_libs="-L$lib -Wl,-rpath,$lib -lhdf5_fortran -lhdf5"
    h5_version=$(grep -h -m1 -oE 'H5_VERSION +"[0-9.]+' "$inc"/H5pubconf*.h "$p"/include/H5pubconf*.h 2>/dev/null |
                 grep -oE '[0-9.]+$' | head -1 || true)
}
# HDF5: CFLAGS and LIBS from a pkg-config name (its Fortran library added when it names only C's)
hdf5_pkgconfig() {
    local name=$1 flag
    PKG_CONFIG_PATH=$syspc pkg-config --exists "$name" 2>/dev/null || return 1
    h5_cflags=$(PKG_CONFIG_PATH=$syspc pkg-config --cflags "$name")
    h5_libs=$(PKG_CONFIG_PATH=$syspc pkg-config --libs "$name")
    h5_version=$(PKG_CONFIG_PATH=$syspc pkg-config --modversion "$name")
    [[ "$h5_libs" == *fortran* ]] || h5_libs="-lhdf5_fortran $h5_libs"
    for flag in $h5_libs; do                    # found at run time without LD_LIBRARY_PATH
        [[ "$flag" == -L* ]] && h5_libs="$h5_libs -Wl,-rpath,${flag#-L}"
    done
    return 0
}
# find_hdf5 serial|mpi: the first HDF5 of the flavour whose probe works, written as
# hdf5_hl_fortran.pc (the first name fpm's hdf5 metapackage looks up) into the project's directory
find_hdf5() {
    local flavour=$1 dir prefix_var wrapper names compiler src mode cand kind
    if [ "$flavour" = serial ]; then
        dir=$pcdir; prefix_var=${VESLIDE_HDF5_DIR:-}; wrapper=h5fc; compiler=$fc; src=hdf5.f90; mode=run
        names=(hdf5-serial hdf5_hl_fortran hdf5-hl-fortran hdf5_fortran hdf5-fortran hdf5_hl hdf5)
    else
        dir=$pcdir_mpi; prefix_var=${VESLIDE_HDF5_MPI_DIR:-}; wrapper=h5pfc; compiler=mpif90; src=hdf5_mpi.f90
        mode=link
        names=(hdf5-openmpi hdf5-mpich hdf5-mpi hdf5_hl_fortran hdf5-hl-fortran hdf5_fortran hdf5-fortran hdf5_hl hdf5)
    fi
    h5_tried=()
    local cands=()
    [ -n "$prefix_var" ] && cands+=("prefix:$prefix_var")
    if command -v pkg-config >/dev/null 2>&1; then
        for cand in "${names[@]}"; do cands+=("pkg-config:$cand"); done
    fi
    command -v "$wrapper" >/dev/null 2>&1 && cands+=("$wrapper:$(command -v "$wrapper")")
    for cand in "${cands[@]}"; do
        kind=${cand%%:*}; cand=${cand#*:}
        h5_version=""
        case "$kind" in
            prefix) hdf5_prefix "$cand" ;;
            pkg-config) hdf5_pkgconfig "$cand" ;;
            *) hdf5_prefix "$(dirname "$(dirname "$cand")")" ;;      # the prefix of h5fc, h5pfc
        esac || { [ "$kind" = pkg-config ] || h5_tried+=("$kind $cand: no hdf5.mod and libhdf5_fortran"); continue; }
        # shellcheck disable=SC2086
        if probe "$mode" "$compiler" "$src" "${fflags[@]}" $h5_cflags "${ldflags[@]}" $h5_libs; then
            mkdir -p "$dir"
            {
                echo "# Written by scripts/setup.sh: the ${flavour/mpi/parallel} HDF5 it found ($kind $cand), under the name"
                echo "# fpm's hdf5 metapackage looks up first; scripts/env.sh (or mpi/build.sh) puts this first."
                echo "Name: hdf5_hl_fortran"
                echo "Description: HDF5 (${flavour/mpi/parallel}) for veslide, from $kind $cand"
                echo "Version: ${h5_version:-0}"
                echo "Cflags: $h5_cflags"
                echo "Libs: $h5_libs"
            } > "$dir/hdf5_hl_fortran.pc.new"
            cmp -s "$dir/hdf5_hl_fortran.pc.new" "$dir/hdf5_hl_fortran.pc" 2>/dev/null ||
                echo "veslide setup: ${flavour/mpi/parallel} HDF5 ${h5_version:-} from $kind $cand"
            mv "$dir/hdf5_hl_fortran.pc.new" "$dir/hdf5_hl_fortran.pc"
            return 0
        fi
        h5_tried+=("$kind $cand: $(why)")
    done
    rm -f "$dir/hdf5_hl_fortran.pc"
    return 1
}

# hint TARGET VAR...: where a module system has set a prefix variable VAR but not veslide's TARGET
hint() {
    local target=$1 var
    shift
    for var in "$@"; do
        if [ -n "${!var:-}" ]; then echo " (\$$var is set: try $target=\$$var)"; return; fi
    done
}

# lack PACKAGES PART...: one missing piece, its message the PARTs joined, its Debian packages
lack() {
    local names
    read -ra names <<<"$1"
    packages+=("${names[@]}")
    shift
    local IFS=""
    missing+=("$*")
}
# probe_all: fills missing (one message per missing piece) and packages (their Debian packages)
probe_all() {
    local tried
    missing=(); packages=(); optional=()
    probe run "$fc" omp.f90 -fopenmp "${fflags[@]}" "${ldflags[@]}" ||
        lack gfortran "no Fortran compiler with OpenMP: '$fc' ($(why)). Provide gfortran >= 12" \
            " (module load gcc, or the distribution's gfortran) or name a gfortran-compatible one: FPM_FC=..."
    probe run "$cc" omp.c -fopenmp "${cflags[@]}" "${ldflags[@]}" ||
        lack gcc "no C compiler with OpenMP: '$cc' ($(why)). Provide gcc (module load gcc) or FPM_CC=..."
    command -v pkg-config >/dev/null 2>&1 ||
        lack pkg-config "no pkg-config (fpm's hdf5 metapackage runs it). Provide pkg-config or pkgconf"
    { probe run "$fc" fftw.F90 "${fflags[@]}" "${ldflags[@]}" -lfftw3 &&
      probe run "$cc" fftw.c "${cflags[@]}" "${ldflags[@]}" -lfftw3; } ||
        lack libfftw3-dev "FFTW 3 (fftw3.f03, fftw3.h, libfftw3) not found: $(why). Provide it" \
            " (module load fftw) and point the build at it: export VESLIDE_FFTW_DIR=PREFIX" \
            " (PREFIX/include/fftw3.f03, PREFIX/lib/libfftw3.so)" \
            "$(hint VESLIDE_FFTW_DIR FFTW_ROOT FFTW_DIR FFTW_HOME)," \
            " or -I in FPM_FFLAGS and FPM_CFLAGS and -L in FPM_LDFLAGS"
    probe run "$fc" lapack.f90 "${fflags[@]}" "${ldflags[@]}" -llapack -lblas ||
        lack "liblapack-dev libblas-dev" "LAPACK and BLAS (liblapack, libblas) not found: $(why)." \
            " Provide them (module load lapack or openblas) and export VESLIDE_LAPACK_DIR=PREFIX" \
            " (PREFIX/lib/liblapack.so and libblas.so; for OpenBLAS alone, links of those two names to" \
            " it: docs/install.md), or -L in FPM_LDFLAGS"
    if ! find_hdf5 serial; then
        tried="${h5_tried[*]:-none (no VESLIDE_HDF5_DIR, no pkg-config entry, no h5fc on PATH)}"
        lack libhdf5-dev "HDF5's Fortran library (hdf5.mod, libhdf5_fortran) not found; tried: $tried." \
            " Provide HDF5 >= 1.10 with Fortran (module load hdf5: its h5fc on PATH is enough, or" \
            " its pkg-config file on PKG_CONFIG_PATH) or export VESLIDE_HDF5_DIR=PREFIX" \
            "$(hint VESLIDE_HDF5_DIR HDF5_ROOT HDF5_DIR HDF5_HOME)"
    fi
    if [ ! -x .venv/bin/python ] && ! { [ -n "$python3_" ] && "$python3_" -c 'import venv, ensurepip' 2>/dev/null; }; then
        lack python3-venv "no python3 with its venv module (for .venv: fpm, numpy, h5py, ...)." \
            " Provide Python >= 3.9 with venv and ensurepip (module load python)"
    fi
    command -v bc >/dev/null 2>&1 || optional+=(bc)       # postproc/make_figures.sh's timings
    [ "$mpi" = 1 ] || return 0
    if ! command -v mpirun >/dev/null 2>&1; then
        echo "mpirun: command not found" > "$tmp/log"; false
    else
        probe link mpif90 mpi.f90 "${fflags[@]}" "${ldflags[@]}"
    fi || lack "libopenmpi-dev openmpi-bin" "no MPI (mpif90 with mpi_f08, mpirun): $(why)." \
              " Provide one (module load openmpi)"
    probe link mpif90 fftw_mpi.F90 "${fflags[@]}" -I/usr/include "${ldflags[@]}" -lfftw3_mpi -lfftw3 ||
        lack libfftw3-mpi-dev "FFTW's MPI library (fftw3-mpi.f03, libfftw3_mpi) not found with mpif90:" \
            " $(why). Provide FFTW built with MPI, pointed at as FFTW is (VESLIDE_FFTW_DIR)"
    if ! find_hdf5 mpi; then
        tried="${h5_tried[*]:-none (no VESLIDE_HDF5_MPI_DIR, no pkg-config entry, no h5pfc on PATH)}"
        lack libhdf5-openmpi-dev "a parallel HDF5 with Fortran not found; tried: $tried. Provide one" \
            " built with this MPI (module load hdf5 of the MPI flavour: its h5pfc on PATH is enough)" \
            " or export VESLIDE_HDF5_MPI_DIR=PREFIX"
    fi
}

probe_all
if ((${#missing[@]} + ${#optional[@]})) && command -v apt-get >/dev/null 2>&1; then
    sudo_=""
    if [ "$(id -u)" -ne 0 ]; then
        if command -v sudo >/dev/null 2>&1; then sudo_=sudo
        else echo "veslide setup: apt-get needs root (no sudo here) to install ${packages[*]} ${optional[*]}" >&2
        fi
    fi
    if [ "$(id -u)" -eq 0 ] || [ -n "$sudo_" ]; then
        echo "veslide setup: installing ${packages[*]} ${optional[*]} (apt-get)"
        { $sudo_ apt-get update -qq &&
          DEBIAN_FRONTEND=noninteractive $sudo_ apt-get install -y -qq --no-install-recommends \
              "${packages[@]}" "${optional[@]}" >/dev/null; } || echo "veslide setup: apt-get failed" >&2
        probe_all
    fi
fi
if ((${#optional[@]})); then
    echo "veslide setup: note: no ${optional[*]} (only postproc/make_figures.sh's timings need it)" >&2
fi
if ((${#missing[@]})); then
    for m in "${missing[@]}"; do echo "veslide setup: $m" >&2; done
    echo "veslide setup: docs/install.md says how each is provided and found" >&2
    exit 1
fi

py_pkgs=(fpm==0.12.0 numpy h5py matplotlib pandas xarray f90nml pytest scipy openpyxl "SurfaceTopography>=1.27"
         "ContactMechanics>=1.8.3")
if [ ! -x .venv/bin/python ]; then
    echo "veslide setup: creating .venv"
    "$python3_" -m venv .venv
fi
# One interpreter start, no imports (find_spec only): 0 all present, 1 packages missing,
# 2 the Python package veslide missing or installed from another checkout (the venv may be shared).
state=0
.venv/bin/python - "$root/python" <<'PY' 2>/dev/null || state=$?
import importlib.util, pathlib, sys
if not all(importlib.util.find_spec(m) for m in ("numpy", "h5py", "matplotlib", "pandas", "xarray", "f90nml", "pytest",
                                                 "scipy", "openpyxl", "SurfaceTopography", "ContactMechanics")):
    sys.exit(1)
spec = importlib.util.find_spec("veslide")
here = pathlib.Path(sys.argv[1]).resolve()
sys.exit(0 if spec and spec.origin and pathlib.Path(spec.origin).resolve().parent.parent == here else 2)
PY
if [ "$state" = 1 ] || [ ! -x .venv/bin/fpm ]; then
    echo "veslide setup: installing ${py_pkgs[*]} into .venv"
    .venv/bin/pip install -q --disable-pip-version-check "${py_pkgs[@]}"
    state=2
fi
if [ "$state" != 0 ]; then
    echo "veslide setup: installing the Python package python/ (editable) into .venv"
    .venv/bin/pip install -q --disable-pip-version-check --no-deps -e python
fi
