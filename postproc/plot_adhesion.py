#!/usr/bin/env python3
"""Johnson's JKR wave solved by veslide, and its approach to the JKR curve as the range shrinks.

    python postproc/plot_adhesion.py [--out docs/figures]

A rigid wave h cos(2 pi x/lambda) (h = 1 um, lambda = 100 um) on an elastic half-space (E* = 10
MPa) with the exponential law, alpha = 0.2 (alpha^2 = 2 w lambda/(pi^2 E* h^2)), at loads
p/p* from -0.03 to 0.5 (p* = pi E* h/lambda), each a cold start (contact at the crest). The
range is held at 4 cells while the grid is refined (1024, 4096 and 16384 cells: rho/lambda =
3.9e-3, 9.8e-4, 2.4e-4), so the discrete range stays resolved as rho -> 0. Writes
adhesion-jkr.csv (one row a run: cells, range, load, contact half-width, deviation from JKR)
and adhesion-jkr.png: the loads against the half-width beside Johnson's curve
p/p* = sin^2(pi a) - alpha sqrt(tan(pi a)), and the largest deviation against rho/lambda.
"""
import argparse
import os
import tempfile

import numpy as np

import veslide

LAMBDA, AMP, E, ALPHA = 1.0e-4, 1.0e-6, 1.0e7, 0.2
PSTAR = np.pi*E*AMP/LAMBDA
W = ALPHA**2*np.pi**2*E*AMP**2/(2.0*LAMBDA)
LOADS = [-0.03, 0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5]
CELLS = [1024, 4096, 16384]


def jkr(a):
    return np.sin(np.pi*a)**2 - ALPHA*np.sqrt(np.tan(np.pi*a))


def solve(n, load, work):
    p = {"grid": {"nx": n, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/n},
         "surface": {"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
         "material": {"young_pa": E, "poisson": 0.0}, "load": {"mean_pressure_pa": load*PSTAR},
         "adhesion": {"law": "exponential", "energy_j_m2": W, "range_m": 4.0*LAMBDA/n},
         "solver": {"tolerance": 1e-9, "fft_planner": "estimate"}}
    r = veslide.run(p, output=os.path.join(work, f"jkr-{n}-{load}.h5"), progress=None)
    if r.scalars["converged"] != 1:
        raise RuntimeError(f"not converged: {n} cells, p/p* = {load}")
    return r.scalars["contact_area_fraction_cells"]/2.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join("docs", "figures"))
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for n in CELLS:
            for load in LOADS:
                a = solve(n, load, work)
                rows.append((n, 4.0/n, load, a, load - jkr(a)))
                print(f"{n:6d} cells  p/p* = {load:6.3f}  a/lambda = {a:.5f}  deviation {load - jkr(a):+.2e}",
                      flush=True)
    rows = np.array(rows)
    os.makedirs(args.out, exist_ok=True)
    np.savetxt(os.path.join(args.out, "adhesion-jkr.csv"), rows, delimiter=",", comments="",
               header="cells,range_over_wavelength,load_over_pstar,half_width_over_wavelength,deviation_over_pstar")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    a = np.linspace(1e-4, 0.4999, 2000)
    ax.plot(a, jkr(a), "k-", lw=1, label="JKR (Johnson 1995)")
    for n, marker in zip(CELLS, "osd"):
        m = rows[:, 0] == n
        ax.plot(rows[m, 3], rows[m, 2], marker, mfc="none", label=f"{n} cells, rho/lambda = {4.0/n:.1e}")
    ax.set_xlabel("contact half-width a/lambda")
    ax.set_ylabel("mean pressure p/p*")
    ax.set_ylim(-0.1, 0.6)
    ax.legend(fontsize=8)
    worst = [np.max(np.abs(rows[rows[:, 0] == n, 4])) for n in CELLS]
    bx.loglog([4.0/n for n in CELLS], worst, "o-")
    bx.set_xlabel("range rho/lambda (4 cells)")
    bx.set_ylabel("largest |p - p_JKR(a)|/p*")
    fig.suptitle("JKR wave, alpha = 0.2, exponential law: veslide's gcg")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "adhesion-jkr.png"), dpi=120)


if __name__ == "__main__":
    main()
