#!/usr/bin/env bash
# Pack the GPU build for a machine that has a GPU but no compilers (the device machine): the
# programs veslide, veslide-bench and veslide-tests with every shared library they need from here
# (gfortran's runtime, FFTW, HDF5, LAPACK, libveslide_device.so) into gpu/dist/{bin,lib}, ignored
# by git. The C library and the CUDA libraries are the machine's own (gpu/remote.sh finds them).
#   bash gpu/pack.sh          prints the folder and its size
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
mapfile -t programs < <(bash gpu/build.sh --paths)
dist="$root/gpu/dist"
rm -rf "$dist"; mkdir -p "$dist/bin" "$dist/lib"
for p in "${programs[@]}"; do cp "$p" "$dist/bin/"; done
skip='^(linux-vdso|libc\.so|libm\.so|libmvec|libpthread|libdl\.so|librt\.so|libresolv|ld-linux|libstdc\+\+|libgcc_s|libcudart|libcufft|libcuda\.so)'
for p in "${programs[@]}"; do
    ldd "$p" | awk '/=> \// {print $1, $3}' | while read -r name path; do
        if [[ ! "$name" =~ $skip ]]; then cp -L -n "$path" "$dist/lib/" 2>/dev/null || true; fi
    done
done
echo "$dist ($(du -sh "$dist" | cut -f1))"
