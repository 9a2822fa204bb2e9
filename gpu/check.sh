#!/usr/bin/env bash
# The device checks, for a machine with a GPU (a few minutes):
#  1. the suite 'device': every device pass against its CPU twin on random data (1e-13 relative),
#     cuFFT against FFTW, the dense references and the 29 hard cases solved on the device, the
#     device against the CPU on the same cases (pressure, area, friction, lateral force to 1e-10;
#     FFT pairs within 2 %), a solve repeated bit for bit, the refusals, the memory given back;
#  2. every other Fortran suite, with 'auto' (so on the device wherever the method runs there);
#  3. with compute-sanitizer (when the machine has it), the passes against their twins again under
#     its memory checker.
#   bash gpu/check.sh [BIN]   BIN: the folder of veslide-tests (default: built by gpu/build.sh)
# Prints each suite's results and ends with "device check: N suites passed, M failed".
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
if [ -n "${1:-}" ]; then
    tests="$1/veslide-tests"
else
    tests=$(bash gpu/build.sh veslide-tests) || exit 1
fi
suites=(device rng grid fftw threads material kernel surface contact anderson solver-pk solver-dr solver-bccg
        solver-pdr analysis anisotropy persson quantities hdf5 config config-grid config-surface config-material
        config-load config-motion config-solver config-analysis config-sweep config-output topography output case
        study hard solver-gcg)
passed=0; failed=0; failures=()
for s in "${suites[@]}"; do
    if "$tests" "$s"; then passed=$((passed + 1)); else failed=$((failed + 1)); failures+=("$s"); fi
done
if command -v compute-sanitizer >/dev/null 2>&1; then
    for t in passes-shared passes-kernel-and-contact passes-bccg passes-pdr passes-dr-and-anderson passes-gcg \
             transform-against-fftw work-area-lent dense-visco-pdr adhesive-scenes-against-cpu; do
        if compute-sanitizer --tool memcheck --error-exitcode 3 "$tests" device "$t" > /tmp/memcheck.log 2>&1; then
            passed=$((passed + 1)); echo "memcheck $t: clean"
        else
            failed=$((failed + 1)); failures+=("memcheck:$t"); echo "memcheck $t: FAILED"; tail -30 /tmp/memcheck.log
        fi
    done
else
    echo "compute-sanitizer not found: the memory checker was not run"
fi
echo "device check: $passed suites passed, $failed failed${failures[*]:+ (${failures[*]})}"
[ "$failed" -eq 0 ]
