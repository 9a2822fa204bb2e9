#!/usr/bin/env bash
# Build the MPI programs with the MPI compiler wrapper, FFTW's MPI transforms and parallel HDF5,
# and print the path of one: `bash mpi/build.sh [veslide-batch | veslide-bench-mpi]` (default
# veslide-batch); `bash mpi/build.sh test [ARGS]` runs the distributed checks instead (ARGS go to
# fpm test, e.g. --runner "mpirun -n 3").
# What MPI needs is found, or installed where apt-get can, by `scripts/setup.sh --mpi` (only the
# MPI scripts need MPI); it names the parallel HDF5 it found in .venv/veslide/pkgconfig-mpi, put
# first on PKG_CONFIG_PATH here (the serial build keeps its serial HDF5). The library is compiled
# with -DVESLIDE_MPI (its distributed code paths); -I/usr/include lets FFTW's fftw3-mpi.f03 find
# the fftw3.f03 it includes (elsewhere VESLIDE_FFTW_DIR's include directory, in FPM_FFLAGS).
# `--gpu` (or `--gpu-emulate`) first builds it with the device backend too (gpu/build.sh): each
# rank of a study then solves on the device rank modulo the number visible.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
# (mpi/check.sh runs the set-up once for its many builds)
[ "${VESLIDE_SETUP_DONE:-}" = mpi ] || bash "$root/scripts/setup.sh" --mpi >&2
source "$root/scripts/env.sh"
export PKG_CONFIG_PATH="$root/.venv/veslide/pkgconfig-mpi:$PKG_CONFIG_PATH"
# (an explicit --flag or --link-flag replaces fpm's FPM_FFLAGS or FPM_LDFLAGS: they are passed on)
fflags="-DVESLIDE_MPI -I/usr/include${FPM_FFLAGS:+ $FPM_FFLAGS}"
flags=(--profile release --compiler mpif90 --flag "$fflags")
if [ "${1:-}" = --gpu ] || [ "${1:-}" = --gpu-emulate ]; then
    mapfile -t device < <(bash "$root/gpu/build.sh" $([ "$1" = --gpu-emulate ] && echo --emulate) --flags)
    flags=(--profile release --compiler mpif90 --flag "$fflags ${device[0]}"
           --link-flag "${device[1]}${FPM_LDFLAGS:+ $FPM_LDFLAGS}")
    shift
fi
cd "$here"
if [ "${1:-}" = "test" ]; then
    shift
    exec fpm test "${flags[@]}" "$@"
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
fpm build "${flags[@]}" >"$log" 2>&1 || { cat "$log" >&2; exit 1; }
echo "$here/$(fpm run "${flags[@]}" "${1:-veslide-batch}" --runner echo 2>/dev/null | tail -1)"
