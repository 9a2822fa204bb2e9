#!/usr/bin/env python3
"""Friction against speed of Johnson's wave sliding over a viscoelastic solid, with and without
adhesion.

    python postproc/plot_adhesion_sliding.py [--out docs/figures] [--cells 2048]

A rigid wave h cos(2 pi x/lambda) (h = 1 um, lambda = 100 um) slides along x over a one-term
viscoelastic half-space (E0 = 10 MPa, Einf = 100 MPa, creep time tau = 10 ms, nu = 0) under
p = 0.1 p* (p* = pi E0 h/lambda), at speeds v tau/lambda from 1e-3 to 1e2. With adhesion: the
exponential law with w set by alpha = 0.2 for E0 (alpha^2 = 2 w lambda/(pi^2 E0 h^2)) and a range
of 4 cells (resolved: a range below a cell traps the contact's edges between cells), solved by
'gcg' (its splitting); without: the hard wall ('auto'). Each case starts cold. Writes
adhesion-sliding.csv (one row a run: speed, law, friction coefficient, contact fraction, the
adhesive force per area, FFT pairs) and adhesion-sliding.png: the friction coefficient and the
contact fraction against v tau/lambda, with and without adhesion.
"""
import argparse
import os
import tempfile

import numpy as np

import veslide

LAMBDA, AMP, E0, RATIO, TAU, ALPHA = 1.0e-4, 1.0e-6, 1.0e7, 10.0, 1.0e-2, 0.2
PSTAR = np.pi*E0*AMP/LAMBDA
W = ALPHA**2*np.pi**2*E0*AMP**2/(2.0*LAMBDA)
SPEEDS = np.logspace(-3, 2, 21)          # v tau/lambda


def solve(n, vt, adhesive, work):
    p = {"grid": {"nx": n, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/n},
         "surface": {"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
         "material": {"model": "one_term", "einf_pa": RATIO*E0, "ratio": RATIO, "tau_s": TAU, "poisson": 0.0},
         "load": {"mean_pressure_pa": 0.1*PSTAR}, "motion": {"speed_m_s": vt*LAMBDA/TAU},
         "solver": {"tolerance": 1e-9, "fft_planner": "estimate", "max_iterations": 200000},
         "output": {"fields": False}}
    if adhesive:
        p["adhesion"] = {"law": "exponential", "energy_j_m2": W, "range_m": 4.0*LAMBDA/n}
    r = veslide.run(p, output=os.path.join(work, f"slide-{vt:.3g}-{int(adhesive)}.h5"), progress=None)
    s = r.scalars
    if s["converged"] != 1:
        raise RuntimeError(f"not converged: v tau/lambda = {vt}, adhesion {adhesive}")
    return (vt, int(adhesive), s["friction_coefficient"], s["contact_area_fraction_cells"],
            s.get("adhesive_pressure_pa", 0.0), s["operator_applications"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join("docs", "figures"))
    ap.add_argument("--cells", type=int, default=2048)
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for vt in SPEEDS:
            for adhesive in (False, True):
                rows.append(solve(args.cells, vt, adhesive, work))
                print("v tau/lambda = {:9.3e}  adhesion {}  friction {:.5f}  contact {:.4f}  "
                      "adhesive force {:9.3e} Pa  FFT pairs {}".format(*rows[-1]), flush=True)
    rows = np.array(rows, dtype=float)
    os.makedirs(args.out, exist_ok=True)
    np.savetxt(os.path.join(args.out, "adhesion-sliding.csv"), rows, delimiter=",", comments="",
               header="speed_tau_over_lambda,adhesion,friction_coefficient,contact_area_fraction_cells,"
                      "adhesive_pressure_pa,fft_pairs", fmt=["%.6e", "%d", "%.9e", "%.9e", "%.9e", "%d"])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(9.5, 3.8))
    for adhesive, style, label in ((0, "o-", "hard wall"), (1, "s-", "adhesion (alpha = 0.2)")):
        m = rows[:, 1] == adhesive
        ax[0].semilogx(rows[m, 0], rows[m, 2], style, label=label)
        ax[1].semilogx(rows[m, 0], rows[m, 3], style, label=label)
    ax[0].set_xlabel("v tau/lambda"); ax[0].set_ylabel("friction coefficient")
    ax[1].set_xlabel("v tau/lambda"); ax[1].set_ylabel("contact fraction (closed cells)")
    ax[0].legend()
    fig.suptitle(f"Johnson's wave sliding at p = 0.1 p*, Einf/E0 = {RATIO:g}, {args.cells} cells", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "adhesion-sliding.png"), dpi=120)
    print("wrote", os.path.join(args.out, "adhesion-sliding.png"))


if __name__ == "__main__":
    main()
