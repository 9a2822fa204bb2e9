#!/usr/bin/env bash
# veslide's two set-up commands (see README.md); both install what is missing first.
#   ./dev.sh run  [FILE.nml] [veslide options]   build and run a case (default: inputs/default.nml)
#   ./dev.sh test [SUITE [TEST]]                 build and run the test suite (Fortran, then Python)
#   ./dev.sh test python [PYTEST ARGS]           the Python package's tests only
#   ./dev.sh bench [ARGS]                         build and run the benchmark program
set -euo pipefail
caller=$PWD
root=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cd "$root"
bash scripts/setup.sh
source scripts/env.sh               # .venv/bin on PATH, the HDF5 setup.sh found, library prefixes
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

# The release build of the veslide program (absolute path), built when out of date; veslide and
# veslide-bench are linked into .venv/bin (source .venv/bin/activate puts them on PATH)
veslide_exe() {
    local exe
    fpm build "${profile[@]}" >&2 || return 1
    exe="$root/$(fpm run "${profile[@]}" veslide --runner echo 2>/dev/null | tail -1)"
    ln -sfn "$exe" "$root/.venv/bin/veslide"
    ln -sfn "$(dirname "$exe")/veslide-bench" "$root/.venv/bin/veslide-bench"
    echo "$exe"
}

# pytest on python/tests against this checkout's build; writes "python: N passed, N failed" to $1
python_tests() {
    local out=$1 log status=0 line passed failed n
    shift
    log=$(mktemp)
    (cd "$root/python" && VESLIDE_EXE="$exe" "$root/.venv/bin/python" -m pytest -q -p no:cacheprovider "$@") \
        2>&1 | tee "$log" || status=$?
    line=$(grep -E '^=* ?[0-9]+ (passed|failed|error|skipped|errors|deselected)' "$log" | tail -1 || true)
    [ -n "$line" ] || line=$(tail -1 "$log")
    passed=$(grep -oE '[0-9]+ passed' <<<"$line" | grep -oE '[0-9]+' || echo 0)
    failed=0
    for n in $(grep -oE '[0-9]+ (failed|errors?)' <<<"$line" | grep -oE '[0-9]+' || true); do
        failed=$((failed + n))
    done
    rm -f "$log"
    [ "$status" -eq 0 ] || [ "${failed:-0}" -gt 0 ] || failed=1   # pytest failed without counting a test
    echo "python: ${passed:-0} passed, ${failed:-0} failed" > "$out"
    return "$status"
}

case "$cmd" in
    run)
        exe=$(veslide_exe)
        if [ $# -eq 0 ] || [[ "$1" == -* ]]; then
            # the default scene, in the repository (its &output file is results/default.h5);
            # an --output path is still the caller's
            args=()
            while [ $# -gt 0 ]; do
                args+=("$1")
                if [[ "$1" == -o || "$1" == --output ]] && [ $# -gt 1 ]; then
                    shift
                    if [[ "$1" == /* ]]; then args+=("$1"); else args+=("$caller/$1"); fi
                fi
                shift
            done
            mkdir -p results
            "$exe" inputs/default.nml ${args[@]+"${args[@]}"}
        else
            # the caller's namelist: every relative path (the file, --output, &output file,
            # &surface file) is the caller's, as when the program is run directly
            cd "$caller"
            "$exe" "$@"
        fi
        ;;
    test)
        exe=$(veslide_exe)
        # fpm 0.12 does not recompile a test whose library modules changed (gpu/build.sh says
        # more): test objects older than the newest library source are made anew
        newest=$(ls -t src/*/*.f90 src/*/*.F90 | head -1)
        find build -path '*/veslide/test_*.o' ! -newer "$newest" -delete 2>/dev/null || true
        if [ "${1:-}" = python ]; then
            shift
            summary=$(mktemp)
            trap 'rm -f "$summary"' EXIT
            pstatus=0
            python_tests "$summary" "$@" || pstatus=$?
            cat "$summary"
            exit "$pstatus"
        fi
        if [ $# -gt 0 ]; then                          # one Fortran suite or test: no pytest
            fpm test "${profile[@]}" -- "$@"
            exit
        fi
        log=$(mktemp -d)
        trap 'rm -rf "$log"' EXIT
        fstatus=0; pstatus=0
        fpm test "${profile[@]}" | tee "$log/fortran" || fstatus=$?
        python_tests "$log/python" || pstatus=$?
        fline=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$log/fortran" | tail -1 || true)
        [ -n "$fline" ] || { fline="0 passed, 1 failed"; echo "fortran: the suite did not finish"; }
        pline=$(tail -1 "$log/python" | sed 's/^python: //')
        fp=${fline%% *}; ff=$(grep -oE '[0-9]+ failed' <<<"$fline"); ff=${ff%% *}
        pp=${pline%% *}; pf=$(grep -oE '[0-9]+ failed' <<<"$pline"); pf=${pf%% *}
        echo "fortran: $fline"
        echo "python: $pline"
        echo "$((fp + pp)) passed, $((ff + pf)) failed"
        [ "$fstatus" -eq 0 ] && [ "$pstatus" -eq 0 ]
        ;;
    bench)
        fpm run "${profile[@]}" veslide-bench -- "$@"
        ;;
    *)
        echo "usage: ./dev.sh run [FILE.nml] | test [SUITE [TEST] | python [PYTEST ARGS]] | bench [ARGS]" >&2; exit 2
        ;;
esac
