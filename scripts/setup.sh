#!/usr/bin/env bash
# Install what veslide needs on Debian 12, idempotently: apt packages, then a project-local
# Python venv (.venv) holding fpm and the post-processing packages. Fast when nothing is missing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

apt_pkgs=(gfortran pkg-config make bc libfftw3-dev liblapack-dev libblas-dev libhdf5-dev hdf5-tools
          libopenmpi-dev openmpi-bin python3-venv)
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

py_pkgs=(fpm==0.12.0 numpy h5py matplotlib)
if [ ! -x .venv/bin/python ]; then
    echo "veslide setup: creating .venv"
    /usr/bin/python3 -m venv .venv
fi
if ! .venv/bin/python -c "import numpy, h5py, matplotlib" 2>/dev/null || [ ! -x .venv/bin/fpm ]; then
    echo "veslide setup: installing ${py_pkgs[*]} into .venv"
    .venv/bin/pip install -q --disable-pip-version-check "${py_pkgs[@]}"
fi
