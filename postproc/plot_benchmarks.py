#!/usr/bin/env python3
"""Plots of `veslide-bench accuracy` (results/bench-accuracy.csv), drawn in the paper style
(veslide.plot.paper_style: 7 in across, 8 pt text) as a PNG at 300 dpi.

usage: python postproc/plot_benchmarks.py [results/bench-accuracy.csv] [docs/figures/accuracy.png]
Left: the relative error of area, separation and friction against the solver tolerance (errors
with respect to a 1e-13 solution), and the solve time (dashed, right axis). Right: the relative
change of area (solid) and friction (dotted) from the next coarser grid against the grid size,
one colour per kernel variant. The table is a measurement: this script only draws it.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

import veslide.plot as vp  # noqa: E402

PAGE = 7.0                         # width [in] across a journal page, as postproc/make_figures.py
KERNELS = (("spectral", "o"), ("collocation", "s"), ("collocation-alias", "^"), ("galerkin", "d"))


def main(src="results/bench-accuracy.csv", out="docs/figures/accuracy.png"):
    with open(src, newline="") as fh:
        rows = list(csv.DictReader(fh))
    tol = [r for r in rows if r["study"] == "tolerance"]
    grid = [r for r in rows if r["study"] == "grid"]
    with vp.paper_style():
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(PAGE, 2.9))
        t = [float(r["tolerance"]) for r in tol]
        for key, label in (("d_area", "area"), ("d_separation", "separation"), ("d_friction", "friction")):
            ax1.loglog(t, [max(float(r[key]), 1e-17) for r in tol], "o-", ms=3, label=label)
        ax1.set_xlabel("solver tolerance")
        ax1.set_ylabel("relative error against 1e-13")
        ax1b = ax1.twinx()
        ax1b.semilogx(t, [float(r["seconds"]) for r in tol], "k--", lw=0.9, label="solve time (right)")
        ax1b.set_ylabel("solve time [s]")
        ax1.invert_xaxis()
        h1, l1 = ax1.get_legend_handles_labels()
        h2, l2 = ax1b.get_legend_handles_labels()
        ax1.legend(h1 + h2, l1 + l2, loc="upper center", bbox_to_anchor=(0.5, -0.22), ncol=2)
        ax1.set_title(r"solver tolerance, 256$^2$")
        sizes = set()
        for k, (kernel, marker) in enumerate(KERNELS):
            rs = [r for r in grid if r["kernel"] == kernel and int(r["n"]) > 128]
            if not rs:
                continue
            n = [int(r["n"]) for r in rs]
            sizes.update(n)
            c = "C%d" % k
            ax2.loglog(n, [float(r["d_area"]) for r in rs], marker + "-", color=c, ms=3, label=kernel)
            ax2.loglog(n, [float(r["d_friction"]) for r in rs], marker + ":", color=c, ms=3, mfc="white")
        sizes = sorted(sizes)
        ax2.set_xticks(sizes, [str(k) for k in sizes])
        ax2.minorticks_off()
        ax2.set_xlabel(r"grid $n$ ($n \times n$)")
        ax2.set_ylabel(r"relative change from $n/2$")
        ax2.set_title("grid refinement, tolerance 1e-10")
        h, l = ax2.get_legend_handles_labels()
        h += [Line2D([], [], color="0.3", ls="-"), Line2D([], [], color="0.3", ls=":", marker="o", mfc="white", ms=3)]
        l += ["area", "friction"]
        ax2.legend(h, l, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
        vp.save(fig, out, formats=("png",))
        plt.close(fig)
    print("wrote", out)


if __name__ == "__main__":
    main(*sys.argv[1:])
