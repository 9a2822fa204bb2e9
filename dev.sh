#!/usr/bin/env bash
# veslide's two set-up commands (see README.md); both install what is missing first.
#   ./dev.sh run  [FILE.nml] [veslide options]   build and run a case (default: inputs/default.nml)
#   ./dev.sh test [SUITE [TEST]]                 build and run the test suite
#   ./dev.sh bench [ARGS]                         build and run the benchmark program
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cd "$root"
bash scripts/setup.sh
export PATH="$root/.venv/bin:$PATH"
rev=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
if [ "$rev" != unknown ] && [ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ]; then
    rev="$rev-dirty"
fi
export VESLIDE_GIT_REVISION="$rev"
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
export VESLIDE_PYTHON="$root/.venv/bin/python"   # the figure scripts, run by the postproc test
export MPLBACKEND=Agg
profile=(--profile release)
cmd="${1:-run}"; shift || true
case "$cmd" in
    run)
        if [ $# -eq 0 ] || [[ "$1" == -* ]]; then set -- inputs/default.nml "$@"; fi
        mkdir -p results
        fpm run "${profile[@]}" veslide -- "$@"
        ;;
    test)
        fpm test "${profile[@]}" -- "$@"
        ;;
    bench)
        fpm run "${profile[@]}" veslide-bench -- "$@"
        ;;
    *)
        echo "usage: ./dev.sh run [FILE.nml] | test [SUITE [TEST]] | bench [ARGS]" >&2; exit 2
        ;;
esac
