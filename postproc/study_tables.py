#!/usr/bin/env python3
"""Tables and figures of the studies in inputs/studies/ (docs/reproduction.md).

usage: python postproc/study_tables.py band|cells RESULTS_DIR OUT_DIR
  band   RESULTS_DIR holds zeta1_1.h5 .. zeta1_8.h5 (inputs/studies/band): gamma_d, theta_d,
         gamma_s, sigma1, sigma2, phi of the figure-2 scene against the lower band edge zeta1,
         mean +- standard error over seeds; writes OUT_DIR/band_zeta1.png and prints a table.
  cells  RESULTS_DIR holds L1_n256.h5, L2_n512.h5, L4_n1024.h5, ... (inputs/studies/cells) and
         their references on the elastic solid E = Einf, E_L1_n256.h5, ...: the fast and the slow
         limit against alpha for cells of L0 .. 8 L0; writes OUT_DIR/cells_alpha.png.
  cellspeed  the same tables for inputs/studies/cellspeed (intermediate speeds, L0 and 4 L0);
         writes OUT_DIR/cellspeed_alpha.png.
  persson  every study in RESULTS_DIR run with &analysis persson (e.g. results/paper: fig4_5_7.h5,
         fig6.h5): the boundary elements against Persson's theory on the same surfaces, friction,
         contact area and lateral force against speed per alpha (or eps), ratios BEM/theory taken
         seed by seed, and the solve times; writes OUT_DIR/<RESULTS_DIR's name>_persson.png.
Tables are markdown, printed to stdout and written to RESULTS_DIR/table.md (persson: persson.md).
Figures are drawn in the paper style (7 in across, 8 pt text) as PNG at 300 dpi, with short titles:
what they show is said in docs/reproduction.md.
"""
import glob
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(os.path.dirname(HERE), "python"), HERE]   # this checkout's package first
import veslide.plot as vp  # noqa: E402
import veslide_results as vr  # noqa: E402

PAGE = 7.0       # figures drawn at their printed size (7 in across, 8 pt text: vp.paper_style), PNG 300 dpi

def stats(x, name=""):
    """mean, standard error, min, max over seeds (veslide_results.seed_stats)."""
    return vr.seed_stats(x, name)


def psd(qx, qy, hurst=0.8, eps=1.0, alpha=0.0, q_low=1.0, q_roll=1.0, q_cut=64.0):
    """C(q)/C0 of appendix B as src/physics/veslide_surface.f90 evaluates it (q in any common unit)."""
    q2 = qx * qx + qy * qy
    a2 = 2.0 / (1.0 + eps ** 2); b2 = 2.0 - a2
    u = np.cos(alpha) * qx + np.sin(alpha) * qy
    v = -np.sin(alpha) * qx + np.cos(alpha) * qy
    tqq = u * u / a2 + v * v / b2
    s = np.where(q2 <= q_roll ** 2, q2, q_roll ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        c = (tqq / np.where(s > 0, s, 1.0)) ** (-(hurst + 1.0))
    inside = (q2 >= q_low ** 2 * (1 - 1e-12)) & (q2 <= q_cut ** 2 * (1 + 1e-12))
    return np.where(inside, c, 0.0)


def lattice(kmax):
    k = np.arange(-kmax, kmax + 1, dtype=float)
    return np.meshgrid(k, k, indexing="xy")


def fmt(m, se, scale=1.0, digits=3):
    return "%.*f +- %.*f" % (digits, m * scale, digits, se * scale)


def fmt_sci(m, se):
    """(m +- se)eN with the exponent of the larger of the two."""
    big = max(abs(m), abs(se))
    e = int(np.floor(np.log10(big))) if big > 0 else 0
    return "(%.2f +- %.2f)e%d" % (m / 10.0 ** e, se / 10.0 ** e, e)


# ----------------------------------------------------------------------------------------- band

def band(results, outdir):
    files = sorted(glob.glob(os.path.join(results, "zeta1_*.h5")),
                   key=lambda p: int(re.search(r"zeta1_(\d+)", p).group(1)))
    if not files:
        raise SystemExit("no zeta1_*.h5 in " + results)
    kx, ky = lattice(64)
    kk = np.hypot(kx, ky)
    slope = (kx ** 2 + ky ** 2) * psd(kx, ky)
    rows, per_seed = [], {}
    for p in files:
        s = vr.table(p)
        z1 = vr.namelist_value(p, "zeta1", 1.0)
        z2 = vr.namelist_value(p, "zeta2", 64.0)
        inband = (kk >= z1 * (1 - 1e-12)) & (kk <= z2 * (1 + 1e-12))
        r = dict(zeta1=z1, zeta2=z2, n=len(s["seed"]), modes=int(inband.sum()),
                 share=slope[inband].sum() / slope.sum())
        for q in ("gamma_s", "gamma_d", "theta_d_rad", "sigma1", "sigma2", "phi_rad",
                  "patch_gamma", "patch_theta_rad", "contact_area_fraction", "friction_coefficient"):
            r[q] = stats(s[q], q)
        rows.append(r)
        per_seed[z1] = s
    lines = ["| zeta1 | wavevectors in band | share of slope trace | gamma_s | gamma_d | gamma_d range"
             " | theta_d [deg] | theta_d range [deg] | sigma1 | sigma2 | phi [deg] |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        d = np.degrees
        lines.append("| %g | %d | %.3f | %s | %s | %.2f-%.2f | %s | %.0f-%.0f | %s | %s | %s |" % (
            r["zeta1"], r["modes"], r["share"], fmt(*r["gamma_s"][:2]), fmt(*r["gamma_d"][:2]),
            r["gamma_d"][2], r["gamma_d"][3], fmt(*r["theta_d_rad"][:2], scale=180 / np.pi, digits=1),
            d(r["theta_d_rad"][2]), d(r["theta_d_rad"][3]), fmt(*r["sigma1"][:2]), fmt(*r["sigma2"][:2]),
            fmt(*r["phi_rad"][:2], scale=180 / np.pi, digits=1)))
    # paired differences between neighbouring lower edges (the same surfaces and solves)
    z = sorted(per_seed)
    lines += ["", "Paired change of gamma_d per seed when zeta1 rises by one (mean +- SE over seeds):", ""]
    for a, b in zip(z[:-1], z[1:]):
        dg = per_seed[b]["gamma_d"] - per_seed[a]["gamma_d"]
        lines.append("- %g -> %g: %+.4f +- %.4f" % (a, b, dg.mean(), dg.std(ddof=1) / np.sqrt(len(dg))))
    r0 = rows[0]
    lines += ["", "Same ensemble, zeta1 = %g: A/A0 = %s, f = %s, patch gamma = %s, patch theta = %s deg"
              % (r0["zeta1"], fmt(*r0["contact_area_fraction"][:2], digits=4),
                 fmt(*r0["friction_coefficient"][:2], digits=4), fmt(*r0["patch_gamma"][:2]),
                 fmt(*r0["patch_theta_rad"][:2], scale=180 / np.pi, digits=1))]
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(results, "table.md"), "w") as fh:
        fh.write(table + "\n")

    zz = np.array([r["zeta1"] for r in rows])
    with vp.paper_style():
        _band_figure(rows, per_seed, zz, outdir)


def _band_figure(rows, per_seed, zz, outdir):
    fig, (a, b) = plt.subplots(1, 2, figsize=(PAGE, 2.9))
    for k, r in enumerate(rows):
        s = per_seed[r["zeta1"]]
        jitter = 0.12 * (np.arange(len(s["seed"])) / max(1, len(s["seed"]) - 1) - 0.5)
        a.plot(r["zeta1"] + jitter, s["gamma_d"], ".", color="0.7", ms=3,
               label="single surfaces" if k == 0 else None)
        td = np.degrees(r["theta_d_rad"][0] + (s["theta_d_rad"] - r["theta_d_rad"][0]
                                                - np.pi * np.round((s["theta_d_rad"] - r["theta_d_rad"][0]) / np.pi)))
        b.plot(r["zeta1"] + jitter, td, ".", color="0.7", ms=3)
    g = np.array([r["gamma_d"][:2] for r in rows])
    gs = np.array([r["gamma_s"][:2] for r in rows])
    t = np.array([r["theta_d_rad"][:2] for r in rows])
    n = rows[0]["n"]
    a.errorbar(zz, g[:, 0], yerr=g[:, 1], fmt="o-", ms=3, color="C0",
               label=r"mean $\pm$ SE over %d seeds" % n)
    a.errorbar(zz, gs[:, 0], yerr=gs[:, 1], fmt="s--", color="C2", ms=3,
               label=r"$\gamma_s$ (rigid surface), mean $\pm$ SE")
    a.axhline(0.37, color="C3", lw=1, ls=":", label=r"paper ($\gamma_d$ = 0.37, $\theta_d$ = 90°)")
    b.errorbar(zz, np.degrees(t[:, 0]), yerr=np.degrees(t[:, 1]), fmt="o-", ms=3, color="C0")
    b.axhline(90, color="C3", lw=1, ls=":")
    for ax in (a, b):
        ax.set_xlabel(r"lower band edge $\zeta_1$ (band $\zeta_1 q_0$ .. $64 q_0$)")
        ax.grid(True, lw=0.3, color="0.88")
    a.set_ylabel(r"$\gamma = \lambda_\min / \lambda_\max$")
    a.set_ylim(0, 1.05)
    a.set_title(r"degree of anisotropy $\gamma_d$ (deformed)")
    b.set_ylabel(r"$\theta_d$ [°] (0: along $\mathbf{v}$)")
    b.set_title(r"major axis $\theta_d$ (deformed)")
    h, lab = a.get_legend_handles_labels()
    fig.legend(h, lab, loc="outside lower center", ncol=2)
    out = os.path.join(outdir, "band_zeta1.png")
    vp.save(fig, out, formats=("png",)); plt.close(fig)
    print("wrote", out)


# ---------------------------------------------------------------------------------------- cells

def rubbery_share(m, eps, alpha_deg, hurst=0.8):
    """Expected share of the slope-tensor trace carried by the modes with q.v = 0 (k_x = 0) for
    v along x, on a cell of m L0 with k_low = 1, k_roll = m, k_cut = 64 m (units 2 pi/L)."""
    kx, ky = lattice(64 * m)
    s = (kx ** 2 + ky ** 2) * psd(kx, ky, hurst, eps, np.radians(alpha_deg), 1.0, float(m), 64.0 * m)
    return s[kx == 0].sum() / s.sum()


def _cell_table(p):
    s = vr.table(p)
    s["sep_over_h"] = s["mean_separation_m"] / s["rms_height_m"]
    s["sigma_ratio"] = s["sigma1"] / s["sigma2"]
    s["vtau_l0"] = vr.dimensionless_speed(p, s["speed_m_s"])
    return s


def _paired(s, sel, quantity, ref, ref_sel_of):
    """Per-case ratio quantity / ref[quantity] of the case with the same seed (ref_sel_of(seed))."""
    out = []
    for k in np.flatnonzero(sel):
        r = ref_sel_of(int(s["seed"][k]))
        if r.sum() == 1:
            out.append(s[quantity][k] / ref[quantity][r][0])
    return np.array(out)


def cells(results, outdir):
    files = sorted(glob.glob(os.path.join(results, "L*_n*.h5")),
                   key=lambda p: tuple(int(x) for x in re.search(r"L(\d+)_n(\d+)", p).groups()))
    if not files:
        raise SystemExit("no L*_n*.h5 in " + results)
    data = []
    for p in files:
        m, n = (int(x) for x in re.search(r"L(\d+)_n(\d+)", p).groups())
        ref = os.path.join(results, "E_" + os.path.basename(p))
        data.append(dict(m=m, n=n, s=_cell_table(p), e=_cell_table(ref) if os.path.exists(ref) else None,
                         eps=vr.namelist_value(p, "eccentricity", 1.0)))
    speeds = sorted({float(x) for d in data for x in np.unique(d["s"]["vtau_l0"])}, reverse=True)
    lines = ["Seeds per case: " + ", ".join("L = %d L0 (%d^2): %d" % (d["m"], d["n"], len(np.unique(d["s"]["seed"])))
                                             for d in data)]
    res = {}   # (m, n, speed, alpha) -> statistics, for the figure
    for speed in speeds:
        fast = speed >= 1.0
        lines += ["", "v tau/L0 = %g (mean +- SE over seeds; ratios taken seed by seed):" % speed, "",
                  "| L/L0 | grid | alpha [deg] | k_x = 0 share of trace | A/A0 | A(alpha)/A(0) | "
                  + ("A / A(E = Einf) | " if fast else "") + "s/h_rms | f | F_y/F_n | sigma1/sigma2 | "
                  + ("sigma1/sigma2 (E = Einf) | " if fast else "") + "phi [deg] |"
                  + (" phi [deg] (E = Einf) |" if fast else ""),
                  "|---" * (14 if fast else 11) + "|"]
        for d in data:
            s, e = d["s"], d["e"]
            sv = np.isclose(s["vtau_l0"], speed, rtol=1e-6)
            if not sv.any():
                continue
            for al in np.unique(s["alpha_deg"][sv]):
                sel = sv & np.isclose(s["alpha_deg"], al)
                a0 = sv & np.isclose(s["alpha_deg"], 0.0)
                st = {q: stats(s[q][sel], q) for q in ("contact_area_fraction", "sep_over_h", "friction_coefficient",
                                                         "lateral_force_ratio", "sigma_ratio", "phi_rad")}
                r0 = stats(_paired(s, sel, "contact_area_fraction", s, lambda sd: a0 & (s["seed"] == sd)))
                row = "| %d | %d^2 | %.1f | %.4f | %s | %s | " % (
                    d["m"], d["n"], al, rubbery_share(d["m"], d["eps"], al),
                    fmt(*st["contact_area_fraction"][:2], digits=5), fmt(*r0[:2], digits=4))
                rec = dict(a_over_a0=r0, sigma_ratio=st["sigma_ratio"], f=st["friction_coefficient"])
                if fast:
                    if e is not None:
                        esel = lambda sd: np.isclose(e["alpha_deg"], al) & (e["seed"] == sd)
                        re_ = stats(_paired(s, sel, "contact_area_fraction", e, esel))
                        rec["a_over_einf"] = re_
                        rec["sigma_ratio_einf"] = stats(e["sigma_ratio"][np.isclose(e["alpha_deg"], al)])
                        rec["phi_einf"] = stats(e["phi_rad"][np.isclose(e["alpha_deg"], al)], "phi_rad")
                        row += "%s | " % fmt(*re_[:2], digits=4)
                    else:
                        row += "- | "
                row += "%s | %s | %s | %s | " % (
                    fmt(*st["sep_over_h"][:2]), fmt_sci(*st["friction_coefficient"][:2]),
                    fmt_sci(*st["lateral_force_ratio"][:2]), fmt(*st["sigma_ratio"][:2]))
                if fast:
                    row += ("%s | " % fmt(*rec["sigma_ratio_einf"][:2])) if e is not None else "- | "
                row += "%s |" % fmt(*st["phi_rad"][:2], scale=180 / np.pi, digits=1)
                if fast:
                    row += (" %s |" % fmt(*rec["phi_einf"][:2], scale=180 / np.pi, digits=1)) if e is not None else " - |"
                lines.append(row)
                res[(d["m"], d["n"], speed, float(al))] = rec
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(results, "table.md"), "w") as fh:
        fh.write(table + "\n")

    with vp.paper_style():
        _cells_figure(data, res, speeds, results, outdir)


def _cells_figure(data, res, speeds, results, outdir):
    """Top row the fastest speed, the others below: A(alpha)/A(0), A/A(E = Einf) (or friction),
    sigma1/sigma2 against alpha, one colour per cell."""
    fig, axs = plt.subplots(len(speeds), 3, figsize=(PAGE, 2.3 * len(speeds) + 0.5), squeeze=False)
    dotted = False
    ticks = [0, 22.5, 45, 67.5, 90]
    for row, speed in enumerate(sorted(speeds, reverse=True)):
        has_einf = any("a_over_einf" in r for (m, n, v, a), r in res.items() if v == speed)
        for k, d in enumerate(data):
            keys = sorted(a for (m, n, v, a) in res if (m, n, v) == (d["m"], d["n"], speed))
            if not keys:
                continue
            al = np.array(keys)
            get = lambda q: np.array([res[(d["m"], d["n"], speed, a)][q][:2] for a in keys])
            lab = (r"$L = L_0$" if d["m"] == 1 else r"$L = %d L_0$" % d["m"]) + r", %d$^2$" % d["n"]
            c = "C%d" % k
            ls = "-" if len(keys) > 2 else "--"     # two angles only: the line is no interpolation
            g = get("a_over_a0")
            axs[row, 0].errorbar(al, g[:, 0], yerr=g[:, 1], marker="o", ms=3, color=c, ls=ls, label=lab)
            if has_einf:
                if "a_over_einf" in res[(d["m"], d["n"], speed, keys[0])]:
                    g = get("a_over_einf")
                    axs[row, 1].errorbar(al, g[:, 0], yerr=g[:, 1], marker="o", ms=3, color=c, ls=ls, label=lab)
            else:
                g = get("f")
                axs[row, 1].errorbar(al, g[:, 0] * 1e3, yerr=g[:, 1] * 1e3, marker="o", ms=3,
                                     color=c, ls=ls, label=lab)
            g = get("sigma_ratio")
            axs[row, 2].errorbar(al, g[:, 0], yerr=g[:, 1], marker="o", ms=3, color=c, ls=ls, label=lab)
            if has_einf and "sigma_ratio_einf" in res[(d["m"], d["n"], speed, keys[0])]:
                g = get("sigma_ratio_einf")
                axs[row, 2].plot(al, g[:, 0], ls=":", marker="x", ms=3, color=c)
                dotted = True
        title = r"$v\tau/L_0$ = %g" % speed
        axs[row, 0].set_ylabel(r"$A(\alpha)/A(0)$, same seed")
        axs[row, 0].axhline(1.0, color="k", lw=0.5)
        if has_einf:
            axs[row, 1].set_ylabel(r"$A / A(E = E_\infty)$")
            axs[row, 1].axhline(1.0, color="k", lw=0.5)
        else:
            axs[row, 1].set_ylabel(r"friction $f$ [$10^{-3}$]")
        axs[row, 2].set_ylabel(r"$\sigma_1/\sigma_2$")
        axs[row, 2].axhline(1.0, color="k", lw=0.5)
        for ax in axs[row]:
            ax.set_xlabel(r"$\alpha$ [°]"); ax.set_xticks(ticks, ["0", "22.5", "45", "67.5", "90"])
            ax.grid(True, lw=0.3, color="0.88")
            ax.set_title(title)
    h, lab = [], []
    for ax in axs.ravel():                                 # every cell once, in the order drawn
        for hh, ll in zip(*ax.get_legend_handles_labels()):
            if ll not in lab:
                h.append(hh); lab.append(ll)
    if dotted:
        h.append(plt.Line2D([], [], ls=":", marker="x", ms=3, color="0.3"))
        lab.append(r"$\sigma_1/\sigma_2$ on $E = E_\infty$ (continuum fast limit)")
    fig.legend(h, lab, loc="outside lower center", ncol=min(len(lab), 3))
    out = os.path.join(outdir, os.path.basename(os.path.normpath(results)) + "_alpha.png")
    vp.save(fig, out, formats=("png",)); plt.close(fig)
    print("wrote", out)


# -------------------------------------------------------------------------------------- persson

PERSSON_Q = (("friction_coefficient", "f"), ("contact_area_fraction", "A/A0"))


def _persson_rows(p, key, member):
    """[(v tau/L0, {quantity: (BEM mean, BEM SE, theory mean, theory SE, ratio mean, ratio SE)})]
    of one member (key = member) of a study with Persson columns; ratios BEM/theory seed by seed."""
    s = vr.table(p)
    rows = []
    for v in np.unique(s["speed_m_s"]):
        sel = np.isclose(s[key], member) & (s["speed_m_s"] == v)
        if not sel.any():
            continue
        rec = {}
        for q, _ in PERSSON_Q + (("lateral_force_ratio", ""),):
            b, t = s[q][sel], s["persson_" + q][sel]
            rec[q] = stats(b)[:2] + stats(t)[:2] + (stats(b / t)[:2] if q != "lateral_force_ratio" else (np.nan, np.nan))
        rows.append((float(vr.dimensionless_speed(p, v)), rec))
    return sorted(rows, key=lambda r: r[0])


def _s_correction(p):
    """Whether the study used Persson's S(q) = 1/2 + P^2/2 (&analysis persson_correction)."""
    with h5py.File(p, "r") as fh:
        text = fh["/input/namelist"][()].decode()
    return re.search(r"persson_correction\s*=\s*\.t", text, re.IGNORECASE) is not None


def persson(results, outdir):
    studies = []
    for p in sorted(glob.glob(os.path.join(results, "*.h5"))):
        with h5py.File(p, "r") as fh:
            if "/summary" not in fh or "persson_friction_coefficient" not in fh["/summary"].dtype.names:
                continue
        s = vr.table(p)
        key, sym = ("eccentricity", "eps") if len(np.unique(s["eccentricity"])) > 1 else ("alpha_deg", "alpha")
        studies.append((os.path.basename(p)[:-3], p, key, sym))
    if not studies:
        raise SystemExit("no study run with &analysis persson in " + results)
    lines = []
    data = {}
    for name, p, key, sym in studies:
        s = vr.table(p)
        members = np.unique(s[key])
        data[name] = {float(m): _persson_rows(p, key, m) for m in members}
        n = len(np.unique(s["seed"]))
        theory = "S = 1/2 + P^2/2" if _s_correction(p) else "S = 1"
        for m in members:
            label = ("alpha = %g deg" % m) if sym == "alpha" else ("eps = %g" % m)
            lines += ["", "%s, %s (%d seeds; theory %s; BEM mean +- SE, theory mean +- SE, ratio BEM/theory seed by seed):"
                      % (name, label, n, theory), "",
                      "| v tau/L0 | f, BEM | f, theory | f: BEM/theory | A/A0, BEM | A/A0, theory | A: BEM/theory |"
                      " F_y/F_n, BEM | F_y/F_n, theory |",
                      "|---" * 9 + "|"]
            for x, rec in data[name][float(m)]:
                f, a, fy = rec["friction_coefficient"], rec["contact_area_fraction"], rec["lateral_force_ratio"]
                lines.append("| %g | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                    float("%.3g" % x), fmt_sci(*f[:2]), fmt_sci(*f[2:4]), fmt(*f[4:], digits=3),
                    fmt(*a[:2], digits=4), fmt(*a[2:4], digits=4), fmt(*a[4:], digits=3),
                    fmt_sci(*fy[:2]), fmt_sci(*fy[2:4])))
        solve = s["solve_seconds"]
        lines += ["", "%s: solve_seconds per case: median %.2f s, mean %.2f s, range %.2f-%.2f s (%d cases)"
                  % (name, np.median(solve), solve.mean(), solve.min(), solve.max(), len(solve))]
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(results, "persson.md"), "w") as fh:
        fh.write(table + "\n")

    with vp.paper_style():
        _persson_figure(studies, data, results, outdir)


def _persson_figure(studies, data, results, outdir):
    """Per study a row: the ratios BEM/theory of friction and contact area against speed, one
    colour per member, the cell artefact's speeds grey."""
    fig, axs = plt.subplots(len(studies), 2, figsize=(PAGE, 2.5 * len(studies)), squeeze=False)
    for row, (name, p, key, sym) in enumerate(studies):
        for k, (m, rows) in enumerate(data[name].items()):
            x = np.array([r[0] for r in rows])
            lab = (r"$\alpha$ = %.1f°" % m) if sym == "alpha" else (r"$\varepsilon$ = %.1f" % m)
            for col, (q, qlab) in enumerate(PERSSON_Q):
                g = np.array([r[1][q][4:] for r in rows])
                axs[row, col].errorbar(x, g[:, 0], yerr=g[:, 1], marker="o", ms=2.5, lw=1.0, color="C%d" % k, label=lab)
        ratio = vr.namelist_value(p, "ratio", None)
        theory = r"$S = 1/2 + P^2/2$" if _s_correction(p) else r"$S = 1$"
        for col, (q, qlab) in enumerate(PERSSON_Q):
            ax = axs[row, col]
            ax.set_xscale("log"); ax.axhline(1.0, color="k", lw=0.5)
            ax.set_xlabel(r"$v\tau/L_0$"); ax.set_ylabel(r"%s: BEM / Persson" % qlab)
            ax.grid(True, which="major", lw=0.3, color="0.88")
            if ratio is not None:             # the cell artefact's speeds (make_figures.cell_artefact_speed)
                lo, hi = ax.get_xlim()
                ax.axvspan(ratio * vr.namelist_value(p, "k_roll", 1.0) / (2 * np.pi), hi, color="0.9", zorder=0, lw=0)
                ax.set_xlim(lo, hi)
            ax.set_title("%s, %s: %s" % (name, theory, qlab))
        axs[row, 1].legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    out = os.path.join(outdir, os.path.basename(os.path.normpath(results)) + "_persson.png")
    vp.save(fig, out, formats=("png",)); plt.close(fig)
    print("wrote", out)


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("band", "cells", "cellspeed", "persson"):
        raise SystemExit(__doc__)
    os.makedirs(sys.argv[3], exist_ok=True)
    {"band": band, "cells": cells, "cellspeed": cells, "persson": persson}[sys.argv[1]](sys.argv[2], sys.argv[3])
