#!/usr/bin/env bash
# The GPU build of veslide: the device passes (src/**/veslide_*.cu) compiled with nvcc and linked,
# with cuFFT and the CUDA runtime, into the release build of the programs (the Fortran compiled
# with -DVESLIDE_CUDA). Built where no GPU is visible it runs on the CPU, and says so once.
#
#   bash gpu/build.sh [--emulate] [PROGRAM]     build; print the path of PROGRAM (veslide,
#                                               veslide-bench or veslide-tests; default veslide);
#                                               without --emulate, veslide and veslide-bench are
#                                               linked into .venv/bin (the programs on the venv's
#                                               PATH and the one Python runs; ./dev.sh links the
#                                               CPU build back)
#   bash gpu/build.sh [--emulate] test [ARGS]   build and run the Fortran suite (ARGS: suite, test)
#   bash gpu/build.sh [--emulate] --paths       build; print the three programs' paths
#   bash gpu/build.sh [--emulate] --flags       only the device library; print the Fortran
#                                               defines and the link flags (mpi/build.sh --gpu)
#
# --emulate compiles the same .cu sources as host C++ (-DVESLIDE_EMULATE): the "emulated device",
# which runs every device pass on the host in the GPU's order of summation, with FFTW in place of
# cuFFT. It needs no CUDA at all; the tests of the device path run on it where there is no GPU.
#
# Where nvcc comes from: $CUDA_HOME/bin/nvcc when CUDA_HOME is set (a cluster's CUDA: `module load
# cuda`, then CUDA_HOME=$CUDA_HOME or $CUDA_PATH), else PyPI's CUDA 13.0 wheels, installed into
# the project's .venv when missing (~700 MB). Machine code is built for $VESLIDE_CUDA_ARCH
# (default "80 90": A100 and H100/H200); add 100 for Blackwell with a CUDA that has it.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
cd "$root"
emulate=0
if [ "${1:-}" = --emulate ]; then emulate=1; shift; fi
bash scripts/setup.sh >&2
source scripts/env.sh     # .venv/bin on PATH, the HDF5 that setup.sh found (serial), library prefixes

sources=(src/core/veslide_device.cu src/grid/veslide_transform.cu src/grid/veslide_passes.cu
         src/physics/veslide_kernel_passes.cu src/contact/veslide_contact_passes.cu
         src/contact/veslide_bccg_passes.cu src/contact/veslide_pdr_passes.cu src/contact/veslide_dr_passes.cu
         src/contact/veslide_anderson_passes.cu src/contact/veslide_gcg_passes.cu)

if [ "$emulate" = 1 ]; then
    mode=emulate
    compile() { g++ -std=c++17 -O2 -fopenmp -ffp-contract=off -fPIC -DVESLIDE_EMULATE -x c++ -c "$1" -o "$2"; }
    device_libs="-lfftw3 -fopenmp"
    defines="-DVESLIDE_CUDA -DVESLIDE_DEVICE_EMULATED"
else
    mode=cuda
    if [ -n "${CUDA_HOME:-}" ] && [ -x "$CUDA_HOME/bin/nvcc" ]; then
        nvcc="$CUDA_HOME/bin/nvcc"
        libdir="$CUDA_HOME/lib64"; [ -d "$libdir" ] || libdir="$CUDA_HOME/lib"
        cudart="-L$libdir -lcudart"; cufft="-lcufft"
    else
        site=$(.venv/bin/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
        cu="$site/nvidia/cu13"
        if [ ! -x "$cu/bin/nvcc" ] || [ ! -e "$cu/lib/libcufft.so.12" ] || [ ! -e "$cu/lib/libcudart.so.13" ]; then
            echo "veslide gpu build: installing CUDA 13.0's nvcc, runtime and cuFFT from PyPI into .venv" >&2
            # (the compiler's parts pinned with it: unpinned, pip takes a newer nvvm whose PTX
            # this ptxas refuses)
            .venv/bin/pip install -q --disable-pip-version-check "nvidia-cuda-nvcc==13.0.*" "nvidia-nvvm==13.0.*" \
                "nvidia-cuda-crt==13.0.*" "nvidia-nvjitlink==13.0.*" "nvidia-cuda-runtime==13.0.*" \
                "nvidia-cufft==12.0.*" >&2
        fi
        nvcc="$cu/bin/nvcc"; libdir="$cu/lib"
        # the wheels hold only versioned libraries: link them by file name
        cudart="$libdir/libcudart.so.13"; cufft="$libdir/libcufft.so.12"
    fi
    gencode=()
    for a in ${VESLIDE_CUDA_ARCH:-80 90}; do gencode+=(-gencode "arch=compute_$a,code=sm_$a"); done
    compile() { "$nvcc" -std=c++17 -O3 --fmad=false "${gencode[@]}" -Xcompiler -fPIC,-fopenmp -c "$1" -o "$2"; }
    device_libs="$cufft $cudart -Wl,-rpath,$libdir -fopenmp"
    defines="-DVESLIDE_CUDA"
fi

# The device objects become one shared library, libveslide_device.so, that the programs load:
# fpm puts link flags before the objects, where a static archive would not be searched, and
# a shared library is found whatever the order (and needs no relink when it is rebuilt).
obj="$root/build/device-$mode"
mkdir -p "$obj"
objects=()
changed=0
for s in "${sources[@]}"; do
    o="$obj/$(basename "${s%.cu}").o"
    if [ ! -e "$o" ] || [ "$s" -nt "$o" ] || [ src/core/veslide_device.cuh -nt "$o" ] ||
       [ src/contact/veslide_contact_law.cuh -nt "$o" ]; then
        echo "veslide gpu build: compiling $s ($mode)" >&2
        compile "$s" "$o"
        changed=1
    fi
    objects+=("$o")
done
lib="$obj/libveslide_device.so"
if [ "$changed" = 1 ] || [ ! -e "$lib" ]; then
    g++ -shared -o "$lib" "${objects[@]}" $device_libs
fi

link="-L$obj -Wl,--no-as-needed -lveslide_device -Wl,-rpath,$obj -lstdc++"
if [ "${1:-}" = --flags ]; then
    echo "$defines"; echo "$link"; exit 0
fi
flags=(--profile release --flag "$defines" --link-flag "$link")
paths() {
    fpm run "${flags[@]}" veslide --runner echo 2>/dev/null | tail -1
    fpm run "${flags[@]}" veslide-bench --runner echo 2>/dev/null | tail -1
    fpm test "${flags[@]}" --runner echo 2>/dev/null | tail -1
}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# fpm 0.12 keeps objects per compiler flags but the library archive per all flags, and does not
# re-archive when the objects were compiled by another build with other link flags (the CPU, GPU
# and emulated builds here): the archives and the programs are made anew every time (seconds)
# (nor does it recompile the test and program sources when a library module they use changed:
# their objects are made anew too)
rm -f build/gfortran_*/veslide/libveslide.a build/gfortran_*/veslide/test_*.o build/gfortran_*/veslide/app_*.o \
      build/gfortran_*/veslide/bench_*.o
for p in $(paths 2>/dev/null); do rm -f "$p"; done
fpm build "${flags[@]}" --tests >"$log" 2>&1 || { cat "$log" >&2; exit 1; }

what=${1:-veslide}
case "$what" in
    test)
        shift
        # the environment ./dev.sh test gives the suite (the figure scripts' Python, no display)
        export VESLIDE_PYTHON="$root/.venv/bin/python" MPLBACKEND=Agg OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
        exec fpm test "${flags[@]}" -- "$@"
        ;;
    --paths)
        for p in $(paths); do echo "$root/$p"; done
        ;;
    veslide|veslide-bench)
        exe="$root/$(fpm run "${flags[@]}" veslide --runner echo 2>/dev/null | tail -1)"
        if [ "$emulate" = 0 ]; then
            # the GPU build becomes the one on the venv's PATH and the one Python runs, as ./dev.sh
            # makes its CPU build (./dev.sh run and ./dev.sh test link the CPU build back)
            ln -sfn "$exe" "$root/.venv/bin/veslide"
            ln -sfn "$(dirname "$exe")/veslide-bench" "$root/.venv/bin/veslide-bench"
            echo "veslide gpu build: .venv/bin/veslide and veslide-bench now run this GPU build (source" \
                 ".venv/bin/activate; Python's veslide.run finds it there unless VESLIDE_EXE or another veslide on" \
                 "PATH comes first: VESLIDE_EXE=$exe runs it from anywhere); ./dev.sh run or test links the CPU" \
                 "build back" >&2
        fi
        echo "$root/$(fpm run "${flags[@]}" "$what" --runner echo 2>/dev/null | tail -1)"
        ;;
    veslide-tests)
        echo "$root/$(fpm test "${flags[@]}" --runner echo 2>/dev/null | tail -1)"
        ;;
    *)
        echo "usage: bash gpu/build.sh [--emulate] [veslide | veslide-bench | veslide-tests | --paths | test [ARGS]]" >&2
        exit 2
        ;;
esac
