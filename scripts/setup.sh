#!/usr/bin/env bash
# Install what veslide needs on Debian 12, idempotently: apt packages, then a project-local
# Python venv (.venv) holding fpm, the post-processing and test packages, and this checkout's
# Python package (python/, editable). Fast when nothing is missing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

apt_pkgs=(gfortran pkg-config make bc libfftw3-dev liblapack-dev libblas-dev libhdf5-dev hdf5-tools
          libopenmpi-dev openmpi-bin libfftw3-mpi-dev libhdf5-openmpi-dev python3-venv)
missing=()
for p in "${apt_pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
    echo "veslide setup: installing ${missing[*]}"
    sudo_=""; [ "$(id -u)" -ne 0 ] && sudo_="sudo"
    $sudo_ apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo_ apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Installing the parallel HDF5 points Debian's pkg-config alias 'hdf5' at it (alternatives, auto mode);
# the serial build resolves HDF5 through that alias, so it is pinned to the serial library (the
# MPI build names the parallel one itself, mpi/pkgconfig). Only when it is not pinned already.
serial_pc=/usr/lib/x86_64-linux-gnu/pkgconfig/hdf5-serial.pc
if [ -e "$serial_pc" ] && [ "$(readlink -f /usr/lib/x86_64-linux-gnu/pkgconfig/hdf5.pc)" != "$serial_pc" ]; then
    echo "veslide setup: pointing pkg-config's 'hdf5' at the serial HDF5 (update-alternatives)"
    sudo_=""; [ "$(id -u)" -ne 0 ] && sudo_="sudo"
    $sudo_ update-alternatives --quiet --set hdf5.pc "$serial_pc"
fi

py_pkgs=(fpm==0.12.0 numpy h5py matplotlib pandas xarray f90nml pytest)
if [ ! -x .venv/bin/python ]; then
    echo "veslide setup: creating .venv"
    /usr/bin/python3 -m venv .venv
fi
# One interpreter start, no imports (find_spec only): 0 all present, 1 packages missing,
# 2 the Python package veslide missing or installed from another checkout (the venv may be shared).
state=0
.venv/bin/python - "$root/python" <<'PY' 2>/dev/null || state=$?
import importlib.util, pathlib, sys
if not all(importlib.util.find_spec(m) for m in ("numpy", "h5py", "matplotlib", "pandas", "xarray", "f90nml", "pytest")):
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
