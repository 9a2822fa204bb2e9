"""Grid refinement: one case on successively finer grids, and the discretisation error of its
scalars from the observed order of convergence and Richardson extrapolation.

    ref = veslide.refine("case.nml", sizes=[256, 512, 1024], output_dir="refine")
    ref.table       # one row per grid: the scalars, solve time, FFT pairs
    ref.estimate    # one row per scalar: finest value, observed order, extrapolated value, error

The error band follows Eca & Hoekstra, J. Comput. Phys. 262 (2014) 104-130 (least-squares fits
over the grids, an observed order, a safety factor of 1.25 or 3, and the scatter of the values
about the fit added): `richardson` says exactly what is done. Several grids matter: the contact
area's error depends on where the edges fall in their cells, so its changes under refinement are
not a clean power of the cell size (docs/validation.md), and three grids can suggest any order.
The surface must be the same on every grid: the generator gives the same surface on any grid that
resolves its spectrum (&surface k_cut below every grid's Nyquist), and the analytic surfaces are
sampled exactly; a topography file is one grid only. Runs computed elsewhere (one job per grid on
a cluster) are analysed by `convergence(results)`.
"""
import copy
import math
import tempfile
from pathlib import Path

import f90nml
import numpy as np
import pandas as pd

from .results import Result, read
from .runner import load_params, run

#: The scalars analysed unless others are asked for (those a file lacks are skipped)
DEFAULT_SCALARS = ("contact_area_fraction", "contact_area_fraction_cells", "mean_separation_m",
                   "friction_coefficient", "lateral_force_ratio")

#: Safety factors: an order observed within 0.5..2.1 on four grids or more; any other case
SAFETY_OBSERVED, SAFETY_ASSUMED = 1.25, 3.0

# default grid of the program (README, &grid)
_DEFAULT_N = 256


class Refinement:
    """The result of `refine` or `convergence`.

    results   the runs, coarsest first (`veslide.Result`)
    table     pandas DataFrame, one row per grid (index `nx`): `ny`, `cell_m` (cell side along x),
              the scalars, `solve_seconds`, `operator_applications`, `converged`
    estimate  pandas DataFrame, one row per scalar (index `scalar`): `finest` (value on the finest
              grid), `change` (finest minus next coarser), `observed_order`, `extrapolated`,
              `error` (absolute error band of `finest`), `relative_error` (error / |finest|),
              `units`, `note` ('' when the order was observed within 0.5..2.1 on four grids or
              more and the values do not scatter; otherwise which rule made the band, or why
              there is none)
    """

    def __init__(self, results, scalars, assumed_order):
        self.results = results
        rows = []
        for r in results:
            s = r.scalars
            row = {"nx": int(s["nx"]), "ny": int(s["ny"]), "cell_m": float(s["length_x_m"]) / int(s["nx"])}
            for name in scalars:
                if name in s:
                    row[name] = float(s[name])
            for name in ("solve_seconds", "operator_applications"):
                row[name] = s.get(name, np.nan)
            row["converged"] = bool(s.get("converged", 0))
            rows.append(row)
        self.table = pd.DataFrame(rows).set_index("nx")
        units = results[-1].scalars.units
        names = [n for n in scalars if n in self.table.columns]
        est = [dict(scalar=n, units=units.get(n, ""),
                    **richardson(self.table["cell_m"].to_numpy(), self.table[n].to_numpy(), assumed_order))
               for n in names]
        self.estimate = pd.DataFrame(est, columns=["scalar", "finest", "change", "observed_order", "extrapolated",
                                                   "error", "relative_error", "units", "note"]).set_index("scalar")

    def __repr__(self):
        return "<veslide.Refinement %s>" % ", ".join("%dx%d" % (r.scalars["nx"], r.scalars["ny"]) for r in self.results)


def _fit(x, phi, powers, weighted=False):
    """Least-squares fit phi = phi0 + sum_k a_k x^powers[k], unweighted or with weights 1/x (the
    finer grids weigh more); returns (coefficients, fitted values, standard deviation of the
    residuals over n - (number of unknowns) when positive, else 0)."""
    a = np.column_stack([np.ones_like(x)] + [x ** q for q in powers])
    w = (1.0 / x) / np.sum(1.0 / x) if weighted else np.full(len(x), 1.0 / len(x))
    sw = np.sqrt(w)
    c, *_ = np.linalg.lstsq(a * sw[:, None], phi * sw, rcond=None)
    fitted = a @ c
    dof = len(x) - a.shape[1]
    sd = math.sqrt(len(x) * float(np.sum(w * (phi - fitted) ** 2)) / dof) if dof > 0 else 0.0
    return c, fitted, sd


def _best_fit(x, phi, powers):
    """The weighted or the unweighted fit, whichever has the smaller standard deviation."""
    fits = [_fit(x, phi, powers, weighted) for weighted in (False, True)]
    return min(fits, key=lambda f: f[2])


def _fit_order(x, phi):
    """The fit phi = phi0 + a x^p with p free (0.05 <= p <= 8), weighted or not (the smaller
    standard deviation): a scan on a logarithmic grid, then golden-section refinement of the best
    bracket. Returns (p, coefficients, fitted, sd)."""
    best = None
    for weighted in (False, True):
        def ssq(q):
            _, f, sd = _fit(x, phi, [q], weighted)
            return sd if len(x) > 3 else float(np.sum((phi - f) ** 2))
        grid = np.exp(np.linspace(math.log(0.05), math.log(8.0), 400))
        vals = [ssq(q) for q in grid]
        k = int(np.argmin(vals))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
        g = (math.sqrt(5.0) - 1.0) / 2.0
        c, d = hi - g * (hi - lo), lo + g * (hi - lo)
        for _ in range(60):
            if ssq(c) < ssq(d):
                hi = d
            else:
                lo = c
            c, d = hi - g * (hi - lo), lo + g * (hi - lo)
        p = 0.5 * (lo + hi)
        coef, fitted, sd = _fit(x, phi, [p], weighted)
        if best is None or sd < best[3]:
            best = (p, coef, fitted, sd)
    return best


def richardson(h, phi, assumed_order=None):
    """Discretisation error of phi[-1] (the finest grid) from its values phi on cells of side h
    (coarsest first), after Eca & Hoekstra, "A procedure for the estimation of the numerical
    uncertainty of CFD calculations based on grid refinement studies", J. Comput. Phys. 262 (2014)
    104-130:

    - the values are fitted by least squares by phi0 + a h^p (p free), unweighted and with weights
      1/h, and the fit with the smaller standard deviation is kept; its p is the observed order;
    - while that order is 2.1 or more and four grids or more remain, the coarsest grid is left out
      (outside the asymptotic range: the values converge faster than any order the method has);
    - when 0.5 <= p < 2.1 that fit is used with safety factor 1.25; otherwise the one of phi0 +
      a h, phi0 + a h^2 and phi0 + a h + b h^2 whose residuals are smallest, with factor 3;
    - error = Fs |phi_1 - phi0| + s + |phi_1 - fit(h_1)|, with s the standard deviation of the
      fit's residuals; when s exceeds the data range (max - min)/(n - 1) the values scatter more
      than they converge, and the band becomes 3 s / range times (|phi_1 - phi0| + s +
      |phi_1 - fit(h_1)|).

    Three grids determine the first fit exactly (no scatter measured: factor 3; four or more are
    better); two grids use `assumed_order` with factor 3 (None: no band). Returns a dict (see
    `Refinement.estimate`)."""
    h = np.asarray(h, float)
    phi = np.asarray(phi, float)
    n = len(h)
    if n < 2 or np.any(np.diff(h) >= 0):
        raise ValueError("richardson: need at least two grids, coarsest first (cell sides decreasing)")
    out = dict(finest=phi[-1], change=phi[-1] - phi[-2], observed_order=np.nan, extrapolated=np.nan,
               error=np.nan, relative_error=np.nan, note="")
    if np.all(phi == phi[-1]):
        out.update(extrapolated=phi[-1], error=0.0, relative_error=0.0, note="the same on every grid")
        return out
    x = h / h[-1]                       # cell side in units of the finest: 1 on the finest grid
    notes = []
    # coarse grids outside the asymptotic range (the values converge faster than h^2.1 with them)
    # are left out, coarsest first, while four grids or more remain
    dropped = 0
    while n - dropped >= 4 and _fit_order(x[dropped:], phi[dropped:])[0] >= 2.1:
        dropped += 1
    if dropped:
        notes.append("coarsest %d grid%s left out (order above 2.1 with %s)"
                     % (dropped, "s" if dropped > 1 else "", "them" if dropped > 1 else "it"))
        x, phi, n = x[dropped:], phi[dropped:], n - dropped
        if np.all(phi == phi[-1]):
            out.update(extrapolated=phi[-1], error=0.0, relative_error=0.0,
                       note="; ".join(notes + ["the same on the grids kept"]))
            return out
    if n == 2:
        if assumed_order is None:
            out["note"] = "two grids: order not observed (give assumed_order)"
            return out
        p = float(assumed_order)
        coef, fitted, sd = _fit(x, phi, [p])
        safety = SAFETY_ASSUMED
        notes.append("two grids: order %g assumed" % p)
    else:
        p, coef, fitted, sd = _fit_order(x, phi)
        out["observed_order"] = p
        safety = SAFETY_OBSERVED
        if n == 3:
            safety = SAFETY_ASSUMED         # an exact fit: its scatter cannot be seen
            notes.append("three grids: no scatter measured")
        if not (0.5 <= p < 2.1):
            best = None
            for powers in ([1.0], [2.0], [1.0, 2.0]):
                if len(powers) + 1 >= n:
                    continue
                c2, f2, s2 = _best_fit(x, phi, powers)
                if best is None or s2 < best[2]:
                    best = (c2, f2, s2, powers)
            if best is None:
                notes.append("observed order %.3g outside 0.5..2.1 and too few grids for other fits" % p)
                out["note"] = "; ".join(notes)
                return out
            coef, fitted, sd, powers = best
            safety = SAFETY_ASSUMED
            notes.append("observed order %.3g outside 0.5..2.1: fit in h^%s used"
                         % (p, " + h^".join("%g" % q for q in powers)))
    phi0 = float(coef[0])
    eps = abs(phi[-1] - phi0)
    off = abs(phi[-1] - fitted[-1])
    data_range = (phi.max() - phi.min()) / (n - 1)
    if sd < data_range:
        error = safety * eps + sd + off
    else:
        error = 3.0 * sd / data_range * (eps + sd + off)
        notes.append("the values scatter more than they converge")
    out.update(extrapolated=phi0, error=error, note="; ".join(notes),
               relative_error=error / abs(phi[-1]) if phi[-1] != 0.0 else np.inf)
    return out


def _grid_of(nml):
    g = nml.get("grid", {}) if nml is not None else {}
    return int(g.get("nx", _DEFAULT_N)), int(g.get("ny", _DEFAULT_N))


def _check_refinable(nml):
    if "sweep" in nml and len(nml["sweep"]) > 0:
        raise ValueError("refine runs one case: remove &sweep (refine each case of a study on its own)")
    kind = str(nml.get("surface", {}).get("kind", "self_affine")).lower()
    if kind == "file":
        raise ValueError("refine: &surface kind = 'file' is a topography on one grid; refinement needs a surface "
                         "the program can sample on any grid (self_affine, cosine, bisinusoid, paraboloid, cylinder)")


def refine(params, sizes, output_dir=None, threads=None, exe=None, *, scalars=DEFAULT_SCALARS, assumed_order=None,
           reuse=True, overwrite=False, progress=print):
    """Run one case on grids of `sizes` cells along x (the same physical cell; ny scaled with nx,
    or kept at 1 for a profile) and return a `Refinement`.

    params      a dict of namelist groups or the path of a namelist file (one case: no &sweep)
    sizes       nx of each grid, e.g. [256, 512, 1024] (three or more to observe the order)
    output_dir  where the result files refine-NXxNY.h5 go (default: a new temporary directory)
    reuse       a result file already there from the same input is read, not run again (a
                refinement interrupted on a cluster continues); one from another input is an error
    overwrite   run again and replace the files instead
    threads, exe, progress   as for `veslide.run`
    """
    base, _ = load_params(params)
    _check_refinable(base)
    sizes = sorted(int(n) for n in sizes)
    if len(sizes) < 2 or len(set(sizes)) != len(sizes) or sizes[0] < 1:
        raise ValueError("refine: sizes must be at least two different positive grid sizes, got %r" % (sizes,))
    nx0, ny0 = _grid_of(base)
    grids = []
    for n in sizes:
        if ny0 == 1:
            grids.append((n, 1))
        elif (n * ny0) % nx0 == 0:
            grids.append((n, n * ny0 // nx0))
        else:
            raise ValueError("refine: nx = %d does not keep the grid's aspect %d x %d (ny would not be whole)"
                             % (n, nx0, ny0))
    out_dir = Path(output_dir) if output_dir is not None else Path(tempfile.mkdtemp(prefix="veslide-refine-"))
    created = not out_dir.exists()
    out_dir.mkdir(parents=True, exist_ok=True)
    try:
        results = _run_grids(base, grids, out_dir, threads, exe, reuse, overwrite, progress)
    except BaseException:
        if created and not any(out_dir.iterdir()):
            out_dir.rmdir()             # nothing was written: leave no empty directory behind
        raise
    return Refinement(results, scalars, assumed_order)


def _run_grids(base, grids, out_dir, threads, exe, reuse, overwrite, progress):
    results = []
    for n, ny in grids:
        nml = copy.deepcopy(base)
        nml.setdefault("grid", f90nml.Namelist())
        nml["grid"]["nx"] = n
        nml["grid"]["ny"] = ny
        nml.setdefault("output", f90nml.Namelist())
        nml["output"].pop("file", None)
        out = out_dir / ("refine-%dx%d.h5" % (n, ny))
        if out.exists() and not overwrite:
            if not reuse:
                raise FileExistsError("%s exists: pass reuse=True to read it or overwrite=True to run again" % out)
            r = read(out)
            if r.input is None or str(r.input) != str(nml):
                raise FileExistsError("%s holds the result of another input: pass overwrite=True or another "
                                      "output_dir" % out)
            if progress is not None:
                progress("refine: %s reused" % out.name)
        else:
            r = run(nml, output=out, threads=threads, exe=exe, overwrite=overwrite, quiet=True, progress=progress)
            if progress is not None:
                progress("refine: %dx%d done" % (n, ny))
        results.append(r)
    return results


def _comparable(nml):
    """The input without what a refinement changes (&grid nx, ny; &output)."""
    d = {g: dict(v) for g, v in (nml or {}).items() if g != "output"}
    d.get("grid", {}).pop("nx", None)
    d.get("grid", {}).pop("ny", None)
    return d


def convergence(results, scalars=DEFAULT_SCALARS, assumed_order=None):
    """A `Refinement` from runs of one case on different grids (Result objects or paths, any
    order): e.g. one cluster job per grid. Every run must have the same input apart from &grid nx,
    ny and &output, and the same physical cell."""
    rs = [r if isinstance(r, Result) else read(r) for r in results]
    if len(rs) < 2:
        raise ValueError("convergence: need at least two runs")
    for r in rs:
        if r.is_study or r.scalars is None:
            raise ValueError("convergence: %s is a study; give single cases" % r.path)
    rs.sort(key=lambda r: int(r.scalars["nx"]))
    nxs = [int(r.scalars["nx"]) for r in rs]
    if len(set(nxs)) != len(nxs):
        raise ValueError("convergence: two runs on the same grid (nx = %s)" % nxs)
    ref = _comparable(rs[-1].input)
    for r in rs[:-1]:
        other = _comparable(r.input)
        for g in sorted(set(ref) | set(other)):
            a, b = ref.get(g, {}), other.get(g, {})
            for v in sorted(set(a) | set(b)):
                if a.get(v) != b.get(v):
                    raise ValueError("convergence: %s and %s differ in &%s %s (%r against %r)"
                                     % (r.path, rs[-1].path, g, v, b.get(v), a.get(v)))
        for length in ("length_x_m",) + (("length_y_m",) if int(r.scalars["ny"]) > 1 else ()):
            if not math.isclose(r.scalars[length], rs[-1].scalars[length], rel_tol=1e-12):
                raise ValueError("convergence: %s and %s have different cells (%s %g against %g)"
                                 % (r.path, rs[-1].path, length, r.scalars[length], rs[-1].scalars[length]))
    return Refinement(rs, scalars, assumed_order)

