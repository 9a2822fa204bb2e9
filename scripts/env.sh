# veslide's build and run environment, sourced (never run) by dev.sh, scripts/setup.sh and the
# mpi/ scripts, or by hand in a shell:   source scripts/env.sh
# - PATH: .venv/bin first (fpm, python, and the veslide and veslide-bench that ./dev.sh links there)
# - PKG_CONFIG_PATH: .venv/veslide/pkgconfig first, where scripts/setup.sh names the HDF5 it found
#   to fpm's hdf5 metapackage (hdf5_hl_fortran.pc, the first name fpm looks up)
# - FPM_FFLAGS, FPM_CFLAGS, FPM_LDFLAGS (fpm's own variables, kept as given) extended by the
#   prefixes VESLIDE_FFTW_DIR and VESLIDE_LAPACK_DIR: -I PREFIX/include, -L and -Wl,-rpath for
#   PREFIX/lib64 and PREFIX/lib (HDF5's prefix, VESLIDE_HDF5_DIR, goes through the pkg-config file)
# Sourcing it twice changes nothing more. Nothing is probed or installed here (scripts/setup.sh).
veslide_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
case ":$PATH:" in
    *":$veslide_root/.venv/bin:"*) ;;
    *) PATH="$veslide_root/.venv/bin:$PATH" ;;
esac
case ":${PKG_CONFIG_PATH:-}:" in
    *":$veslide_root/.venv/veslide/pkgconfig:"*) ;;
    *) PKG_CONFIG_PATH="$veslide_root/.venv/veslide/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}" ;;
esac
export PATH PKG_CONFIG_PATH

# $1: name of a flags variable, $2: a flag to append unless it is there already
veslide_add_flag() {
    case " ${!1:-} " in
        *" $2 "*) ;;
        *) printf -v "$1" '%s' "${!1:+${!1} }$2"; export "${1?}" ;;
    esac
}
for veslide_prefix in "${VESLIDE_FFTW_DIR:-}" "${VESLIDE_LAPACK_DIR:-}"; do
    [ -n "$veslide_prefix" ] || continue
    if [ -d "$veslide_prefix/include" ]; then
        veslide_add_flag FPM_FFLAGS "-I$veslide_prefix/include"
        veslide_add_flag FPM_CFLAGS "-I$veslide_prefix/include"
    fi
    for veslide_lib in "$veslide_prefix/lib64" "$veslide_prefix/lib"; do
        if [ -d "$veslide_lib" ]; then
            veslide_add_flag FPM_LDFLAGS "-L$veslide_lib"
            veslide_add_flag FPM_LDFLAGS "-Wl,-rpath,$veslide_lib"
        fi
    done
done
unset -f veslide_add_flag
unset veslide_prefix veslide_lib
