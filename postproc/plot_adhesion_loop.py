#!/usr/bin/env python3
"""A loading-unloading loop of Johnson's JKR wave, run by veslide as two load paths.

    python postproc/plot_adhesion_loop.py [--out docs/figures]

The wave of docs/adhesion.md (h = 1 um, lambda = 100 um, E* = 10 MPa, alpha = 0.2, exponential
law of range h/64, 4096 cells), as two studies whose `&sweep` list is a load path (each case
warm-started from the one before, both ways):

- load control, `&sweep pressures_pa`: unloaded from 0.3 p* past the pull-off, reloaded from the
  separation past the jump into full contact, unloaded again in full contact;
- approach control, `&sweep approaches_m`: the approach lowered from 0.3 h to -0.3 h and raised
  again, which follows the branch that load control jumps across.

Writes adhesion-loop.csv (one row a case: the path's control, its place, the load, the contact
half-width, the approach, the event flagged and the FFT pairs) and adhesion-loop.png: the loads
against the half-width beside Johnson's p/p* = sin^2(pi a) - alpha sqrt(tan(pi a)) (stable
under load control where it rises, dashed where it falls), with the closed form's jumps marked,
and the loads against the approach. Prints each path's /paths row and the FFT pairs of the load
path with and without warm starts.
"""
import argparse
import os
import tempfile

import numpy as np

import veslide

LAMBDA, AMP, E, ALPHA, N = 1.0e-4, 1.0e-6, 1.0e7, 0.2, 4096
PSTAR = np.pi*E*AMP/LAMBDA
W = ALPHA**2*np.pi**2*E*AMP**2/(2.0*LAMBDA)
RHO = AMP/64.0
#: unload to separation, reload from it into full contact, unload in full contact [p*]
LOADS = [0.3, 0.2, 0.1, 0.05, 0.0, -0.02, -0.04, -0.05, -0.054, -0.058,
         -0.03, 0.0, 0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.53, 0.56, 0.6, 0.4, 0.2, 0.0, -0.05, -0.1]
#: approach lowered and raised [h]
APPROACHES = list(np.round(np.r_[np.arange(0.3, -0.3, -0.02), np.arange(-0.3, 0.3001, 0.02)], 6))


def jkr(a):
    return np.sin(np.pi*a)**2 - ALPHA*np.sqrt(np.tan(np.pi*a))


def study(sweep, path):
    p = {"grid": {"nx": N, "ny": 1, "lx_m": LAMBDA, "ly_m": LAMBDA/N},
         "surface": {"kind": "cosine", "amplitude_m": AMP, "wavelength_m": LAMBDA},
         "material": {"young_pa": E, "poisson": 0.0},
         "adhesion": {"law": "exponential", "energy_j_m2": W, "range_m": RHO},
         "solver": {"tolerance": 1e-10, "fft_planner": "estimate"},
         "sweep": sweep, "output": {"fields": False}}
    # (cases past the pull-off under load control do not converge: the gap opens without bound)
    return veslide.run(p, output=path, progress=None)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join("docs", "figures"))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as work:
        load = study({"pressures_pa": [x*PSTAR for x in LOADS]}, os.path.join(work, "load.h5"))
        cold = study({"pressures_pa": [x*PSTAR for x in LOADS], "warm_start": False}, os.path.join(work, "cold.h5"))
        appr = study({"approaches_m": [x*AMP for x in APPROACHES]}, os.path.join(work, "approach.h5"))
        rows = []
        for control, r in ((0, load), (1, appr)):
            s = r.summary
            for _, c in s.iterrows():
                rows.append((control, c["path_step"], c["mean_pressure_pa"]/PSTAR,
                             c["contact_area_fraction_cells"]/2.0, c["approach_m"]/AMP, c["path_jump"],
                             c["converged"], c["operator_applications"]))
            print(("load" if control == 0 else "approach") + " path:", r.paths.iloc[0].to_dict())
        ws, cs = load.summary, cold.summary
        both = (ws["converged"] == 1) & (cs["converged"] == 1)
        print("load path, FFT pairs of the cases both converge: warm-started %d, cold-started %d; "
              "not converged: warm %d, cold %d" % (ws["operator_applications"][both].sum(),
                                                   cs["operator_applications"][both].sum(),
                                                   (ws["converged"] == 0).sum(), (cs["converged"] == 0).sum()))
    rows = np.array(rows, dtype=float)
    os.makedirs(args.out, exist_ok=True)
    np.savetxt(os.path.join(args.out, "adhesion-loop.csv"), rows, delimiter=",", comments="",
               fmt=["%d", "%d", "%.10e", "%.10e", "%.10e", "%d", "%d", "%d"],
               header="approach_control,path_step,load_over_pstar,half_width_over_wavelength,approach_over_h,"
                      "path_jump,converged,fft_pairs")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.4))
    a = np.linspace(1e-5, 0.4999, 4000)
    p = jkr(a)
    rising = np.gradient(p) > 0
    ax.plot(np.where(rising, a, np.nan), np.where(rising, p, np.nan), "k-", lw=1,
            label="JKR (Johnson 1995), stable under load control")
    ax.plot(np.where(~rising, a, np.nan), np.where(~rising, p, np.nan), "k--", lw=1, label="JKR, unstable")
    ia, ib = np.argmin(p[a < 0.25]), np.argmax(np.where(a > 0.25, p, -np.inf))
    ax.plot([a[ia], a[ib]], [p[ia], p[ib]], "k*", ms=10, label="closed form's pull-off and jump to full contact")
    for control, style, name in ((0, "o-", "veslide, load control"), (1, "s-", "veslide, approach control")):
        m = (rows[:, 0] == control) & (rows[:, 6] == 1)
        ax.plot(rows[m, 3], rows[m, 2], style, ms=4, mfc="none", lw=0.6, label=name)
        jumps = (rows[:, 0] == control) & (rows[:, 5] != 0)
        for k in np.flatnonzero(jumps):
            # (a case that did not converge, past the pull-off, drawn at a = 0: separated)
            a0, a1 = (rows[j, 3] if rows[j, 6] == 1 else 0.0 for j in (k - 1, k))
            ax.annotate("", xy=(a1, rows[k, 2]), xytext=(a0, rows[k - 1, 2]),
                        arrowprops=dict(arrowstyle="->", color="C3", lw=1))
    m = (rows[:, 0] == 0) & (rows[:, 6] == 0)
    ax.plot(np.zeros(m.sum()), rows[m, 2], "x", color="C0", label="load control: separated (not converged)")
    ax.set_xlabel("contact half-width a/lambda")
    ax.set_ylabel("mean pressure p/p*")
    ax.set_xlim(-0.01, 0.52)
    ax.set_ylim(-0.12, 0.65)
    ax.legend(fontsize=7, loc="upper left")
    for control, style, name in ((0, "o", "load control"), (1, "s-", "approach control")):
        m = (rows[:, 0] == control) & (rows[:, 6] == 1)
        bx.plot(rows[m, 4], rows[m, 2], style, ms=4, mfc="none", lw=0.6, label=name)
    bx.set_xlabel("approach since first contact / h")
    bx.set_ylabel("mean pressure p/p*")
    bx.set_xlim(-0.35, 1.05)
    bx.set_ylim(-0.12, 0.65)
    bx.legend(fontsize=8)
    fig.suptitle("JKR wave, alpha = 0.2, range h/64, 4096 cells: load paths warm-started both ways "
                 "(red arrows: jumps flagged)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "adhesion-loop.png"), dpi=120)


if __name__ == "__main__":
    main()
