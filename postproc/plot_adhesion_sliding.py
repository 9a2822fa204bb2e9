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

The third panel is the energy release rates of the contact's trailing and leading edges
(docs/adhesion.md, *Contact edges*) of the same wave with a short range, h/64 on 4096 cells (its
cohesive zone at rest 4 cells, against a contact of hundreds: a crack's edge; with the range of 4
cells above the zone is wider than the contact, and no edge is measured), from v tau/lambda = 1e-6
to 1e3, with w, (Einf/E0) w and (E0/Einf) w: adhesion-trailing-edge.csv (speed, trailing G/w,
leading G/w (NaN where it is not measured), contact fraction, FFT pairs).
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


def edges(vt, work, n=4096):
    """The trailing and leading edges' G/w of the wave with range h/64 on n cells at v tau/lambda
    = vt (the leading one NaN where it is not measured)"""
    p = {"grid": {"nx": n, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/n},
         "surface": {"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
         "material": {"model": "one_term", "einf_pa": RATIO*E0, "ratio": RATIO, "tau_s": TAU, "poisson": 0.0},
         "load": {"mean_pressure_pa": 0.1*PSTAR}, "motion": {"speed_m_s": vt*LAMBDA/TAU},
         "adhesion": {"law": "exponential", "energy_j_m2": W, "range_m": AMP/64},
         "solver": {"tolerance": 1e-10, "fft_planner": "estimate", "max_iterations": 200000},
         "output": {"fields": False}}
    r = veslide.run(p, output=os.path.join(work, f"edge-{vt:.3g}.h5"), progress=None)
    s = r.scalars
    if s["converged"] != 1 or s["trailing_edges"] != 1:
        raise RuntimeError(f"not converged, or not one trailing edge: v tau/lambda = {vt}")
    return (vt, s["trailing_edge_energy_j_m2"]/W, s["leading_edge_energy_j_m2"]/W, s["contact_area_fraction_cells"],
            s["operator_applications"])


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
        rates = []
        for vt in np.logspace(-6, 3, 37):
            rates.append(edges(vt, work))
            print("v tau/lambda = {:9.3e}  G/w trailing {:.5f} leading {:.5f}  contact {:.4f}  "
                  "FFT pairs {}".format(*rates[-1]), flush=True)
    rows = np.array(rows, dtype=float)
    rates = np.array(rates, dtype=float)
    os.makedirs(args.out, exist_ok=True)
    np.savetxt(os.path.join(args.out, "adhesion-trailing-edge.csv"), rates, delimiter=",", comments="",
               header="speed_tau_over_lambda,trailing_edge_energy_over_w,leading_edge_energy_over_w,"
                      "contact_area_fraction_cells,fft_pairs", fmt=["%.6e", "%.9e", "%.9e", "%.9e", "%d"])
    np.savetxt(os.path.join(args.out, "adhesion-sliding.csv"), rows, delimiter=",", comments="",
               header="speed_tau_over_lambda,adhesion,friction_coefficient,contact_area_fraction_cells,"
                      "adhesive_pressure_pa,fft_pairs", fmt=["%.6e", "%d", "%.9e", "%.9e", "%.9e", "%d"])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13.5, 3.8))
    for adhesive, style, label in ((0, "o-", "hard wall"), (1, "s-", "adhesion (alpha = 0.2)")):
        m = rows[:, 1] == adhesive
        ax[0].semilogx(rows[m, 0], rows[m, 2], style, label=label)
        ax[1].semilogx(rows[m, 0], rows[m, 3], style, label=label)
    ax[0].set_xlabel("v tau/lambda"); ax[0].set_ylabel("friction coefficient")
    ax[1].set_xlabel("v tau/lambda"); ax[1].set_ylabel("contact fraction (closed cells)")
    ax[2].loglog(rates[:, 0], rates[:, 1], "s-", color="C1", ms=4, label="trailing edge")
    ax[2].loglog(rates[:, 0], rates[:, 2], "o-", color="C2", ms=4, label="leading edge")
    ax[2].axhline(RATIO, color="k", lw=0.8, ls="--", label="Einf/E0")
    ax[2].axhline(1.0, color="k", lw=0.8, ls=":", label="w")
    ax[2].axhline(1.0/RATIO, color="k", lw=0.8, ls="-.", label="E0/Einf")
    ax[2].set_xlabel("v tau/lambda"); ax[2].set_ylabel("energy release rate G/w")
    ax[2].set_title("range h/64, 4096 cells", fontsize=9)
    ax[2].legend(loc="lower right", fontsize=8)
    ax[0].legend()
    fig.suptitle(f"Johnson's wave sliding at p = 0.1 p*, Einf/E0 = {RATIO:g}, {args.cells} cells", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "adhesion-sliding.png"), dpi=120)
    print("wrote", os.path.join(args.out, "adhesion-sliding.png"))


if __name__ == "__main__":
    main()
