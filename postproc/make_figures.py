#!/usr/bin/env python3
"""Draw the paper's figures from veslide results, with the plot helpers of the package
(python/veslide/plot.py), at their printed size.

usage: python postproc/make_figures.py RESULTS_DIR OUT_DIR [NAME ...]
RESULTS_DIR holds fig1.h5, fig2.h5, fig3.h5, fig4_5_7.h5 and fig6.h5 (the studies of
inputs/paper/, or their small versions in inputs/quick/); figures missing their input are
skipped with a message. Every figure is written as NAME.png (300 dpi), NAME.pdf and NAME.svg:
fig1 .. fig7 (the paper's), fig8_stretch_rotation (sigma1, sigma2, phi against speed and
alpha), fig9_pressure_gap (pressure and gap over the whole cell of the fig1 case),
fig10_surface_psd (the PSD of the fig1 surface, radial and 2-D) and fig11_friction_direction
(friction against the direction of sliding, from the fig4_5_7 study). NAMEs (e.g. fig2
fig9_pressure_gap) draw only those. Titles are short or absent: what a figure shows (the scene,
the pressure, the seeds behind each point, what colours and symbols mean) is its caption in
docs/reproduction.md.
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(os.path.dirname(HERE), "python"), HERE]   # this checkout's package first
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

import veslide  # noqa: E402
import veslide.plot as vp  # noqa: E402
import veslide_results as vr  # noqa: E402

PAGE = 7.0                         # width [in] of a figure across a journal page
XLABEL = r"$v\tau/L_0$"
ALPHA = r"$\alpha$ = %.4g°"
EPS = r"$\varepsilon$ = %.2g"
PERSSON = "Persson's theory"


def _speed_scale(r):
    """tau/L0: v times it is the dimensionless speed v tau/L0 (veslide_results.dimensionless_speed)."""
    return float(vr.dimensionless_speed(r.path, 1.0))


def _stats(r, **match):
    """{quantity: (mean, sem, n)} over the seeds of the cases whose parameters match: from
    /ensemble when the study has several seeds, else the first matching case (sem 0)."""
    if not r.is_study:
        return {k: (v, 0.0, 1) for k, v in r.scalars.items()}
    s = r.summary
    sel = np.ones(len(s), bool)
    for k, v in match.items():
        sel &= np.isclose(s[k], v)
    n = s["seed"][sel].nunique()
    if r.ensemble is not None:
        e = r.ensemble
        esel = np.ones(len(e), bool)
        for k, v in match.items():
            esel &= np.isclose(e[k], v)
        row = e[esel].iloc[0]
        out = {k: (row[k], 0.0, n) for k in e.columns if not k.startswith(("mean_", "sem_"))}
        out.update({k[5:]: (row[k], row["sem_" + k[5:]], n) for k in e.columns if k.startswith("mean_")})
        return out
    row = s[sel].iloc[0]
    return {k: (row[k], 0.0, 1) for k in s.columns}


def _members(r, **match):
    """The Results of a study's cases whose parameters match (every case without `match`), or
    [r] for a single case."""
    if not r.is_study:
        return [r]
    s = r.summary
    sel = np.ones(len(s), bool)
    for k, v in match.items():
        sel &= np.isclose(s[k], v)
    return [r.cases[int(c)] for c in s["case"][sel]]


# -- figure 1 and the maps of its case -----------------------------------------------------------

def fig1(r):
    """Contact map with a zoom on the patch of highest pressure."""
    fig, (a, b) = plt.subplots(1, 2, figsize=(PAGE, 3.5), width_ratios=[1, 1.12])
    vp.contact_map(r, a)
    p = r.fields.pressure_pa.values                     # [ix, iy]
    nx, ny = p.shape
    lx, ly = r.scalars["length_x_m"], r.scalars["length_y_m"]
    dx, dy = lx / nx, ly / ny
    ix, iy = np.unravel_index(np.argmax(p), p.shape)
    w = max(nx // 16, 4)                                # half-width of the zoom [cells]
    window = ((ix - w) * dx, (iy - w) * dy, 2 * w * dx, 2 * w * dy)
    x0, y0 = (window[0] % lx - dx / 2) * 1e3, (window[1] % ly - dy / 2) * 1e3     # its corner [mm]
    for sx in (-lx, 0.0, lx):                           # the window wraps around the periodic cell
        for sy in (-ly, 0.0, ly):
            a.add_patch(plt.Rectangle((x0 + sx * 1e3, y0 + sy * 1e3), window[2] * 1e3, window[3] * 1e3,
                                      fill=False, ec="C3", lw=1.0))
    a.set_xlim((-dx / 2) * 1e3, (lx - dx / 2) * 1e3)
    a.set_ylim((-dy / 2) * 1e3, (ly - dy / 2) * 1e3)
    vp.pressure_map(r, b, unit="MPa", window=window, arrow=False, zero_color="white")
    b.set_title("red box: the patch of highest pressure")
    return fig


def fig9_pressure_gap(r):
    """Pressure (white out of contact) and gap over the whole cell of the fig1 case."""
    fig, (a, b) = plt.subplots(1, 2, figsize=(PAGE, 3.5))
    vp.pressure_map(r, a, unit="MPa", zero_color="white")
    a.set_title(r"pressure $p$ (white: no contact)")
    vp.gap_map(r, b, unit="um", contact_color="deepskyblue")
    b.set_title(r"gap $g$ (blue: contact)")
    return fig


def fig10_surface_psd(r):
    """The fig1 surface's power spectral density: shell average against |q|/q0 with the
    self-affine slope, and log10 C over the (qx, qy) plane."""
    surf = r.input["surface"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(PAGE, 3.0), width_ratios=[1, 1.1])
    vp.psd(r, a, relative=True, hurst=surf.get("hurst", 0.8), q_max=surf.get("k_cut", 64.0) - 0.5, ms=2, lw=0.8,
           color="C0", label="realised")     # the shell at k_cut lies half outside the spectrum
    a.legend(loc="lower left")
    a.set_title(r"shell average over $|\mathbf{q}|$")
    a.set_xlabel(r"$|\mathbf{q}|/q_0$")
    vp.psd_2d(r, b, q_max=1.15 * surf.get("k_cut", 64.0))
    b.set_title(r"over the $(q_x, q_y)$ plane ($C$ = 0 blank)")
    return fig


# -- figures 2 and 3: polar plots of m2 and mu2 --------------------------------------------------

def _polar_axes(ax, title, zero=r"0° ($\mathbf{v}$)", nbins=4):
    """Angles every 45° (0: `zero`); radial ticks labelled along the ray where the labels lie
    clear of the curves (veslide.plot.place_radial_labels). Call it after the last curve."""
    ax.set_title(title, pad=10)
    ax.figure.get_layout_engine().set(h_pad=0.1)     # room the layout misses above polar titles
    ax.set_thetagrids(range(0, 360, 45), [zero] + ["%d°" % t for t in range(45, 360, 45)])
    ax.tick_params(axis="x", pad=1)
    rmax = ax.get_rmax()
    ticks = [t for t in MaxNLocator(nbins, steps=[1, 2, 2.5, 5, 10]).tick_values(0, rmax) if 0 < t <= rmax]
    ax.set_rgrids(ticks, ["%g" % t for t in ticks])
    vp.place_radial_labels(ax)
    for label in ax.yaxis.get_ticklabels():         # legible where curves cross everywhere (fig3)
        label.set_bbox(dict(fc="white", ec="none", alpha=0.7, pad=0.3))


def _decade(values):
    return int(np.floor(np.log10(np.max(values))))


def _curves(members):
    theta = members[0].anisotropy["theta_rad"]
    m2 = np.array([c.anisotropy["m2_surface"] for c in members])
    mu2 = np.array([c.anisotropy["mu2_deformed"] for c in members])
    return theta, m2, mu2


def fig2(r):
    """m2 and mu2 of the isotropic surface: the mean over the seeds (single surfaces in grey)."""
    members = _members(r)
    theta, m2_all, mu2_all = _curves(members)
    m2, mu2 = m2_all.mean(axis=0), mu2_all.mean(axis=0)
    st = _stats(r)
    n = st["gamma_d"][2]
    em, ed = _decade(m2_all), _decade(mu2_all)
    fig, axs = plt.subplots(1, 2, subplot_kw=dict(projection="polar"), figsize=(PAGE, 3.7))
    if n > 1:
        for k in range(len(members)):
            vp.anisotropy_polar((theta, m2_all[k] / 10.0 ** em, mu2_all[k] / 10.0 ** ed), axs, titles=False, marks={},
                                color="0.78", lw=0.5, label=None)
    vp.anisotropy_polar((theta, m2 / 10.0 ** em, mu2 / 10.0 ** ed), axs, titles=False,
                        marks={"theta_d_rad": st["theta_d_rad"][0]}, color="C3", lw=1.6, label=None)

    def pm(q, scale=1.0, digits=3):
        m, se, _ = st[q]
        return ("%.*f" % (digits, m * scale)) + ((r" $\pm$ %.*f" % (digits, se * scale)) if n > 1 else "")
    _polar_axes(axs[0], r"rigid surface $m_2(\theta)\,/\,10^{%d}$" % em + "\n" + r"$\gamma_s$ = " + pm("gamma_s"))
    _polar_axes(axs[1], r"deformed solid $\mu_2(\theta)\,/\,10^{%d}$" % ed + "\n" + r"$\gamma_d$ = " + pm("gamma_d") +
                r", $\theta_d$ = " + pm("theta_d_rad", 180 / np.pi, 1) + "° (dashed)")
    return fig


def fig3(r):
    """m2 and mu2 for eps = 0.6 and the alpha family: per alpha the mean over the seeds."""
    alphas = np.unique(r.summary["alpha_deg"]) if r.is_study else [r.input["surface"].get("alpha_deg", 0.0)]
    per = [(al, *_curves(_members(r, alpha_deg=al) if r.is_study else [r])) for al in alphas]
    em = _decade(np.concatenate([c[2].ravel() for c in per]))
    ed = _decade(np.concatenate([c[3].ravel() for c in per]))
    fig, axs = plt.subplots(1, 2, subplot_kw=dict(projection="polar"), figsize=(PAGE, 4.1))
    n = 1
    for k, (al, theta, m2, mu2) in enumerate(per):
        st = _stats(r, alpha_deg=al) if r.is_study else _stats(r)
        n = st["gamma_d"][2]
        g, t = st["gamma_d"], st["theta_d_rad"]
        if n > 1:
            lab = r"$\alpha$ = %.1f°: $\gamma_d$ = %.2f $\pm$ %.2f, $\theta_d$ = %.0f $\pm$ %.0f°" % (
                al, g[0], g[1], np.degrees(t[0]), np.degrees(t[1]))
        else:
            lab = r"$\alpha$ = %.1f°: $\gamma_d$ = %.2f, $\theta_d$ = %.0f°" % (al, g[0], np.degrees(t[0]))
        vp.anisotropy_polar((theta, m2.mean(axis=0) / 10.0 ** em, mu2.mean(axis=0) / 10.0 ** ed), axs, titles=False,
                            marks={}, color="C%d" % k, lw=1.3, label=lab)
    _polar_axes(axs[0], r"rigid surface $m_2(\theta)\,/\,10^{%d}$" % em)
    _polar_axes(axs[1], r"deformed solid $\mu_2(\theta)\,/\,10^{%d}$" % ed)
    h, l = axs[1].get_legend_handles_labels()
    fig.legend(h, l, loc="outside lower center", ncol=2)
    return fig


# -- figures 4 to 8: against speed ---------------------------------------------------------------

def cell_artefact_speed(r):
    """v tau/L0 above which the periodic cell's modes with q.v = 0 (k_x = 0) are the only rubbery
    ones: the column k_x = 1 (q_x = 2 pi/L) is glassy once q_x v tau > Einf/E0, i.e.
    v tau/L0 > (Einf/E0)(L/L0)/(2 pi) (docs/reproduction.md, cells larger than the punch).
    None unless the solid is the one-term law."""
    ratio = vr.namelist_value(r.path, "ratio", None)
    if ratio is None:
        return None
    return ratio * vr.namelist_value(r.path, "k_roll", 1.0) / (2 * np.pi)


def _speed_axes(ax, r):
    """Grid, and the range of the cell artefact shaded grey and named just above the axes at its
    right end (outside the data, so never over a curve)."""
    ax.grid(True, which="major", lw=0.3, color="0.88")
    v = cell_artefact_speed(r)
    lo, hi = ax.get_xlim()
    if v is not None and v < hi:
        y0, y1 = ax.get_ylim()
        ax.axvspan(v, hi, color="0.92", zorder=0, lw=0)
        ax.text(1.0, 1.0, "cell artefact", transform=ax.transAxes, ha="right", va="bottom", color="0.4")
        ax.set_xlim(lo, hi)
        ax.set_ylim(y0, y1)


def _theory(r, column):
    return column if column in r.summary.columns else None


def _against_speed(r, quantity, ax, key, ylabel, theory=None, **kw):
    """One curve per member of the family `key` (mean and standard error over the seeds) against
    v tau/L0; the theory column, when the study has it, dashed in the same colours. Returns
    whether the theory was drawn."""
    fmt = {"alpha_deg": ALPHA, "eccentricity": EPS}
    theory = _theory(r, theory) if theory else None
    vp.force_vs_speed(r, quantity, ax, by=[key], speed_scale=_speed_scale(r), speed_label=XLABEL, ylabel=ylabel,
                      theory=theory, theory_label=PERSSON, formats=fmt, ms=2.5, capsize=1.5, lw=1.0, **kw)
    ax.set_title("")
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    return theory is not None


def _legend(ax, reverse=False, where=None, **kw):
    """The family's curves (reversed if asked, to stack as the curves do), then the theory; in
    the axes, or outside them in the figure (where='right' or 'below')."""
    h, l = ax.get_legend_handles_labels()
    curves = [i for i in range(len(l)) if l[i] != PERSSON]
    rest = [i for i in range(len(l)) if l[i] == PERSSON]
    if reverse:
        curves = curves[::-1]
    h, l = [h[i] for i in curves + rest], [l[i] for i in curves + rest]
    if where == "right":
        return ax.legend(h, l, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0, **kw)
    if where == "below":
        return ax.figure.legend(h, l, loc="outside lower center", ncol=len(l), **kw)
    return ax.legend(h, l, **kw)


def fig4(r):
    fig, (a, b) = plt.subplots(1, 2, figsize=(PAGE, 2.9))
    drawn = _against_speed(r, "contact_area_fraction", a, "alpha_deg", r"contact area $A/A_0$",
                           theory="persson_contact_area_fraction")
    _against_speed(r, lambda s: s.mean_separation_m / s.rms_height_m, b, "alpha_deg",
                   r"mean separation $s/h_\mathrm{rms}$")
    _speed_axes(a, r)
    _speed_axes(b, r)
    _legend(a, where="below")
    return fig, drawn


def _single(r, quantity, key, ylabel, theory):
    fig, ax = plt.subplots(figsize=(4.6, 2.9))
    drawn = _against_speed(r, quantity, ax, key, ylabel, theory=theory)
    _speed_axes(ax, r)
    return fig, ax, drawn


def fig5(r):
    fig, ax, drawn = _single(r, "friction_coefficient", "alpha_deg", r"friction $f = F_x/F_n$",
                             "persson_friction_coefficient")
    _legend(ax, where="right")
    return fig, drawn


def fig6(r):
    fig, ax, drawn = _single(r, "friction_coefficient", "eccentricity", r"friction $f = F_x/F_n$",
                             "persson_friction_coefficient")
    _legend(ax, reverse=True, where="right")           # eps descending, as the curves stack
    return fig, drawn


def fig7(r):
    fig, ax, drawn = _single(r, "lateral_force_ratio", "alpha_deg", r"lateral force $F_y/F_n$",
                             "persson_lateral_force_ratio")
    ax.axhline(0, color="k", lw=0.5)
    _legend(ax, where="right")
    return fig, drawn


def fig8(r):
    """sigma1, sigma2 and phi against speed for the alpha family (described, not plotted, in the paper)."""
    fig, axs = plt.subplots(1, 3, figsize=(PAGE, 2.6))
    for ax, q, lab, unit in zip(axs, ("sigma1", "sigma2", "phi_rad"),
                                (r"stretch $\sigma_1$ (major axis of $M$)", r"stretch $\sigma_2$ (minor axis)",
                                 r"rotation $\phi$ [°]"), (None, None, "deg")):
        _against_speed(r, q, ax, "alpha_deg", lab, unit=unit)
        _speed_axes(ax, r)
    axs[2].axhline(0, color="k", lw=0.5)
    _legend(axs[0], where="below")
    return fig, False


# -- friction against the direction of sliding ---------------------------------------------------

def fig11_friction_direction(r, targets=(0.01, 0.1, 1.0)):
    """Friction against the direction of sliding from the PSD's major axis at a few speeds: the
    alpha family of the fig4_5_7 study (v along x, the surface turned by alpha: direction -alpha),
    completed around the circle by the spectrum's symmetries."""
    scale = _speed_scale(r)
    speeds = np.unique(r.summary["speed_m_s"])
    pick = sorted({float(speeds[np.argmin(np.abs(np.log(speeds * scale / t)))]) for t in targets})
    fig, ax = plt.subplots(figsize=(4.2, 4.4), subplot_kw=dict(projection="polar"))
    vp.friction_polar(r, ax, speeds=pick, mirror=True, legend=False, ms=3, capsize=1.5, lw=1.0,
                      formats={"speed_m_s": lambda v: r"$v\tau/L_0$ = %.2g" % (v * scale)})
    ax.set_rmax(1.12 * max(np.max(line.get_ydata()) for line in ax.get_lines() if len(line.get_ydata())))
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.06), ncol=len(pick), handletextpad=0.3, columnspacing=1.0)
    _polar_axes(ax, r"friction $f$ against the direction $\theta$ of $\mathbf{v}$" "\n"
                r"from the PSD's major axis", zero="0°")
    return fig


JOBS = [("fig1.h5", fig1, "fig1"), ("fig2.h5", fig2, "fig2"), ("fig3.h5", fig3, "fig3"),
        ("fig4_5_7.h5", fig4, "fig4"), ("fig4_5_7.h5", fig5, "fig5"), ("fig6.h5", fig6, "fig6"),
        ("fig4_5_7.h5", fig7, "fig7"), ("fig4_5_7.h5", fig8, "fig8_stretch_rotation"),
        ("fig1.h5", fig9_pressure_gap, "fig9_pressure_gap"), ("fig1.h5", fig10_surface_psd, "fig10_surface_psd"),
        ("fig4_5_7.h5", fig11_friction_direction, "fig11_friction_direction")]
NEEDS_FIELDS = (fig1, fig9_pressure_gap, fig10_surface_psd)


def main(results="results/paper", outdir="docs/figures/paper", *only):
    """Draw every figure of JOBS (or those named in `only`) from RESULTS_DIR into OUT_DIR."""
    os.makedirs(outdir, exist_ok=True)
    made, read = 0, {}
    with vp.paper_style():
        for src, draw, name in JOBS:
            if only and name not in only:
                continue
            path = os.path.join(results, src)
            if not os.path.exists(path):
                print("skipped %s: no %s" % (name, path))
                continue
            if path not in read:
                read[path] = veslide.read(path)
            r = read[path]
            if draw in NEEDS_FIELDS and not r.has_fields:
                print("skipped %s: %s has no fields" % (name, path))
                continue
            out = os.path.join(outdir, name)
            drawn = draw(r)
            fig, with_theory = drawn if isinstance(drawn, tuple) else (drawn, False)
            vp.save(fig, out)
            plt.close(fig)
            print("wrote %s.png%s, .pdf, .svg" % (out, " (with Persson's theory)" if with_theory else ""))
            made += 1
    return made


if __name__ == "__main__":
    sys.exit(0 if main(*sys.argv[1:]) > 0 else 1)
