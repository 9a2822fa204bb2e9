#!/usr/bin/env python3
"""Draw the paper's figures from veslide results.

usage: python postproc/make_figures.py RESULTS_DIR OUT_DIR
RESULTS_DIR holds fig1.h5, fig2.h5, fig3.h5, fig4_5_7.h5 and fig6.h5 (the studies of
inputs/paper/); figures missing their input are skipped with a message. Writes fig1.png ...
fig7.png and fig8_stretch_rotation.png (sigma1, sigma2, phi against speed and alpha).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import veslide_results as vr  # noqa: E402


def fig1(src, out):
    """Contact map with a zoomed patch."""
    p, _ = vr.field(src, "pressure_pa")
    lx = vr.namelist_value(src, "lx_m", 0.01)
    contact = p > 0
    ny, nx = p.shape
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.8))
    ext = [0, lx * 1e3, 0, lx * 1e3 * ny / nx]
    a.imshow(contact, origin="lower", cmap="gray_r", extent=ext, interpolation="nearest")
    a.set_xlabel("x [mm]"); a.set_ylabel("y [mm]")
    a.set_title("contact area (black), A/A0 = %.4f, v along +x" % contact.mean())
    iy, ix = np.unravel_index(np.argmax(p), p.shape)
    w = max(nx // 16, 4)
    rows = np.arange(iy - w, iy + w) % ny
    cols = np.arange(ix - w, ix + w) % nx
    zoom = p[np.ix_(rows, cols)]
    im = b.imshow(zoom / 1e3, origin="lower", cmap="viridis", interpolation="nearest")
    b.set_title("zoom on the patch of highest pressure")
    b.set_xticks([]); b.set_yticks([])
    fig.colorbar(im, ax=b, label="pressure [kPa]")
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def _polar_pair(ax_s, ax_d, theta, m2, mu2, label=None):
    t = np.concatenate([theta, theta + np.pi, theta[:1] + 2 * np.pi])
    ax_s.plot(t, np.concatenate([m2, m2, m2[:1]]), label=label)
    ax_d.plot(t, np.concatenate([mu2, mu2, mu2[:1]]), label=label)


def fig2(src, out):
    """Polar plots of m2 and mu2 for the isotropic surface."""
    theta, m2, mu2 = vr.polar(src)
    fig, (a, b) = plt.subplots(1, 2, subplot_kw=dict(projection="polar"), figsize=(9, 4.5))
    _polar_pair(a, b, theta, m2, mu2)
    a.set_title("rigid surface m2(theta)")
    with h5py.File(src) as f:
        gd = f["/scalars/gamma_d"][()]; td = f["/scalars/theta_d_rad"][()]
    b.set_title("deformed solid mu2(theta)\ngamma_d = %.2f, theta_d = %.2f rad" % (gd, td))
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def fig3(src, out):
    """Polar plots of m2 and mu2 for eps = 0.6 and the alpha family."""
    t = vr.table(src)
    fig, (a, b) = plt.subplots(1, 2, subplot_kw=dict(projection="polar"), figsize=(10, 4.8))
    for k in range(len(t["case"])):
        theta, m2, mu2 = vr.polar(src, vr.case_group(src, int(t["case"][k])))
        _polar_pair(a, b, theta, m2, mu2, label="alpha = %.1f deg" % t["alpha_deg"][k])
    a.set_title("rigid surface m2(theta)"); b.set_title("deformed solid mu2(theta)")
    b.legend(loc="lower left", bbox_to_anchor=(1.0, 0.0), fontsize=8)
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def _family(src, key, name, quantity, fmt):
    """(label, x, mean, sem) per member of a family (alpha_deg or eccentricity) from /ensemble,
    or from /summary when there is one seed."""
    try:
        e = vr.table(src, "/ensemble")
        mean, sem = e["mean_" + quantity], e["sem_" + quantity]
    except KeyError:
        e = vr.table(src)
        mean, sem = e[quantity], np.zeros_like(e[quantity])
    out = []
    for v in np.unique(e[key]):
        sel = e[key] == v
        x = vr.dimensionless_speed(src, e["speed_m_s"][sel])
        order = np.argsort(x)
        out.append((fmt % v, x[order], mean[sel][order], sem[sel][order]))
    return out


def _speed_plot(ax, fam, ylabel, logy=False):
    for label, x, m, s in fam:
        ax.errorbar(x, m, yerr=s, marker="o", ms=3, capsize=2, label=label)
    ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel("v tau / L0"); ax.set_ylabel(ylabel)


def fig4(src, out):
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    _speed_plot(a, _family(src, "alpha_deg", "alpha", "contact_area_fraction", "alpha = %.1f deg"), "A/A0")
    sep = _family(src, "alpha_deg", "alpha", "mean_separation_m", "alpha = %.1f deg")
    rms = _family(src, "alpha_deg", "alpha", "rms_height_m", "%.1f")
    _speed_plot(b, [(l, x, m / r[2], s / r[2]) for (l, x, m, s), r in zip(sep, rms)], "s / h_rms")
    a.legend(fontsize=8)
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def fig5(src, out):
    fig, ax = plt.subplots(figsize=(6, 4.2))
    _speed_plot(ax, _family(src, "alpha_deg", "alpha", "friction_coefficient", "alpha = %.1f deg"), "f = F_x/F_n")
    ax.legend(fontsize=8); fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def fig6(src, out):
    fig, ax = plt.subplots(figsize=(6, 4.2))
    _speed_plot(ax, _family(src, "eccentricity", "eps", "friction_coefficient", "eps = %.1f"), "f = F_x/F_n")
    ax.legend(fontsize=8); fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def fig7(src, out):
    fig, ax = plt.subplots(figsize=(6, 4.2))
    _speed_plot(ax, _family(src, "alpha_deg", "alpha", "lateral_force_ratio", "alpha = %.1f deg"), "F_y / F_n")
    ax.axhline(0, color="k", lw=0.5)
    ax.legend(fontsize=8); fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def fig8(src, out):
    """sigma1, sigma2 and phi against speed for the alpha family (described, not plotted, in the paper)."""
    fig, axs = plt.subplots(1, 3, figsize=(13, 4))
    for ax, q, lab in zip(axs, ("sigma1", "sigma2", "phi_rad"), ("sigma1", "sigma2", "phi [rad]")):
        _speed_plot(ax, _family(src, "alpha_deg", "alpha", q, "alpha = %.1f deg"), lab)
    axs[0].legend(fontsize=8)
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


JOBS = [("fig1.h5", fig1, "fig1.png"), ("fig2.h5", fig2, "fig2.png"), ("fig3.h5", fig3, "fig3.png"),
        ("fig4_5_7.h5", fig4, "fig4.png"), ("fig4_5_7.h5", fig5, "fig5.png"), ("fig6.h5", fig6, "fig6.png"),
        ("fig4_5_7.h5", fig7, "fig7.png"), ("fig4_5_7.h5", fig8, "fig8_stretch_rotation.png")]


def main(results="results/paper", outdir="docs/figures/paper"):
    os.makedirs(outdir, exist_ok=True)
    made = 0
    for src, draw, name in JOBS:
        path = os.path.join(results, src)
        if not os.path.exists(path):
            print("skipped %s: no %s" % (name, path))
            continue
        draw(path, os.path.join(outdir, name))
        print("wrote", os.path.join(outdir, name))
        made += 1
    return made


if __name__ == "__main__":
    sys.exit(0 if main(*sys.argv[1:]) > 0 else 1)
