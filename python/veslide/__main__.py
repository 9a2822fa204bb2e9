"""python -m veslide refine NAMELIST NX NX NX ... [--output-dir DIR] [--threads N]

Runs one case on several grids (or reuses the files already there from the same input) and prints
the table and the error estimate of `veslide.refine`; exit status 1 on bad input, 2 when a solve
did not converge (as the program's)."""
import argparse
import sys
import warnings

import pandas as pd

from .refinement import refine
from .runner import ConvergenceWarning, InputError


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m veslide")
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("refine", help="run one case on several grids and estimate the discretisation error "
                                      "of its scalars")
    r.add_argument("namelist", help="the case's namelist file (one case: no &sweep)")
    r.add_argument("sizes", nargs="+", type=int, help="nx of each grid (ny scaled with it)")
    r.add_argument("--output-dir", default="refine", help="where refine-NXxNY.h5 go (default: ./refine)")
    r.add_argument("--threads", type=int, default=None, help="OMP_NUM_THREADS of each run")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore", ConvergenceWarning)       # the exit status and the notes say it
    try:
        ref = refine(args.namelist, args.sizes, args.output_dir, threads=args.threads, progress=None)
    except (InputError, ValueError, FileNotFoundError, FileExistsError) as e:
        print("veslide refine: %s" % (getattr(e, "message", None) or e), file=sys.stderr)
        return 1
    with pd.option_context("display.width", 200, "display.max_columns", 20, "display.max_colwidth", 90):
        print(ref.table.to_string())
        print()
        print(ref.estimate.to_string())
    return 0 if ref.converged else 2      # as the program: 2 when a solve did not converge


if __name__ == "__main__":
    raise SystemExit(main())
