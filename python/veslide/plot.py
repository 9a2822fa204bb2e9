"""Plots of veslide results with matplotlib.

Every function takes a `Result` (or arrays: fields and heights indexed [ix, iy], with the cell
side `length_m`), an optional `ax`, draws into it (a new figure when ax is None) and returns the
Axes (its figure is `ax.figure`; a colorbar, when drawn, is `ax.images[0].colorbar`). Axes are
labelled with symbols and units; maps are drawn with x to the right and y up, in mm.

For print: `with paper_style(): ...` sets sizes for figures drawn at their printed size (8 pt
text, TrueType fonts in PDF), and `save(fig, "out/name")` writes name.png (300 dpi), name.pdf
and name.svg.
"""
import os

import matplotlib as mpl
import numpy as np
import matplotlib.pyplot as plt
from matplotlib.ticker import MaxNLocator, ScalarFormatter
import pandas as pd

from . import topography as _topo
from .results import parameter_columns, seed_statistics

SYMBOLS = {
    "contact_area_fraction": r"$A/A_0$",
    "persson_contact_area_fraction": r"$A/A_0$ (Persson)",
    "friction_coefficient": r"$\mu = -\mathbf{F}\cdot\hat{\mathbf{v}}/p_0$",
    "persson_friction_coefficient": r"$\mu$ (Persson)",
    "friction_coefficient_slope": r"$\mu_{\nabla h} = -\langle p\,\nabla h\rangle\cdot\hat{\mathbf{v}}/p_0$",
    "friction_hysteresis": r"$\mu_\mathrm{hys} = -\langle p\,\nabla w\rangle\cdot\hat{\mathbf{v}}/p_0$",
    "friction_interfacial": r"$\mu_f \langle p\rangle/p_0$",
    "shear_coefficient": r"$\mu_f$",
    "lateral_force_ratio": r"$F_\perp/p_0 = \mathbf{F}\cdot(\hat{\mathbf{z}}\times\hat{\mathbf{v}})/p_0$",
    "persson_lateral_force_ratio": r"$F_\perp/p_0$ (Persson)",
    "friction_force_pa": r"$F_\parallel$",
    "lateral_force_pa": r"$F_\perp$",
    "force_x_pa": r"$F_x$",
    "force_y_pa": r"$F_y$",
    "dissipated_power_w_m2": r"$-\mathbf{F}\cdot\mathbf{v}$",
    "mean_separation_m": r"$\bar{u}$",
    "max_pressure_pa": r"$p_\mathrm{max}$",
    "mean_pressure_pa": r"$p_0$",
    "pressure_pa": r"$p$",
    "height_m": r"$h$",
    "gap_m": r"$g$",
    "displacement_m": r"$w$",
    "speed_m_s": r"$v$",
    "eccentricity": r"$\varepsilon$",
    "alpha_deg": r"$\alpha$",
    "gamma_s": r"$\gamma_s$",
    "gamma_d": r"$\gamma_d$",
    "theta_s_rad": r"$\theta_s$",
    "theta_d_rad": r"$\theta_d$",
    "sigma1": r"$\sigma_1$",
    "sigma2": r"$\sigma_2$",
    "phi_rad": r"$\phi$",
}
SHORT = {"friction_coefficient": r"$\mu$", "lateral_force_ratio": r"$F_\perp/p_0$",
         "friction_coefficient_slope": r"$\mu_{\nabla h}$"}
_UNITS_TEX = {"-": "", "": "", "W/m^2": r"W/m$^2$", "1/m": r"m$^{-1}$", "degree": r"$^\circ$", "deg": r"$^\circ$",
              "m/Pa": "m/Pa", "um": r"$\mu$m", "µm": r"$\mu$m"}
# a display unit -> its factor from the SI unit of the files (Pa, m, rad)
_SCALE = {"Pa": 1.0, "kPa": 1e-3, "MPa": 1e-6, "m": 1.0, "mm": 1e3, "um": 1e6, "µm": 1e6, "nm": 1e9,
          "rad": 1.0, "deg": 180 / np.pi}

# sizes for figures drawn at their printed size (a journal column is ~3.4 in, a page ~7 in)
PAPER_RC = {
    "font.size": 8, "axes.titlesize": 8, "axes.labelsize": 8, "xtick.labelsize": 7, "ytick.labelsize": 7,
    "legend.fontsize": 7, "legend.title_fontsize": 7, "figure.titlesize": 8, "lines.linewidth": 1.1,
    "lines.markersize": 3, "errorbar.capsize": 1.5, "axes.linewidth": 0.6, "grid.linewidth": 0.4,
    "xtick.major.width": 0.6, "ytick.major.width": 0.6, "xtick.minor.width": 0.4, "ytick.minor.width": 0.4,
    "legend.frameon": True, "legend.framealpha": 0.9, "legend.edgecolor": "0.8", "legend.borderpad": 0.3,
    "legend.labelspacing": 0.3, "legend.handlelength": 1.8,
    "mathtext.fontset": "dejavusans", "pdf.fonttype": 42, "ps.fonttype": 42, "svg.fonttype": "path",
    "savefig.dpi": 300, "savefig.bbox": "tight", "savefig.pad_inches": 0.02, "figure.dpi": 100, "image.interpolation": "nearest", "svg.hashsalt": "veslide",
    "figure.constrained_layout.use": True,
}
FORMATS = ("png", "pdf", "svg")


def paper_style(**overrides):
    """A context (`with paper_style(): ...`) with PAPER_RC (and `overrides`) in force."""
    return mpl.rc_context({**PAPER_RC, **overrides})


def save(fig, path, formats=FORMATS, dpi=300):
    """Write `fig` as path.png (at `dpi`), path.pdf and path.svg (vector; images inside them at
    their own resolution). `path` may end in one of the formats' suffixes. Returns the paths."""
    base, ext = os.path.splitext(str(path))
    if ext.lstrip(".") not in formats:
        base = str(path)
    out = []
    for fmt in formats:
        name = "%s.%s" % (base, fmt)
        fig.savefig(name, dpi=dpi if fmt == "png" else None, metadata=_metadata(fmt))
        out.append(name)
    return out


def _metadata(fmt):
    """No creation date in the vector files, so that a redrawn figure does not differ by it."""
    if fmt == "pdf":
        return {"CreationDate": None}
    if fmt == "svg":
        return {"Date": None}
    return None


def unit_tex(units):
    """A unit string of the files ('W/m^2', '1/m', '-') as matplotlib text ('' for none)."""
    return _UNITS_TEX.get(units, units)


def label(name, units=None):
    """'symbol [unit]' for a scalar, column or field name (`mean_`/`sem_` prefixes understood)."""
    base = name[5:] if name not in SYMBOLS and name.startswith("mean_") and name[5:] in SYMBOLS else name
    text = SYMBOLS.get(base, base.replace("_", " "))
    u = unit_tex(units or "")
    return "%s [%s]" % (text, u) if u else text


def _new_axes(ax, polar=False):
    if ax is None:
        _, ax = plt.subplots(subplot_kw=dict(projection="polar") if polar else None, layout="constrained")
    elif polar and getattr(ax, "name", "") != "polar":
        raise ValueError("this plot needs a polar axes (subplot_kw=dict(projection='polar'))")
    if polar:
        ax.yaxis.set_major_locator(MaxNLocator(3))
        ax.set_rlabel_position(67.5)
    return ax


def _field(source, name, length_m=None):
    """(values [ix, iy], lx, ly, units) of a field of a Result, a DataArray or an array."""
    if hasattr(source, "has_fields"):
        if source.fields is None:
            raise ValueError("%s has no fields (run with &output fields = .true.)" % source.path)
        source = source.fields[name]
    if hasattr(source, "dims"):
        da = source.transpose("x", "y")
        x, y = da["x"].values, da["y"].values
        lx = x[1] * len(x) if len(x) > 1 else float(length_m or 1.0)
        ly = y[1] * len(y) if len(y) > 1 else lx
        return np.asarray(da.values), lx, ly, da.attrs.get("units", "")
    values = np.asarray(source, dtype=float)
    if values.ndim != 2:
        raise ValueError("a field must be a 2-D array indexed [ix, iy]")
    if length_m is None:
        raise ValueError("pass length_m (the cell side along x) with a bare array")
    nx, ny = values.shape
    return values, float(length_m), float(length_m) * ny / nx, ""


def _window(values, lx, ly, window):
    """The part of a periodic field inside window = (x0, y0, width, height) [m] (wrapped around
    the cell), as (values [ix, iy], x of its first column, y of its first row) [m]."""
    nx, ny = values.shape
    dx, dy = lx / nx, ly / ny
    x0, y0, wx, wy = window
    i0, j0 = int(round(x0 / dx)), int(round(y0 / dy))
    ni, nj = max(1, int(round(wx / dx))), max(1, int(round(wy / dy)))
    part = values[np.ix_(np.arange(i0, i0 + ni) % nx, np.arange(j0, j0 + nj) % ny)]
    return part, i0 * dx, j0 * dy


def _map(ax, values, lx, ly, window=None, **kw):
    """values [ix, iy] drawn with x to the right, y up, pixel centres on the grid points, in mm;
    only the periodic window (x0, y0, width, height) [m] when given."""
    nx, ny = values.shape
    dx, dy = lx / nx * 1e3, ly / ny * 1e3
    x0 = y0 = 0.0
    if window is not None:
        values, x0, y0 = _window(values, lx, ly, window)
        x0, y0 = x0 * 1e3, y0 * 1e3
    mx, my = values.shape
    im = ax.imshow(values.T, origin="lower", interpolation="nearest",
                   extent=[x0 - dx / 2, x0 + mx * dx - dx / 2, y0 - dy / 2, y0 + my * dy - dy / 2], **kw)
    ax.set_xlabel(r"$x$ [mm]")
    ax.set_ylabel(r"$y$ [mm]")
    ax.set_aspect("equal")
    return im


def _velocity_arrow(ax, source):
    """An arrow along v (of the rigid surface) in the upper left corner, labelled at its tail."""
    s = getattr(source, "scalars", None) or {}
    if s.get("speed_m_s", 0.0) > 0:
        th = np.radians(s.get("velocity_direction_deg", 0.0))
        d = np.array([np.cos(th), np.sin(th)])
        c, half = np.array([0.16, 0.92]), 0.055
        tail, tip = c - half * d, c + half * d
        ax.annotate("", xy=tip, xytext=tail, xycoords="axes fraction",
                    arrowprops=dict(arrowstyle="-|>", color="tab:red", lw=1.5, mutation_scale=10))
        ax.text(*(tail - 0.025 * d), r"$\mathbf{v}$", transform=ax.transAxes, color="tab:red",
                ha="right" if d[0] >= -1e-9 else "left", va="center" if abs(d[1]) < 0.7 else ("top" if d[1] > 0 else "bottom"),
                bbox=dict(fc="white", ec="none", alpha=0.7, pad=0.3))


def contact_map(source, ax=None, *, length_m=None, window=None, arrow=True):
    """Contact cells (p > 0) in black; the title gives A/A0, named for what it is: for a Result
    the file's primary `contact_area_fraction` (the sub-cell estimate; the black cells are its
    `contact_area_fraction_cells`), else the fraction of cells. An arrow shows v (of the rigid
    surface) when the source is a Result of a sliding case (arrow=False: none). window = (x0, y0,
    width, height) [m] draws that part of the periodic cell only."""
    ax = _new_axes(ax)
    p, lx, ly, _ = _field(source, "pressure_pa", length_m)
    contact = p > 0
    _map(ax, contact.astype(float), lx, ly, window, cmap="gray_r", vmin=0, vmax=1)
    scalars = getattr(source, "scalars", None) or {}
    if "contact_area_fraction" in scalars:          # the file's primary area: the sub-cell estimate
        area, what = scalars["contact_area_fraction"], "sub-cell estimate"
    else:
        area, what = contact.mean(), "fraction of cells"
    ax.set_title(r"contact (black), $A/A_0$ = %.4f (%s)" % (area, what))
    if arrow:
        _velocity_arrow(ax, source)
    return ax


def pressure_map(source, ax=None, *, length_m=None, unit="kPa", cmap="viridis", colorbar=True, window=None,
                 zero_color=None, arrow=True):
    """The contact pressure map in `unit` ('Pa', 'kPa', 'MPa'). zero_color (e.g. 'white'):
    the cells out of contact (p = 0) in that colour instead of the colormap's lowest; window =
    (x0, y0, width, height) [m]: that part of the periodic cell only."""
    ax = _new_axes(ax)
    p, lx, ly, _ = _field(source, "pressure_pa", length_m)
    values = p * _SCALE[unit]
    kw = {}
    if zero_color is not None:
        values = np.ma.masked_where(p <= 0, values)
        kw["cmap"] = mpl.colormaps[cmap].with_extremes(bad=zero_color)
        kw["vmin"] = 0.0
    im = _map(ax, values, lx, ly, window, **(kw or {"cmap": cmap}))
    if colorbar:
        ax.figure.colorbar(im, ax=ax, label=label("pressure_pa", unit))
    ax.set_title(r"pressure, $p_\mathrm{max}$ = %.3g %s" % (p.max() * _SCALE[unit], unit))
    if arrow:
        _velocity_arrow(ax, source)
    return ax


def gap_map(source, ax=None, *, length_m=None, unit="um", cmap="magma", colorbar=True, window=None,
            contact_color=None):
    """The gap g = w - h + d (zero in contact) in `unit` ('m', 'mm', 'um', 'nm'); window =
    (x0, y0, width, height) [m]: that part of the periodic cell only. contact_color (e.g.
    'deepskyblue'): the contact cells (p > 0 for a Result, else g <= 0) in that colour, told apart
    from small gaps."""
    ax = _new_axes(ax)
    g, lx, ly, _ = _field(source, "gap_m", length_m)
    values = g * _SCALE[unit]
    kw = {"cmap": cmap}
    if contact_color is not None:
        if getattr(source, "has_fields", False) and "pressure_pa" in source.fields:
            contact = source.fields["pressure_pa"].transpose("x", "y").values > 0
        else:
            contact = g <= 0
        values = np.ma.masked_where(contact, values)
        kw["cmap"] = mpl.colormaps[cmap].with_extremes(bad=contact_color)
    im = _map(ax, values, lx, ly, window, vmin=0.0, **kw)
    if colorbar:
        ax.figure.colorbar(im, ax=ax, label=label("gap_m", unit))
    ax.set_title(r"gap, mean separation $\bar{u}$ = %.3g %s" % (g.mean() * _SCALE[unit], unit_tex(unit)))
    return ax


# power below this fraction of the largest is round-off (float64 heights: ~1e-32), not spectrum
ZERO_POWER = 1e-20


def _heights(source, length_m):
    h, lx, ly, _ = _field(source, "height_m", length_m)
    return h, lx, ly


def psd(source, ax=None, *, length_m=None, relative=False, hurst=None, q_max=None, **kw):
    """The radial (shell-averaged) power spectral density C(q) of the heights, log-log; against
    q/q0 (q0 = 2 pi/Lx) when `relative`. hurst: a dashed reference line with the self-affine
    slope q^(-2(1+H)) through the middle of the curve. q_max (in the units of the x axis): the
    shells up to it only (e.g. the spectrum's cut-off, whose shell is partly empty). Other
    keywords go to `loglog`."""
    ax = _new_axes(ax)
    h, lx, ly = _heights(source, length_m)
    q, c = _topo.psd_radial(h, lx, ly)
    keep = c > c.max() * ZERO_POWER
    q, c = q[keep], c[keep]
    x = q / (2 * np.pi / lx) if relative else q
    if q_max is not None:
        x, c = x[x <= q_max], c[x <= q_max]
    kw.setdefault("marker", ".")
    ax.loglog(x, c, **kw)
    if hurst is not None and len(x) > 2:
        slope = -2 * (1 + hurst)
        i = len(x) // 2
        xr = np.array([x[len(x) // 8], x[-1]])
        ax.loglog(xr, 2 * c[i] * (xr / x[i]) ** slope, ls="--", lw=0.8, color="0.4",
                  label=r"$\propto q^{-2(1+H)}$, $H$ = %g" % hurst)
    ax.set_xlabel(r"$q/q_0$" if relative else r"$|\mathbf{q}|$ [m$^{-1}$]")
    ax.set_ylabel(r"$C(q)$ [m$^4$]")
    ax.set_title("surface PSD (shell average)")
    return ax


def psd_2d(source, ax=None, *, length_m=None, cmap="viridis", colorbar=True, q_max=None):
    """The 2-D power spectral density log10 C(qx, qy) over qx/q0, qy/q0 (q0 = 2 pi/Lx); q_max
    (in q0) limits both axes to [-q_max, q_max]."""
    ax = _new_axes(ax)
    h, lx, ly = _heights(source, length_m)
    qx, qy, c = _topo.psd_2d(h, lx, ly)
    q0 = 2 * np.pi / lx
    with np.errstate(divide="ignore"):
        lc = np.log10(np.where(c > c.max() * ZERO_POWER, c, np.nan))
    lc[0, 0] = np.nan
    kx, ky, lc = np.fft.fftshift(qx) / q0, np.fft.fftshift(qy) / q0, np.fft.fftshift(lc)
    dkx = kx[1] - kx[0] if len(kx) > 1 else 1.0
    dky = ky[1] - ky[0] if len(ky) > 1 else 1.0
    im = ax.imshow(lc.T, origin="lower", interpolation="nearest", cmap=cmap,
                   extent=[kx[0] - dkx / 2, kx[-1] + dkx / 2, ky[0] - dky / 2, ky[-1] + dky / 2])
    if colorbar:
        ax.figure.colorbar(im, ax=ax, label=r"$\log_{10}\,C(\mathbf{q})$ [m$^4$]")
    ax.set_xlabel(r"$q_x/q_0$")
    ax.set_ylabel(r"$q_y/q_0$")
    ax.set_aspect("equal")
    if q_max is not None:
        ax.set_xlim(-q_max, q_max)
        ax.set_ylim(-q_max, q_max)
    ax.set_title("surface PSD")
    return ax


# radii whose largest value lies in these decades are labelled as they are (0.01 .. 999); others as
# multiples of a power of ten, one factor per polar axes, stated by the caller (title) or the offset text
_PLAIN_DECADES = (-2, 2)


def _drawn_radii(ax):
    """The radii of every line drawn on a polar axes."""
    out = [np.asarray(line.get_ydata(), dtype=float) for line in ax.lines]
    out = [r[np.isfinite(r)] for r in out if np.size(r)]
    return np.concatenate(out) if out else np.array([])


def radial_scale(ax, exponent=None):
    """One radial scale for a polar axes: its tick labels as they are when the largest radius drawn
    lies between 0.01 and 1000, else as multiples of 10^e, e the decade of the largest radius
    (or `exponent`). The factor is shown as the axis' offset text ('x10^e'); a caller that states it
    elsewhere (a title '/ 10^e') hides that with ax.yaxis.offsetText.set_visible(False). Returns e
    (0: no factor)."""
    if exponent is None:
        r = np.abs(_drawn_radii(ax))
        top = r.max() if r.size and r.max() > 0 else 1.0
        exponent = int(np.floor(np.log10(top)))
        if _PLAIN_DECADES[0] <= exponent <= _PLAIN_DECADES[1]:
            exponent = 0
    fmt = ScalarFormatter(useMathText=True, useOffset=False)
    fmt.set_powerlimits((exponent, exponent) if exponent else (-1000, 1000))
    ax.yaxis.set_major_formatter(fmt)
    return exponent


def _scale_text(exponent):
    return r" / $10^{%d}$" % exponent if exponent else ""


def _polar_points(ax, steps=24):
    """(theta, r) points along every line and error bar of a polar axes, each segment divided in
    `steps` (polar lines are drawn straight in (theta, r)), and the largest marker radius [pt]."""
    pieces, marker = [], 0.0
    for line in ax.lines:
        t, r = (np.asarray(v, dtype=float) for v in line.get_data())
        if t.size == 0:
            continue
        if line.get_marker() not in (None, "None", "none", "", " "):
            marker = max(marker, line.get_markersize() / 2)
        pieces.append((t, r))
    for c in ax.collections:
        for seg in getattr(c, "get_segments", lambda: [])():
            seg = np.asarray(seg, dtype=float)
            if seg.ndim == 2 and len(seg):
                pieces.append((seg[:, 0], seg[:, 1]))
    pts = []
    for t, r in pieces:
        ok = np.isfinite(t) & np.isfinite(r)
        t, r = t[ok], r[ok]
        if t.size == 1:
            pts.append(np.column_stack([t, r]))
        elif t.size > 1:
            f = np.linspace(0.0, 1.0, steps, endpoint=False)
            tt = (t[:-1, None] + f * np.diff(t)[:, None]).ravel()
            rr = (r[:-1, None] + f * np.diff(r)[:, None]).ravel()
            pts.append(np.column_stack([np.append(tt, t[-1]), np.append(rr, r[-1])]))
    return (np.concatenate(pts) if pts else np.zeros((0, 2))), marker


def place_radial_labels(ax, candidates=None, pad_pt=1.5):
    """Put the radial tick labels of a polar axes along the ray where they lie clear of the curves.
    For each candidate angle [deg] (default: midway between the 45-degree grid lines first, then
    every 7.5 degrees) the labels are placed and the points of the lines and error bars (with their
    markers) inside their boxes (grown by pad_pt) are counted: the angle with fewest wins, then the
    one with the widest clearance (up to 3 pt; beyond that the earlier candidate). The figure is laid
    out once, so call it after the last curve, legend and title. Returns the angle chosen [deg]."""
    fig = ax.figure
    if candidates is None:
        first = [22.5 + 45 * k for k in range(8)]
        cands = first + [a for a in np.arange(0.0, 360.0, 7.5) if not np.any(np.isclose(a, first))]
    else:
        cands = list(candidates)
    pts, marker = _polar_points(ax)
    px = fig.dpi / 72.0
    grow, enough = (pad_pt + marker) * px, 3.0 * px
    fig.draw_without_rendering()                      # the layout, once
    renderer = fig.canvas.get_renderer()
    xy = ax.transData.transform(pts) if len(pts) else np.zeros((0, 2))
    best = None
    for k, angle in enumerate(cands):
        ax.set_rlabel_position(angle)
        ax.yaxis.get_tightbbox(renderer)              # places the tick labels at the new angle
        lo, hi = sorted(ax.get_ylim())
        hits, clear = 0, np.inf
        for tick in ax.yaxis.get_major_ticks():
            t = tick.label1
            if not (t.get_visible() and t.get_text() and lo <= tick.get_loc() <= hi):
                continue
            b = t.get_window_extent(renderer)
            dx = np.maximum(np.maximum(b.x0 - xy[:, 0], xy[:, 0] - b.x1), 0.0)
            dy = np.maximum(np.maximum(b.y0 - xy[:, 1], xy[:, 1] - b.y1), 0.0)
            d = np.hypot(dx, dy)
            hits += int(np.sum(d <= grow))
            if d.size:
                clear = min(clear, float(d.min()))
        score = (hits, -min(clear, enough), k)
        if best is None or score < best[0]:
            best = (score, angle)
    ax.set_rlabel_position(best[1])
    return best[1]


def _around(theta, r):
    """Axial data on [0, pi) drawn around the circle (r(theta + pi) = r(theta)), closed."""
    return np.concatenate([theta, theta + np.pi, theta[:1] + 2 * np.pi]), np.concatenate([r, r, r[:1]])


def anisotropy_polar(source, ax=None, *, normalise=False, titles=True, marks=None, **kw):
    """m2(theta) of the rigid surface and mu2(theta) of the deformed solid (polar), with their
    major axes theta_s, theta_d dashed. source: a Result with &analysis anisotropy, or a tuple
    (theta_rad, m2, mu2). ax: a pair of polar axes (m2 left, mu2 right; a new figure when None)
    or one polar axes holding both curves. normalise divides each curve by its mean (compare
    shapes). marks: {theta_s_rad, theta_d_rad, gamma_s, gamma_d} to mark (a Result's scalars by
    default); other keywords (color, lw, label, ...) go to the curves.

    Each polar axes gets one radial scale (`radial_scale`): the radii as they are, or as
    multiples of 10^e for all of its curves, the factor stated in the title ('/ 10^e'). With
    titles (the default) the function also titles the axes and puts the radial labels clear of
    the curves (`place_radial_labels`). titles=False leaves titles and the labels' place alone,
    to draw several curves on the same axes: the factor, if any, is then the axis' offset text,
    and the caller titles the axes and calls place_radial_labels after the last curve.

    Returns what it drew into: the pair of axes (the `ax` given, or a numpy array of the two new
    polar Axes) when drawn in two, else the one polar Axes."""
    if ax is None:
        _, ax = plt.subplots(1, 2, figsize=(9, 4.5), subplot_kw=dict(projection="polar"), layout="constrained")
    pair = np.ndim(ax) == 1
    axes_list = list(ax) if pair else [ax, ax]
    for a in axes_list:
        _new_axes(a, polar=True)
    found = {}
    if hasattr(source, "anisotropy"):
        if source.anisotropy is None:
            raise ValueError("%s has no /anisotropy (run with &analysis anisotropy = .true.)" % source.path)
        a = source.anisotropy
        theta, m2, mu2 = a["theta_rad"], a["m2_surface"], a["mu2_deformed"]
        s = source.scalars or {}
        found = {k: s[k] for k in ("theta_s_rad", "theta_d_rad", "gamma_s", "gamma_d") if k in s}
    else:
        theta, m2, mu2 = (np.asarray(v, dtype=float) for v in source)
    marks = found if marks is None else marks
    for a, r, lab, key, title in (
            (axes_list[0], m2, r"$m_2(\theta)$", "theta_s_rad", "rigid surface"),
            (axes_list[1], mu2, r"$\mu_2(\theta)$", "theta_d_rad", "deformed solid")):
        r = r / r.mean() if normalise else r
        t, rr = _around(theta, r)
        line_kw = dict(kw)
        line_kw.setdefault("label", lab + (" / mean" if normalise else "") + ", " + title)
        (line,) = a.plot(t, rr, **line_kw)
        if key in marks:
            for t0 in (marks[key], marks[key] + np.pi):
                a.plot([t0, t0], [0, rr.max()], ls="--", lw=0.8, color=line.get_color())
    for k, a in enumerate(axes_list[:2] if pair else axes_list[:1]):
        e = radial_scale(a)
        if not titles:
            continue
        a.yaxis.offsetText.set_visible(False)
        if pair:
            lab, key, g, title = ((r"$m_2(\theta)$", "theta_s_rad", "gamma_s", "rigid surface") if k == 0 else
                                  (r"$\mu_2(\theta)$", "theta_d_rad", "gamma_d", "deformed solid"))
            extra = ""
            if key in marks and g in marks:
                extra = "\n" + r"$\gamma$ = %.3f, $\theta$ = %.1f°" % (marks[g], np.degrees(marks[key]))
            a.set_title("%s, %s%s%s" % (title, lab, " / mean" if normalise else _scale_text(e), extra),
                        fontsize="medium")
        else:
            a.set_title(r"slope variance along $\theta$%s" % ("" if normalise else _scale_text(e)),
                        fontsize="medium")
            a.legend(loc="upper left", bbox_to_anchor=(1.05, 1.0), fontsize="small")
        place_radial_labels(a)
    return ax


def _table(source):
    """(table, is_ensemble) from a study Result (its /ensemble if any, else /summary) or a
    DataFrame."""
    if isinstance(source, pd.DataFrame):
        return source, "n_seeds" in source.columns     # /ensemble has n_seeds, /summary does not
    if getattr(source, "ensemble", None) is not None:
        return source.ensemble, True
    if getattr(source, "summary", None) is not None:
        return source.summary, False
    raise ValueError("a study result (with /summary) or a DataFrame is needed")


_GROUP_FORMATS = {"eccentricity": r"$\varepsilon$ = %.3g", "alpha_deg": r"$\alpha$ = %.4g$^\circ$",
                  "pressure_pa": r"$p_0$ = %.4g Pa", "seed": "seed %d", "speed_m_s": r"$v$ = %.3g m/s",
                  "temperature_c": r"$T$ = %.4g °C"}


def _format(fmt, value):
    return fmt(value) if callable(fmt) else fmt % value


def _groups(table, keys, formats=None):
    keys = [k for k in keys if k in table.columns and table[k].nunique() > 1]
    if not keys:
        return [("", table)]
    fmts = {**_GROUP_FORMATS, **(formats or {})}
    out = []
    for values, part in table.groupby(keys, sort=True):
        values = values if isinstance(values, tuple) else (values,)
        out.append((", ".join(_format(fmts.get(k, k + " = %s"), v) for k, v in zip(keys, values)), part))
    return out


def _column(table, is_ensemble, quantity):
    """(values, standard errors or None) as numpy arrays."""
    if is_ensemble:
        sem = table.get("sem_" + quantity)
        return table["mean_" + quantity].to_numpy(), (sem.to_numpy() if sem is not None else None)
    return table[quantity].to_numpy(), None


def seed_means(summary, values, name="value"):
    """An /ensemble-like DataFrame of `values` (one per row of a study's /summary, e.g. a ratio
    of two columns): per combination of the other parameters, `n_seeds` and the mean and standard
    error over the seeds as columns mean_<name>, sem_<name> (0 for a single seed)."""
    keys = [k for k in parameter_columns(summary) if k not in ("case", "seed")]
    df = summary[keys].copy()
    df[name] = np.asarray(values, dtype=float)
    rows = []
    for group, part in df.groupby(keys, sort=True):
        mean, sem, _, _ = seed_statistics(part[name].to_numpy(), name)
        rows.append((*(group if isinstance(group, tuple) else (group,)), mean, len(part), sem))
    return pd.DataFrame(rows, columns=keys + ["mean_" + name, "n_seeds", "sem_" + name])


def force_vs_speed(source, quantity="friction_coefficient", ax=None, *, by=None, errorbars=True, speed_scale=1.0,
                   speed_label=None, unit=None, theory=None, theory_label=None, formats=None, ylabel=None, **kw):
    """A study's `quantity` against the sliding speed (log axis): from /ensemble (mean with the
    standard error over seeds as error bars) when the study has several seeds, else /summary.
    One line per combination of the other parameters that vary (or of the columns `by`).

    quantity     a column name, or a function of the /summary DataFrame giving one value per case
                 (e.g. lambda s: s.mean_separation_m / s.rms_height_m), averaged over the seeds here.
    speed_scale  x = speed * speed_scale (e.g. tau/L0 for v tau/L0), labelled `speed_label`.
    unit         display unit of the quantity ('kPa', 'um', 'deg' for an angle in rad, ...).
    theory       a column drawn dashed in the colour of each line (e.g. 'persson_friction_coefficient'),
                 with one legend entry `theory_label`.
    formats      {column: format string or function} of the lines' legend labels.
    Other keywords (ms, capsize, lw, ...) go to `errorbar`."""
    ax = _new_axes(ax)
    table, ens = _table(source)
    units = table.attrs.get("units", {})
    if callable(quantity):
        if ens and isinstance(source, pd.DataFrame):
            raise ValueError("a function of the cases needs a study result or its /summary, not /ensemble")
        summary = source if isinstance(source, pd.DataFrame) else source.summary
        table, ens = seed_means(summary, quantity(summary)), True
        quantity, units = "value", {}
    # one line per combination of the parameters other than the speed (temperature_c in the
    # studies of a material with a temperature shift)
    params = parameter_columns(table)
    keys = by if by is not None else ([k for k in params if k not in ("case", "seed", "speed_m_s")
                                       and k in table.columns] + ([] if ens else ["seed"]))
    scale = _SCALE[unit] if unit else 1.0
    kw = {"marker": "o", "ms": 4, "capsize": 3, **kw}
    for lab, part in _groups(table, keys, formats):
        part = part.sort_values("speed_m_s")
        x = part["speed_m_s"].to_numpy() * speed_scale
        y, e = _column(part, ens, quantity)
        bars = ax.errorbar(x, y * scale, yerr=e * scale if (errorbars and e is not None) else None, label=lab or None,
                           **kw)
        if theory is not None:
            t, _ = _column(part, ens, theory)
            ax.plot(x, t * scale, ls="--", color=bars.lines[0].get_color())
    if theory is not None:
        ax.plot([], [], ls="--", color="0.3", label=theory_label or "dashed: " + label(theory))
    ax.set_xscale("log")
    ax.set_xlabel(speed_label or (label("speed_m_s", "m/s") if speed_scale == 1.0 else "scaled speed"))
    u = unit or units.get(("mean_" if ens else "") + quantity, units.get(quantity))
    ax.set_ylabel(ylabel or label(quantity, u))
    if ens and table["n_seeds"].max() > 1:
        n = table["n_seeds"]
        ax.set_title("mean over %s seeds, error bars: standard error" % (n.iloc[0] if n.nunique() == 1 else "the"))
    if len(ax.get_legend_handles_labels()[0]) > 1:
        ax.legend(fontsize="small")
    return ax


def friction_vs_speed(source, ax=None, **kw):
    """The friction coefficient against speed (see `force_vs_speed`)."""
    return force_vs_speed(source, "friction_coefficient", ax, **kw)


def lateral_vs_speed(source, ax=None, **kw):
    """The lateral force ratio against speed (see `force_vs_speed`)."""
    return force_vs_speed(source, "lateral_force_ratio", ax, **kw)


def _direction_table(source):
    """Rows with the sliding direction from the surface's major axis, `direction_deg` =
    velocity_direction_deg - alpha_deg in (-180, 180], from a study or a list of single-case
    Results."""
    if isinstance(source, (list, tuple)):
        rows = []
        for r in source:
            surface = (r.input or {}).get("surface", {}) or {}
            row = dict(r.scalars)
            row["alpha_deg"] = float(surface.get("alpha_deg", 0.0))
            row["eccentricity"] = float(surface.get("eccentricity", 1.0))
            rows.append(row)
        table, ens = pd.DataFrame(rows), False
        table.attrs["units"] = dict(source[0].scalars.units) if source else {}
    else:
        table, ens = _table(source)
        units = table.attrs.get("units", {})
        table = table.copy()
        table.attrs["units"] = units
    vdir = table["mean_velocity_direction_deg" if ens else "velocity_direction_deg"]
    table["direction_deg"] = _wrap(vdir - table["alpha_deg"])
    return table, ens


def _wrap(deg):
    """Angles in degrees into (-180, 180]."""
    return 180.0 - (180.0 - np.asarray(deg, dtype=float)) % 360.0


# quantities odd under a mirror image of the surface about its PSD's axes (they change sign)
_ODD = ("lateral_force_ratio", "lateral_force_pa", "persson_lateral_force_ratio")


def _mirrored(direction_deg, values, errors, odd):
    """The images of measured directions under the symmetries of an elliptic spectrum: q -> -q
    (theta + 180, quantity unchanged) and the mirror about its axes (-theta, 180 - theta; a
    quantity that is odd under reflection changes sign). Returns the directions not measured
    already, with their values and errors."""
    seen = set(np.round(direction_deg, 6))
    out = []
    for th, v, e in zip(direction_deg, values, errors):
        for image, sign in ((th + 180.0, 1.0), (-th, -1.0 if odd else 1.0), (180.0 - th, -1.0 if odd else 1.0)):
            key = round(float(_wrap(image)), 6)
            if key not in seen:
                seen.add(key)
                out.append((float(_wrap(image)), sign * v, e))
    out.sort()
    return [np.array(c) for c in zip(*out)] if out else [np.array([])] * 3


def friction_polar(source, ax=None, *, quantity="friction_coefficient", speeds=None, errorbars=True, mirror=False,
                   formats=None, legend=True, **kw):
    """`quantity` (friction coefficient by default) against the direction of sliding measured from
    the major axis of the surface's PSD (velocity direction - alpha), on a polar axes: one curve
    per speed (and eccentricity, pressure). source: a study over alphas_deg (rigid surface turned
    under v along x), or a list of single-case Results (different &motion direction_deg).
    mirror: also draw (open markers, joined by the curve) the directions that follow from the
    measured ones by the symmetries of an elliptic spectrum, C(q) = C(-q) and its mirror images
    about its axes (ensemble statements: exact for the mean over many surfaces); e.g. alpha
    0..90 deg gives the full circle. formats: legend labels as in `force_vs_speed`. Other
    keywords (ms, capsize, ...) go to `errorbar`. The angle theta_v - alpha is in the title, the
    radial scale is one (`radial_scale`, a factor 10^e stated in the title) and its labels are put
    clear of the curves (`place_radial_labels`; call it again after changing rmax). Returns the
    axes."""
    ax = _new_axes(ax, polar=True)
    table, ens = _direction_table(source)
    if speeds is not None:
        table = table[np.isin(table["speed_m_s"], np.atleast_1d(speeds))]
    kw = {"marker": "o", "ms": 4, "capsize": 2, **kw}
    for lab, part in _groups(table, ["speed_m_s", "eccentricity", "pressure_pa"], formats):
        part = part.sort_values("direction_deg")
        th = part["direction_deg"].to_numpy()
        y, e = _column(part, ens, quantity)
        bars = ax.errorbar(np.radians(th), y, yerr=e if errorbars else None, label=lab or None,
                           **{"ls": "none" if mirror else "-", **kw})
        if mirror:
            color = bars.lines[0].get_color()
            mth, my, me = _mirrored(th, y, e if e is not None else np.zeros_like(y), quantity in _ODD)
            if len(mth):
                ax.errorbar(np.radians(mth), my, yerr=me if (errorbars and e is not None) else None,
                            **{**kw, "ls": "none", "mfc": "white", "color": color})
            at = np.concatenate([th, mth])
            ay = np.concatenate([y, my])
            order = np.argsort(at)
            at, ay = at[order], ay[order]
            ax.plot(np.radians(np.append(at, at[0] + 360.0)), np.append(ay, ay[0]), color=color,
                    lw=kw.get("lw", mpl.rcParams["lines.linewidth"]))
    e = radial_scale(ax)
    ax.yaxis.offsetText.set_visible(False)
    ax.set_title(SHORT.get(quantity, label(quantity)) + _scale_text(e) + r" against $\theta_v - \alpha$",
                 fontsize="medium")
    if legend and len(ax.get_legend_handles_labels()[0]) > 1:
        ax.legend(loc="upper left", bbox_to_anchor=(1.05, 1.0), fontsize="small")
    place_radial_labels(ax)
    return ax


def refinement(ref, scalar="contact_area_fraction", ax=None, *, cells=True, **kw):
    """A scalar of a `veslide.refine` / `veslide.convergence` result against the grid (log axis:
    nx when `cells`, else the cell side in metres): the values on each grid, the extrapolated value
    dashed and the error band of the finest grid as its error bar. Other keywords (marker, ms, ...)
    go to the values' `plot`."""
    ax = _new_axes(ax)
    t, e = ref.table, ref.estimate.loc[scalar]
    x = t.index.to_numpy() if cells else t["cell_m"].to_numpy()
    ax.plot(x, t[scalar].to_numpy(), **{"marker": "o", "ms": 4, **kw})
    if np.isfinite(e["error"]):
        ax.errorbar([x[-1]], [e["finest"]], yerr=[e["error"]], capsize=4, color="k", lw=1)
    if np.isfinite(e["extrapolated"]):
        ax.axhline(e["extrapolated"], ls="--", color="0.4", lw=1)
    ax.set_xscale("log")
    if cells:                                   # every grid labelled by its nx
        crowded = len(x) > 5 or (len(x) > 1 and np.min(np.diff(np.log(np.sort(x)))) < np.log(1.5))
        ax.set_xticks(x, [str(int(v)) for v in x], rotation=45 if crowded else 0)   # 768, 1024 apart
        ax.minorticks_off()
    ax.set_xlabel("$n_x$ (cells along $x$)" if cells else label("cell_m", "m"))
    ax.set_ylabel(label(scalar, e["units"]))
    order = "" if not np.isfinite(e["observed_order"]) else ", observed order %.2g" % e["observed_order"]
    ax.set_title("error band of the finest grid %.2g%s" % (e["error"], order), fontsize="small")
    return ax


def modulus_vs_frequency(material, ax=None, *, frequency_hz=None, storage_pa=None, loss_pa=None, temperature_c=None,
                         unit="MPa", n=400):
    """A material's E'(f) and E''(f) (log axes, solid and dashed lines) and tan delta (dotted, on a
    second axis to the right), with the data as markers: those given, else the data of its fit
    (`material.fit`, moved from the reference to the temperature drawn, f / a_T). Drawn at
    `temperature_c` (default: the material's). Returns (ax, ax_tan)."""
    ax = _new_axes(ax)
    fit = getattr(material, "fit", None)
    if frequency_hz is None and fit is not None:
        frequency_hz = fit.frequency_hz / material.shift_factor(temperature_c)
        storage_pa, loss_pa = fit.storage_pa, fit.loss_pa
    if frequency_hz is not None:
        fd = np.asarray(frequency_hz, dtype=float)
        lo, hi = fd.min() / 3, fd.max() * 3
    else:
        t = material.times_s * material.shift_factor(temperature_c)
        lo, hi = 0.01 / (2 * np.pi * t.max()), 100 / (2 * np.pi * t.min())
    f = np.geomspace(lo, hi, n)
    e = material.modulus(f, temperature_c)
    k = _SCALE[unit]
    ax.plot(f, k * e.real, "-", color="C0", label="$E'$")
    ax.plot(f, k * e.imag, "--", color="C1", label="$E''$")
    ax_tan = ax.twinx()
    ax_tan.plot(f, e.imag / e.real, ":", color="C2", label=r"$\tan\delta$")
    if frequency_hz is not None:
        s, lss = np.asarray(storage_pa, dtype=float), np.asarray(loss_pa, dtype=float)
        ax.plot(fd, k * s, "o", color="C0", ms=3, mfc="none", label="$E'$ data")
        ax.plot(fd, k * lss, "s", color="C1", ms=3, mfc="none", label="$E''$ data")
        ax_tan.plot(fd, lss / s, "^", color="C2", ms=3, mfc="none", label=r"$\tan\delta$ data")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax_tan.set_yscale("log")
    ax.set_xlabel("$f$ [Hz]")
    ax.set_ylabel("$E'$, $E''$ [%s]" % unit_tex(unit))
    ax_tan.set_ylabel(r"$\tan\delta$")
    t = material.temperature_c if temperature_c is None else temperature_c
    t = material.reference_temperature_c if t is None else t
    if t is not None:
        ax.set_title("%g $^\\circ$C" % t, fontsize="small")
    lines = ax.get_lines() + ax_tan.get_lines()
    ax.legend(lines, [ln.get_label() for ln in lines], fontsize="small")
    return ax, ax_tan
