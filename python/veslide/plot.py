"""Plots of veslide results with matplotlib.

Every function takes a `Result` (or arrays: fields and heights indexed [ix, iy], with the cell
side `length_m`), an optional `ax`, draws into it (a new figure when ax is None) and returns the
Axes (its figure is `ax.figure`; a colorbar, when drawn, is `ax.images[0].colorbar`). Axes are
labelled with symbols and units; maps are drawn with x to the right and y up, in mm.
"""
import numpy as np
import matplotlib.pyplot as plt
from matplotlib.ticker import MaxNLocator
import pandas as pd

from . import topography as _topo

SYMBOLS = {
    "contact_area_fraction": r"$A/A_0$",
    "persson_contact_area_fraction": r"$A/A_0$ (Persson)",
    "friction_coefficient": r"$\mu = -\mathbf{F}\cdot\hat{\mathbf{v}}/p_0$",
    "persson_friction_coefficient": r"$\mu$ (Persson)",
    "friction_coefficient_slope": r"$\mu_{\nabla h} = -\langle p\,\nabla h\rangle\cdot\hat{\mathbf{v}}/p_0$",
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
    "eccentricity": r"$\epsilon$",
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
_UNITS_TEX = {"-": "", "": "", "W/m^2": r"W/m$^2$", "1/m": r"m$^{-1}$", "degree": r"$^\circ$", "m/Pa": "m/Pa",
              "um": r"$\mu$m", "µm": r"$\mu$m"}
_SCALE = {"Pa": 1.0, "kPa": 1e-3, "MPa": 1e-6, "m": 1.0, "mm": 1e3, "um": 1e6, "µm": 1e6, "nm": 1e9}


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
        _, ax = plt.subplots(subplot_kw=dict(projection="polar") if polar else None)
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


def _map(ax, values, lx, ly, **kw):
    """values [ix, iy] drawn with x to the right, y up, pixel centres on the grid points, in mm."""
    nx, ny = values.shape
    dx, dy = lx / nx * 1e3, ly / ny * 1e3
    im = ax.imshow(values.T, origin="lower", interpolation="nearest",
                   extent=[-dx / 2, lx * 1e3 - dx / 2, -dy / 2, ly * 1e3 - dy / 2], **kw)
    ax.set_xlabel(r"$x$ [mm]")
    ax.set_ylabel(r"$y$ [mm]")
    ax.set_aspect("equal")
    return im


def _velocity_arrow(ax, source):
    s = getattr(source, "scalars", None) or {}
    if s.get("speed_m_s", 0.0) > 0:
        th = np.radians(s.get("velocity_direction_deg", 0.0))
        x0, y0, r = 0.1, 0.9, 0.07
        ax.annotate("", xy=(x0 + r * np.cos(th), y0 + r * np.sin(th)), xytext=(x0, y0), xycoords="axes fraction",
                    arrowprops=dict(arrowstyle="->", color="tab:red", lw=1.5))
        ax.text(x0, y0 - 0.06, r"$\mathbf{v}$", transform=ax.transAxes, color="tab:red", ha="center", va="top")


def contact_map(source, ax=None, *, length_m=None):
    """Contact cells (p > 0) in black; the title gives A/A0; an arrow shows v (of the rigid
    surface) when the source is a Result of a sliding case."""
    ax = _new_axes(ax)
    p, lx, ly, _ = _field(source, "pressure_pa", length_m)
    contact = p > 0
    _map(ax, contact.astype(float), lx, ly, cmap="gray_r", vmin=0, vmax=1)
    ax.set_title(r"contact (black), $A/A_0$ = %.4f" % contact.mean())
    _velocity_arrow(ax, source)
    return ax


def pressure_map(source, ax=None, *, length_m=None, unit="kPa", cmap="viridis", colorbar=True):
    """The contact pressure map in `unit` ('Pa', 'kPa', 'MPa')."""
    ax = _new_axes(ax)
    p, lx, ly, _ = _field(source, "pressure_pa", length_m)
    im = _map(ax, p * _SCALE[unit], lx, ly, cmap=cmap)
    if colorbar:
        ax.figure.colorbar(im, ax=ax, label=label("pressure_pa", unit))
    ax.set_title(r"pressure, $p_\mathrm{max}$ = %.3g %s" % (p.max() * _SCALE[unit], unit))
    _velocity_arrow(ax, source)
    return ax


def gap_map(source, ax=None, *, length_m=None, unit="um", cmap="magma", colorbar=True):
    """The gap g = w - h + d (zero in contact) in `unit` ('m', 'mm', 'um', 'nm')."""
    ax = _new_axes(ax)
    g, lx, ly, _ = _field(source, "gap_m", length_m)
    im = _map(ax, g * _SCALE[unit], lx, ly, cmap=cmap)
    if colorbar:
        ax.figure.colorbar(im, ax=ax, label=label("gap_m", unit))
    ax.set_title(r"gap, mean separation $\bar{u}$ = %.3g %s" % (g.mean() * _SCALE[unit], unit_tex(unit)))
    return ax


# power below this fraction of the largest is round-off (float64 heights: ~1e-32), not spectrum
ZERO_POWER = 1e-20


def _heights(source, length_m):
    h, lx, ly, _ = _field(source, "height_m", length_m)
    return h, lx, ly


def psd(source, ax=None, *, length_m=None, **kw):
    """The radial (shell-averaged) power spectral density C(q) of the heights, log-log."""
    ax = _new_axes(ax)
    h, lx, ly = _heights(source, length_m)
    q, c = _topo.psd_radial(h, lx, ly)
    keep = c > c.max() * ZERO_POWER
    ax.loglog(q[keep], c[keep], marker=".", **kw)
    ax.set_xlabel(r"$|\mathbf{q}|$ [m$^{-1}$]")
    ax.set_ylabel(r"$C(q)$ [m$^4$]")
    ax.set_title("surface PSD (shell average)")
    return ax


def psd_2d(source, ax=None, *, length_m=None, cmap="viridis", colorbar=True):
    """The 2-D power spectral density log10 C(qx, qy) over qx/q0, qy/q0 (q0 = 2 pi/Lx)."""
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
    ax.set_title("surface PSD")
    return ax


def _around(theta, r):
    """Axial data on [0, pi) drawn around the circle (r(theta + pi) = r(theta)), closed."""
    return np.concatenate([theta, theta + np.pi, theta[:1] + 2 * np.pi]), np.concatenate([r, r, r[:1]])


def anisotropy_polar(source, ax=None, *, normalise=False):
    """m2(theta) of the rigid surface and mu2(theta) of the deformed solid (polar), with their
    major axes theta_s, theta_d dashed. source: a Result with &analysis anisotropy, or a tuple
    (theta_rad, m2, mu2). ax: a pair of polar axes (m2 left, mu2 right; made when None) or one
    polar axes holding both curves. normalise divides each curve by its mean (compare shapes).
    Returns the axes (a pair when drawn in two)."""
    if ax is None:
        _, ax = plt.subplots(1, 2, figsize=(9, 4.5), subplot_kw=dict(projection="polar"))
    pair = np.ndim(ax) == 1
    axes_list = list(ax) if pair else [ax, ax]
    for a in axes_list:
        _new_axes(a, polar=True)
    marks = {}
    if hasattr(source, "anisotropy"):
        if source.anisotropy is None:
            raise ValueError("%s has no /anisotropy (run with &analysis anisotropy = .true.)" % source.path)
        a = source.anisotropy
        theta, m2, mu2 = a["theta_rad"], a["m2_surface"], a["mu2_deformed"]
        s = source.scalars or {}
        marks = {k: s[k] for k in ("theta_s_rad", "theta_d_rad", "gamma_s", "gamma_d") if k in s}
    else:
        theta, m2, mu2 = (np.asarray(v, dtype=float) for v in source)
    for a, r, lab, key, g, title in (
            (axes_list[0], m2, r"$m_2(\theta)$", "theta_s_rad", "gamma_s", "rigid surface"),
            (axes_list[1], mu2, r"$\mu_2(\theta)$", "theta_d_rad", "gamma_d", "deformed solid")):
        r = r / r.mean() if normalise else r
        t, rr = _around(theta, r)
        (line,) = a.plot(t, rr, label=lab + (" / mean" if normalise else "") + ", " + title)
        if key in marks:
            for t0 in (marks[key], marks[key] + np.pi):
                a.plot([t0, t0], [0, rr.max()], ls="--", lw=0.8, color=line.get_color())
        if pair:
            extra = ""
            if key in marks and g in marks:
                extra = "\n" + r"$\gamma$ = %.3f, $\theta$ = %.1f$^\circ$" % (marks[g], np.degrees(marks[key]))
            a.set_title("%s%s of the %s%s" % (lab, " / mean" if normalise else "", title, extra), fontsize="medium")
    if not pair:
        ax.set_title(r"slope variance along $\theta$", fontsize="medium")
        ax.legend(loc="lower left", bbox_to_anchor=(0.75, -0.05), fontsize="small")
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


_GROUP_FORMATS = {"eccentricity": r"$\epsilon$ = %.3g", "alpha_deg": r"$\alpha$ = %.4g$^\circ$",
                  "pressure_pa": r"$p_0$ = %.4g Pa", "seed": "seed %d", "speed_m_s": r"$v$ = %.3g m/s"}


def _groups(table, keys):
    keys = [k for k in keys if k in table.columns and table[k].nunique() > 1]
    if not keys:
        return [("", table)]
    out = []
    for values, part in table.groupby(keys, sort=True):
        values = values if isinstance(values, tuple) else (values,)
        out.append((", ".join(_GROUP_FORMATS.get(k, k + " = %s") % v for k, v in zip(keys, values)), part))
    return out


def _column(table, is_ensemble, quantity):
    """(values, standard errors or None) as numpy arrays."""
    if is_ensemble:
        sem = table.get("sem_" + quantity)
        return table["mean_" + quantity].to_numpy(), (sem.to_numpy() if sem is not None else None)
    return table[quantity].to_numpy(), None


def force_vs_speed(source, quantity="friction_coefficient", ax=None, *, by=None, errorbars=True):
    """A study's `quantity` against the sliding speed (log axis): from /ensemble (mean with the
    standard error over seeds as error bars) when the study has several seeds, else /summary.
    One line per combination of the other parameters that vary (or of the columns `by`)."""
    ax = _new_axes(ax)
    table, ens = _table(source)
    units = table.attrs.get("units", {})
    keys = by if by is not None else ["eccentricity", "alpha_deg", "pressure_pa"] + ([] if ens else ["seed"])
    for lab, part in _groups(table, keys):
        part = part.sort_values("speed_m_s")
        y, e = _column(part, ens, quantity)
        ax.errorbar(part["speed_m_s"].to_numpy(), y, yerr=e if errorbars else None, marker="o", ms=4, capsize=3,
                    label=lab or None)
    ax.set_xscale("log")
    ax.set_xlabel(label("speed_m_s", "m/s"))
    ax.set_ylabel(label(quantity, units.get(("mean_" if ens else "") + quantity, units.get(quantity))))
    if ens:
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
    table["direction_deg"] = 180.0 - (180.0 - (vdir - table["alpha_deg"])) % 360.0   # (-180, 180]
    return table, ens


def friction_polar(source, ax=None, *, quantity="friction_coefficient", speeds=None, errorbars=True):
    """`quantity` (friction coefficient by default) against the direction of sliding measured from
    the major axis of the surface's PSD (velocity direction - alpha), on a polar axes: one curve
    per speed (and eccentricity, pressure). source: a study over alphas_deg (rigid surface turned
    under v along x), or a list of single-case Results (different &motion direction_deg)."""
    ax = _new_axes(ax, polar=True)
    table, ens = _direction_table(source)
    if speeds is not None:
        table = table[np.isin(table["speed_m_s"], np.atleast_1d(speeds))]
    for lab, part in _groups(table, ["speed_m_s", "eccentricity", "pressure_pa"]):
        part = part.sort_values("direction_deg")
        y, e = _column(part, ens, quantity)
        ax.errorbar(np.radians(part["direction_deg"].to_numpy()), y, yerr=e if errorbars else None, marker="o", ms=4,
                    capsize=2, label=lab or None)
    units = table.attrs.get("units", {})
    ax.set_title(SHORT.get(quantity, label(quantity)) + " against the direction of sliding\n"
                 r"from the surface's major axis ($\theta_v - \alpha$)", fontsize="medium")
    if len(ax.get_legend_handles_labels()[0]) > 1:
        ax.legend(loc="lower left", bbox_to_anchor=(0.8, -0.1), fontsize="small")
    return ax
