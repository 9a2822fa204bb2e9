#!/usr/bin/env python3
"""The figure of grid refinement in docs/validation.md, from the tables `veslide.refine` made.

usage: python postproc/plot_refinement.py [DEFAULT.csv] [BISINUSOID.csv] [OUT.png]
(defaults: docs/figures/refinement-default.csv, docs/figures/refinement-bisinusoid.csv,
docs/figures/refinement.png). Each table is a `Refinement.table` written with `to_csv`: the
default scene (inputs/default.nml, viscoelastic) refined from 256^2 to 2048^2, and the
bisinusoid of docs/validation.md from 32^2 to 8192^2 (drawn on the doubling grids from 128^2). Left: its contact
area, sub-cell and cell count; middle: its friction coefficient; right: the bisinusoid's area.
Error bars: the band of the finest grid; dashed: the extrapolated value. Drawn in the paper style
(veslide.plot.paper_style: 7 in across, 8 pt text), PNG at 300 dpi; the tables are measurements,
this script only draws them.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

import veslide.plot as vp  # noqa: E402
from veslide.refinement import Refinement  # noqa: E402

UNITS = {"contact_area_fraction": "-", "contact_area_fraction_cells": "-", "mean_separation_m": "m",
         "friction_coefficient": "-", "lateral_force_ratio": "-"}


PAGE = 7.0                          # width [in] across a journal page, as postproc/make_figures.py


def main(default="docs/figures/refinement-default.csv", bisinusoid="docs/figures/refinement-bisinusoid.csv",
         out="docs/figures/refinement.png"):
    ref = Refinement.from_table(pd.read_csv(default, index_col="nx"), units=UNITS)
    bis_table = pd.read_csv(bisinusoid, index_col="nx")
    doubling = [n for n in bis_table.index if n >= 128 and n & (n - 1) == 0]      # 128, 256, ... 8192
    bis = Refinement.from_table(bis_table.loc[doubling], units=UNITS)
    with vp.paper_style():
        fig, axs = plt.subplots(1, 3, figsize=(PAGE, 2.5))
        for ax, r, title in ((axs[0], ref, "default scene: contact area"),
                             (axs[2], bis, "bisinusoid: contact area")):
            vp.refinement(r, "contact_area_fraction", ax, label="sub-cell", ms=3)
            vp.refinement(r, "contact_area_fraction_cells", ax, label="cell count", marker="s", ms=3)
            ax.set_ylabel(r"$A/A_0$")
            ax.set_title(title)
            ax.legend(loc="upper right")
        vp.refinement(ref, "friction_coefficient", axs[1], ms=3)
        axs[1].set_ylabel(r"friction $\mu$")
        axs[1].set_title("default scene: friction")
        for ax in axs:
            ax.ticklabel_format(axis="y", useOffset=False)
        vp.save(fig, out, formats=("png",))
        plt.close(fig)
    print("wrote", out)


if __name__ == "__main__":
    main(*sys.argv[1:])
