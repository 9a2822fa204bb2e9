#!/usr/bin/env python3
"""The figure of grid refinement in docs/validation.md, from the tables `veslide.refine` made.

usage: python postproc/plot_refinement.py [DEFAULT.csv] [BISINUSOID.csv] [OUT.png]
(defaults: docs/figures/refinement-default.csv, docs/figures/refinement-bisinusoid.csv,
docs/figures/refinement.png). Each table is a `Refinement.table` written with `to_csv`: the
default scene (inputs/default.nml, viscoelastic) refined from 256^2 to 2048^2, and the
bisinusoid of docs/validation.md from 32^2 to 8192^2 (drawn on the doubling grids from 128^2). Left: its contact
area, sub-cell and cell count; middle: its friction coefficient; right: the bisinusoid's area.
Error bars: the band of the finest grid; dashed: the extrapolated value.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

import veslide.plot as vp  # noqa: E402
from veslide.refinement import Refinement  # noqa: E402

UNITS = {"contact_area_fraction": "-", "contact_area_fraction_cells": "-", "mean_separation_m": "m",
         "friction_coefficient": "-", "lateral_force_ratio": "-"}


def main(default="docs/figures/refinement-default.csv", bisinusoid="docs/figures/refinement-bisinusoid.csv",
         out="docs/figures/refinement.png"):
    ref = Refinement.from_table(pd.read_csv(default, index_col="nx"), units=UNITS)
    bis_table = pd.read_csv(bisinusoid, index_col="nx")
    doubling = [n for n in bis_table.index if n >= 128 and n & (n - 1) == 0]      # 128, 256, ... 8192
    bis = Refinement.from_table(bis_table.loc[doubling], units=UNITS)
    with vp.paper_style():
        fig, axs = plt.subplots(1, 3, figsize=(11, 3.5), constrained_layout=True)
        for ax, r, title in ((axs[0], ref, "inputs/default.nml (viscoelastic)"),
                             (axs[2], bis, "bisinusoid, p/p* = 0.1 (elastic)")):
            vp.refinement(r, "contact_area_fraction", ax, label="sub-cell")
            vp.refinement(r, "contact_area_fraction_cells", ax, label="cell count", marker="s")
            ax.set_ylabel("contact area fraction")
            ax.set_title(title, fontsize="small")
            ax.legend(fontsize="small")
        vp.refinement(ref, "friction_coefficient", axs[1])
        band = ref.estimate.loc["friction_coefficient", "error"]
        axs[1].set_title("inputs/default.nml: friction, band %.1e" % band, fontsize="small")
        fig.savefig(out, dpi=120)
    print("wrote", out)


if __name__ == "__main__":
    main(*sys.argv[1:])
