#!/usr/bin/env python3
"""Plots of `veslide-bench accuracy` (results/bench-accuracy.csv).

usage: python postproc/plot_benchmarks.py [results/bench-accuracy.csv] [docs/figures/accuracy.png]
Left: solver tolerance against time and the error of area, separation and friction with respect
to a 1e-13 solution. Right: grid size against the change of each quantity from the next coarser
grid, per kernel variant.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src="results/bench-accuracy.csv", out="docs/figures/accuracy.png"):
    with open(src, newline="") as fh:
        rows = list(csv.DictReader(fh))
    tol = [r for r in rows if r["study"] == "tolerance"]
    grid = [r for r in rows if r["study"] == "grid"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    t = [float(r["tolerance"]) for r in tol]
    for key, label in (("d_separation", "separation"), ("d_friction", "friction")):
        ax1.loglog(t, [max(float(r[key]), 1e-17) for r in tol], "o-", label=label + " error")
    ax1.set_xlabel("solver tolerance")
    ax1.set_ylabel("relative error vs 1e-13 solution")
    ax1b = ax1.twinx()
    ax1b.semilogx(t, [float(r["seconds"]) for r in tol], "k--", label="solve time")
    ax1b.set_ylabel("solve time [s] (dashed)")
    ax1.invert_xaxis()
    ax1.legend(loc="upper left")
    ax1.set_title("tolerance, 256^2, ratio 11, v tau/L0 = 0.13")
    for kernel, marker in (("spectral", "o"), ("collocation", "s"), ("collocation-alias", "^"), ("galerkin", "d")):
        rs = [r for r in grid if r["kernel"] == kernel and int(r["n"]) > 128]
        if not rs:
            continue
        n = [int(r["n"]) for r in rs]
        ax2.loglog(n, [float(r["d_area"]) for r in rs], marker + "-", label=kernel + ": area")
        ax2.loglog(n, [float(r["d_friction"]) for r in rs], marker + ":", label=kernel + ": friction")
    sizes = sorted({int(r["n"]) for r in grid if float(r["d_area"]) > 0})
    ax2.set_xticks(sizes, [str(k) for k in sizes])
    ax2.minorticks_off()
    ax2.set_xlabel("grid n (n x n)")
    ax2.set_ylabel("relative change from n/2")
    ax2.set_title("grid refinement, tolerance 1e-10")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main(*sys.argv[1:])
