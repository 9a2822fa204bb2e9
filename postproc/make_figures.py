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
    a.set_title(r"contact (black), $A/A_0$ = %.4f; $\mathbf{v}$ along +x" % contact.mean())
    iy, ix = np.unravel_index(np.argmax(p), p.shape)
    w = max(nx // 16, 4)
    rows = np.arange(iy - w, iy + w) % ny
    cols = np.arange(ix - w, ix + w) % nx
    zoom = p[np.ix_(rows, cols)]
    dx = lx * 1e3 / nx                                   # cell size [mm]
    x0, y0 = (ix - w) * dx, (iy - w) * dx                # zoom window, unwrapped coordinates [mm]
    for sx in (-ext[1], 0.0, ext[1]):                    # the window wraps around the periodic cell
        for sy in (-ext[3], 0.0, ext[3]):
            a.add_patch(plt.Rectangle((x0 % ext[1] + sx, y0 % ext[3] + sy), 2 * w * dx, 2 * w * dx,
                                      fill=False, ec="C3", lw=1.2))
    a.set_xlim(0, ext[1]); a.set_ylim(0, ext[3])
    im = b.imshow(zoom / 1e6, origin="lower", cmap="viridis", interpolation="nearest",
                  extent=[x0, x0 + 2 * w * dx, y0, y0 + 2 * w * dx])
    b.set_title("zoom (red box) on the patch of highest pressure", fontsize=10)
    b.set_xlabel("x [mm]"); b.set_ylabel("y [mm]")
    fig.colorbar(im, ax=b, label="pressure [MPa]")
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)


def _closed(theta, r):
    """A polar curve over [0, 2 pi] from samples over [0, pi) (m2 and mu2 have period pi)."""
    return np.concatenate([theta, theta + np.pi, theta[:1] + 2 * np.pi]), np.concatenate([r, r, r[:1]])


def _members(src):
    """[(parameters, group prefix)] of every case of a study, or [({}, "")] for a single run."""
    with h5py.File(src) as f:
        if "/summary" not in f:
            return [({}, "")]
    t = vr.table(src)
    return [({k: t[k][i] for k in ("seed", "eccentricity", "alpha_deg")}, vr.case_group(src, int(t["case"][i])))
            for i in range(len(t["case"]))]


def _ensemble_row(src, **match):
    """{quantity: (mean, sem, n)} over the seeds of the cases whose parameters match, from
    /ensemble when the study has several seeds, else from the single case (sem 0)."""
    with h5py.File(src) as f:
        if "/summary" not in f:
            return {k: (f["/scalars/" + k][()], 0.0, 1) for k in f["/scalars"]}
        has_ens = "/ensemble" in f
    s = vr.table(src)
    sel = np.ones(len(s["case"]), bool)
    for k, v in match.items():
        sel &= np.isclose(s[k], v)
    n = len(np.unique(s["seed"][sel]))
    if has_ens:
        e = vr.table(src, "/ensemble")
        esel = np.ones(len(e["alpha_deg"]), bool)
        for k, v in match.items():
            esel &= np.isclose(e[k], v)
        i = int(np.flatnonzero(esel)[0])
        row = {k: (e[k][i], 0.0, n) for k in e if not k.startswith(("mean_", "sem_"))}
        row.update({k[5:]: (e[k][i], e["sem_" + k[5:]][i], n) for k in e if k.startswith("mean_")})
        return row
    i = int(np.flatnonzero(sel)[0])
    return {k: (s[k][i], 0.0, 1) for k in s}


def _mean_polar(src, members):
    """theta, the mean m2 and mu2 over the given cases, and every case's curves."""
    curves = [vr.polar(src, prefix) for _, prefix in members]
    theta = curves[0][0]
    m2 = np.array([c[1] for c in curves]); mu2 = np.array([c[2] for c in curves])
    return theta, m2.mean(axis=0), mu2.mean(axis=0), m2, mu2


def _polar_axes(ax, title):
    ax.set_title(title, fontsize=10, pad=12)
    ax.set_thetagrids([0, 45, 90, 135, 180, 225, 270, 315],
                      [r"0 ($\mathbf{v}$)", "45°", "90°", "135°", "180°", "225°", "270°", "315°"])
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
    ax.yaxis.get_offset_text().set_fontsize(8)
    ax.tick_params(axis="y", labelsize=7)
    ax.set_rlabel_position(112.5)


def _band_text(src, prefix):
    with h5py.File(src) as f:
        z = f[prefix + "/anisotropy/band_zeta"][()]
    return r"band %g $q_0$ .. %g $q_0$" % (z[0], z[1])


def fig2(src, out):
    """Polar plots of m2 and mu2 for the isotropic surface: the mean over the seeds of a study
    (single surfaces in grey), or one surface."""
    members = _members(src)
    theta, m2, mu2, m2_all, mu2_all = _mean_polar(src, members)
    r = _ensemble_row(src)
    n = r["gamma_d"][2]
    fig, (a, b) = plt.subplots(1, 2, subplot_kw=dict(projection="polar"), figsize=(10, 5.8), layout="constrained")
    if n > 1:
        for k in range(len(members)):
            a.plot(*_closed(theta, m2_all[k]), color="0.8", lw=0.6)
            b.plot(*_closed(theta, mu2_all[k]), color="0.8", lw=0.6)
    a.plot(*_closed(theta, m2), color="C0", lw=2)
    b.plot(*_closed(theta, mu2), color="C3", lw=2)

    def pm(q, scale=1.0, digits=3):
        m, se, _ = r[q]
        return ("%.*f" % (digits, m * scale)) + ((r" $\pm$ %.*f" % (digits, se * scale)) if n > 1 else "")
    what = "mean of %d surfaces (grey: each surface)" % n if n > 1 else "one surface"
    _polar_axes(a, r"rigid surface $m_2(\theta)$" + "\n" + r"$\gamma_s$ = " + pm("gamma_s"))
    _polar_axes(b, r"deformed solid $\mu_2(\theta)$" + "\n" + r"$\gamma_d$ = " + pm("gamma_d") +
                r", $\theta_d$ = " + pm("theta_d_rad", 180 / np.pi, 1) + "°")
    ecc = vr.namelist_value(src, "eccentricity", 1.0)
    fig.suptitle(r"%s, $v\tau/L_0$ = %.2f, p = %.0f kPa; %s; %s" % (
        "isotropic surface" if ecc == 1.0 else r"$\varepsilon$ = %.2g" % ecc, vr.dimensionless_speed(src, r["speed_m_s"][0]), r["mean_pressure_pa"][0] / 1e3,
        _band_text(src, members[0][1]), what) + ("\n" + r"$\gamma$, $\theta$: mean $\pm$ SE of the single surfaces' values"
                                                  if n > 1 else ""), fontsize=10)
    fig.savefig(out, dpi=110); plt.close(fig)


def fig3(src, out):
    """Polar plots of m2 and mu2 for eps = 0.6 and the alpha family: per alpha the mean over
    the seeds of the study, or one surface."""
    members = _members(src)
    alphas = np.unique([m["alpha_deg"] for m, _ in members])
    fig, (a, b) = plt.subplots(1, 2, subplot_kw=dict(projection="polar"), figsize=(12, 5.6), layout="constrained")
    n = 1
    for k, al in enumerate(alphas):
        sub = [(m, p) for m, p in members if np.isclose(m["alpha_deg"], al)]
        theta, m2, mu2, _, _ = _mean_polar(src, sub)
        r = _ensemble_row(src, alpha_deg=al)
        n = r["gamma_d"][2]
        g, t = r["gamma_d"], r["theta_d_rad"]
        if n > 1:
            lab = r"$\alpha$ = %.1f°: $\gamma_d$ = %.2f $\pm$ %.2f, $\theta_d$ = %.0f $\pm$ %.0f°" % (
                al, g[0], g[1], np.degrees(t[0]), np.degrees(t[1]))
        else:
            lab = r"$\alpha$ = %.1f°: $\gamma_d$ = %.2f, $\theta_d$ = %.0f°" % (al, g[0], np.degrees(t[0]))
        a.plot(*_closed(theta, m2), color="C%d" % k, lw=1.5, label=lab)
        b.plot(*_closed(theta, mu2), color="C%d" % k, lw=1.5, label=lab)
    _polar_axes(a, r"rigid surface $m_2(\theta)$")
    _polar_axes(b, r"deformed solid $\mu_2(\theta)$")
    b.legend(loc="center left", bbox_to_anchor=(1.12, 0.5), fontsize=8,
             title=("means over %d seeds" % n) if n > 1 else None, title_fontsize=8)
    ecc = members[0][0].get("eccentricity", vr.namelist_value(src, "eccentricity", 0.6))
    r0 = _ensemble_row(src, alpha_deg=alphas[0])
    fig.suptitle(r"$\varepsilon$ = %.1f, $v\tau/L_0$ = %.2f, p = %.0f kPa; %s; %s" % (
        ecc, vr.dimensionless_speed(src, r0["speed_m_s"][0]), r0["mean_pressure_pa"][0] / 1e3,
        _band_text(src, members[0][1]),
        ("curves: mean over %d seeds" % n) if n > 1 else "one surface per angle"), fontsize=10)
    fig.savefig(out, dpi=110); plt.close(fig)


ALPHA = r"$\alpha$ = %.1f°"
EPS = r"$\varepsilon$ = %.1f"
XLABEL = r"$v\tau/L_0$  ($\tau$ the creep time)"


def _family(src, key, quantity, fmt):
    """[(label, v tau/L0, mean, sem)] per member of a family (key alpha_deg or eccentricity),
    statistics over the seeds of every case (veslide_results.family_stats)."""
    return [(fmt % member, x, m, se) for member, (x, m, se) in vr.family_stats(src, key, quantity).items()]


def _note(src, fixed):
    """Subtitle: the fixed parameters and the number of seeds behind each point."""
    s = vr.table(src)
    n = len(np.unique(s["seed"]))
    return "%s, p = %.0f kPa; %s" % (fixed, s["pressure_pa"][0] / 1e3,
                                     "mean $\\pm$ SE over %d seeds" % n if n > 1 else "one surface")


def cell_artefact_speed(src):
    """v tau/L0 above which the periodic cell's modes with q.v = 0 (k_x = 0) are the only rubbery
    ones: the column k_x = 1 (q_x = 2 pi/L) is glassy once q_x v tau > Einf/E0, i.e.
    v tau/L0 > (Einf/E0)(L/L0)/(2 pi) (docs/reproduction.md, cells larger than the punch).
    None unless the solid is the one-term law."""
    ratio = vr.namelist_value(src, "ratio", None)
    if ratio is None:
        return None
    return ratio * vr.namelist_value(src, "k_roll", 1.0) / (2 * np.pi)


PERSSON = "dashed: Persson theory (realised PSD)"


def _theory(src, key, column, fmt):
    """The seed mean of Persson's theory per member of a family, [(label, v tau/L0, mean, sem)],
    or None when the study was run without &analysis persson (no such column in /summary)."""
    if column not in vr.table(src):
        return None
    return _family(src, key, column, fmt)


def _speed_plot(ax, fam, ylabel, logy=False, src=None, theory=None):
    """One curve per member of `fam` (mean with standard-error bars over the seeds); `theory`,
    when given, the same members' Persson estimate (its seed mean), drawn dashed in the same colour."""
    for k, (label, x, m, s) in enumerate(fam):
        ax.errorbar(x, m, yerr=s, marker="o", ms=3, capsize=2, color="C%d" % (k % 10), label=label)
    if theory is not None:
        for k, (label, x, m, _) in enumerate(theory):
            ax.plot(x, m, ls="--", lw=1.2, color="C%d" % (k % 10))
        ax.plot([], [], ls="--", lw=1.2, color="0.3", label=PERSSON)
    ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(XLABEL); ax.set_ylabel(ylabel)
    ax.grid(True, which="major", lw=0.3, color="0.85")
    v = cell_artefact_speed(src) if src is not None else None
    if v is not None:
        lo, hi = ax.get_xlim()
        if v < hi:
            ax.axvspan(v, hi, color="0.9", zorder=0, lw=0, label=r"cell artefact: $\mathbf{q}\cdot\mathbf{v} = 0$ modes rubbery")
            ax.set_xlim(lo, hi)
    return theory is not None


def _legend(ax, fam, reverse=False, **kw):
    """The legend with the family's curves first (reversed if asked), then the notes (theory, band)."""
    h, l = ax.get_legend_handles_labels()
    names = [f[0] for f in fam]
    curves = sorted((i for i in range(len(l)) if l[i] in names), key=lambda i: names.index(l[i]), reverse=reverse)
    rest = [i for i in range(len(l)) if l[i] not in names]
    ax.legend([h[i] for i in curves + rest], [l[i] for i in curves + rest], **kw)


def _ecc_text(src):
    return EPS % vr.table(src)["eccentricity"][0]


def fig4(src, out):
    fig, (a, b) = plt.subplots(1, 2, figsize=(10.5, 4.3))
    fam = _family(src, "alpha_deg", "contact_area_fraction", ALPHA)
    drawn = _speed_plot(a, fam, r"contact area $A/A_0$", src=src,
                        theory=_theory(src, "alpha_deg", "persson_contact_area_fraction", ALPHA))
    _speed_plot(b, _family(src, "alpha_deg", lambda t: t["mean_separation_m"] / t["rms_height_m"], ALPHA),
                r"separation $s/h_\mathrm{rms}$", src=src)
    _legend(a, fam, fontsize=8)
    fig.suptitle(_note(src, _ecc_text(src)), fontsize=10)
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)
    return drawn


def fig5(src, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.5))
    fam = _family(src, "alpha_deg", "friction_coefficient", ALPHA)
    drawn = _speed_plot(ax, fam, r"friction $f = F_x/F_n$", src=src,
                        theory=_theory(src, "alpha_deg", "persson_friction_coefficient", ALPHA))
    ax.set_title(_note(src, _ecc_text(src)), fontsize=9)
    _legend(ax, fam, fontsize=8); fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)
    return drawn


def fig6(src, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.5))
    fam = _family(src, "eccentricity", "friction_coefficient", EPS)
    drawn = _speed_plot(ax, fam, r"friction $f = F_x/F_n$", src=src,
                        theory=_theory(src, "eccentricity", "persson_friction_coefficient", EPS))
    ax.set_title(_note(src, r"$\alpha$ = %.0f°" % vr.table(src)["alpha_deg"][0]), fontsize=9)
    _legend(ax, fam, reverse=True, fontsize=8)        # eps descending, as the curves stack
    fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)
    return drawn


def fig7(src, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.5))
    fam = _family(src, "alpha_deg", "lateral_force_ratio", ALPHA)
    drawn = _speed_plot(ax, fam, r"lateral force $F_y/F_n$", src=src,
                        theory=_theory(src, "alpha_deg", "persson_lateral_force_ratio", ALPHA))
    ax.axhline(0, color="k", lw=0.5)
    ax.set_title(_note(src, _ecc_text(src)) + "\n" + r"$F_y$: along +y, 90° counter-clockwise from $\mathbf{v}$",
                 fontsize=9)
    _legend(ax, fam, fontsize=8); fig.tight_layout(); fig.savefig(out, dpi=110); plt.close(fig)
    return drawn


def fig8(src, out):
    """sigma1, sigma2 and phi against speed for the alpha family (described, not plotted, in the paper)."""
    fig, axs = plt.subplots(1, 3, figsize=(14, 4.4))
    for ax, q, lab in zip(axs, ("sigma1", "sigma2", "phi_rad"),
                          (r"$\sigma_1$ (along the major axis of $M$)", r"$\sigma_2$ (along its minor axis)",
                           r"rotation $\phi$ [deg]")):
        fam = _family(src, "alpha_deg", q, ALPHA)
        if q == "phi_rad":
            fam = [(l, x, np.degrees(m), np.degrees(se)) for l, x, m, se in fam]
        _speed_plot(ax, fam, lab, src=src)
    axs[2].axhline(0, color="k", lw=0.5)
    axs[0].legend(fontsize=8)
    band = _band_text(src, vr.case_group(src, 1))
    fig.suptitle(_note(src, _ecc_text(src)) + "; eq. (16) of the deformed slope tensor, " + band, fontsize=10)
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
        with_theory = draw(path, os.path.join(outdir, name))
        print("wrote", os.path.join(outdir, name) + (" (with Persson's theory)" if with_theory else ""))
        made += 1
    return made


if __name__ == "__main__":
    sys.exit(0 if main(*sys.argv[1:]) > 0 else 1)
