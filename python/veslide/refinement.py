"""Grid refinement: one case on successively finer grids, and the discretisation error of its
scalars from the observed order of convergence and Richardson extrapolation.

    ref = veslide.refine("case.nml", sizes=[256, 512, 768, 1024, 2048], output_dir="refine")
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
a cluster) are analysed by `convergence(results)`. A study (&sweep) is refined case by case.
"""
import copy
import math
import tempfile
import warnings
from pathlib import Path

import f90nml
import numpy as np
import pandas as pd

from .results import Result, parameter_columns, read
from ._warning import VeslideWarning
from .runner import ConvergenceWarning, _raised_warnings, load_params, reuse_existing, run

#: The scalars analysed unless others are asked for (those a file lacks are skipped)
DEFAULT_SCALARS = ("contact_area_fraction", "contact_area_fraction_cells", "mean_separation_m",
                   "friction_coefficient", "lateral_force_ratio")


#: Safety factors: an order observed within 0.5..2.1 on four grids or more; any other case
SAFETY_OBSERVED, SAFETY_ASSUMED = 1.25, 3.0

#: The range of the free order: an observed order at either end means no power law fitted
P_MIN, P_MAX = 0.05, 8.0

# default grid of the program (README, &grid)
_DEFAULT_N = 256


class Refinement:
    """The result of `refine` or `convergence`.

    results   the runs, coarsest first (`veslide.Result`; empty for `Refinement.from_table`)
    table     pandas DataFrame, one row per grid (index `nx`): `ny`, `cell_m` (cell side along x),
              the scalars, `solve_seconds`, `operator_applications`, `converged`
    estimate  pandas DataFrame, one row per scalar (index `scalar`): `finest` (value on the finest
              grid), `change` (finest minus next coarser), `observed_order`, `extrapolated`,
              `error` (absolute error band of `finest`), `relative_error` (error / |finest|),
              `units`, `note` (which rules of `richardson` made the band, or why there is none;
              '' when the free fit on every grid gave it with factor 1.25)
    converged True when every grid's solve converged (otherwise each note says which did not,
              and a `ConvergenceWarning` was issued)
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
        self._estimate([n for n in scalars if n in self.table.columns], results[-1].scalars.units, assumed_order)

    @classmethod
    def from_table(cls, table, scalars=DEFAULT_SCALARS, units=None, assumed_order=None):
        """The estimate from a table of values (e.g. `Refinement.table` written to CSV and read
        back): index `nx`, a column `cell_m`, the scalars' columns, optionally `converged`."""
        self = cls.__new__(cls)
        self.results = []
        self.table = table.sort_values("cell_m", ascending=False).copy()
        if "converged" not in self.table.columns:
            self.table["converged"] = True
        self.table["converged"] = self.table["converged"].astype(bool)
        self._estimate([n for n in scalars if n in self.table.columns], units or {}, assumed_order)
        return self

    def _estimate(self, names, units, assumed_order):
        est = [dict(scalar=n, units=units.get(n, ""),
                    **richardson(self.table["cell_m"].to_numpy(), self.table[n].to_numpy(), assumed_order))
               for n in names]
        self.estimate = pd.DataFrame(est, columns=["scalar", "finest", "change", "observed_order", "extrapolated",
                                                   "error", "relative_error", "units", "note"]).set_index("scalar")
        failed = [n for n, ok in zip(self.table.index, self.table["converged"]) if not ok]
        if failed:
            why = "not converged on nx = %s" % ", ".join(str(n) for n in failed)
            self.estimate["note"] = [why + ("; " + v if v else "") for v in self.estimate["note"]]
            warnings.warn("veslide.refine: %s: the band includes the solver's error" % why, ConvergenceWarning,
                          stacklevel=4)

    @property
    def converged(self):
        """Every grid's solve converged."""
        return bool(self.table["converged"].all())

    def __repr__(self):
        ny = self.table["ny"] if "ny" in self.table.columns else ["?"] * len(self.table)
        return "<veslide.Refinement %s>" % ", ".join("%sx%s" % g for g in zip(self.table.index, ny))


class StudyRefinement:
    """The result of `refine` or `convergence` for a study (&sweep): every case refined on its own
    from its rows of the studies' /summary (the same plan, so the same case numbers, on every grid).

    results   the study files, coarsest first
    cases     case number -> `Refinement` (its `table` and `estimate`; `results` empty)
    table     every case on every grid: index (case, nx), the parameters, `ny`, `cell_m`, the
              scalars, `solve_seconds`, `operator_applications`, `converged`
    estimate  index (case, scalar): the case's parameters, then the columns of
              `Refinement.estimate`
    converged True when every case converged on every grid
    """

    def __init__(self, results, scalars, assumed_order):
        self.results = results
        frames = []
        for r in results:
            f = r.summary.copy()
            f["cell_m"] = f["length_x_m"] / f["nx"]
            f["converged"] = f["converged"].astype(bool)
            frames.append(f)
        # the parameters the file names (temperature_c in a study of a material with a shift)
        params = tuple(p for p in parameter_columns(frames[-1]) if p != "case")
        plan = frames[-1].set_index("case")[list(params)]
        for r, f in zip(results, frames):
            mine = f.set_index("case")[list(params)]
            if not mine.index.equals(plan.index) or not np.allclose(mine.to_numpy(float), plan.to_numpy(float),
                                                                     rtol=1e-12, atol=0.0):
                raise ValueError("%s: its cases are not those of %s (an unfinished or another study)"
                                 % (r.path, results[-1].path))
        rows = pd.concat(frames)
        names = [n for n in scalars if n in rows.columns]
        columns = ["ny", "cell_m"] + names + ["solve_seconds", "operator_applications", "converged"]
        units = frames[-1].attrs.get("units", {})
        self.cases, estimates = {}, []
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", ConvergenceWarning)
            for k in plan.index:
                mine = rows[rows["case"] == k].set_index("nx")
                ref = Refinement.from_table(mine[columns], names, units, assumed_order)
                self.cases[int(k)] = ref
                e = ref.estimate.reset_index()
                for j, name in enumerate(("case",) + params):
                    e.insert(j, name, int(k) if name == "case" else plan.loc[k, name])
                estimates.append(e)
        if caught:
            warnings.warn("veslide.refine: %d case(s) did not converge on some grid: see the notes" % len(caught),
                          ConvergenceWarning, stacklevel=3)
        self.estimate = pd.concat(estimates, ignore_index=True).set_index(["case", "scalar"])
        self.table = rows.set_index(["case", "nx"]).sort_index()[list(params) + columns]

    @property
    def converged(self):
        """Every case converged on every grid."""
        return bool(self.table["converged"].all())

    def __repr__(self):
        return "<veslide.StudyRefinement %d cases on %d grids>" % (len(self.cases), len(self.results))


def _fit(x, phi, powers, weighted=False, extra_unknowns=0):
    """Least-squares fit phi = phi0 + sum_k a_k x^powers[k], unweighted or with weights 1/x (the
    finer grids weigh more); returns (phi0, fitted values, standard deviation of the residuals over
    n - (number of unknowns, `extra_unknowns` more than the coefficients) when positive, else 0).
    The columns are scaled by their largest value, which keeps high powers of x well conditioned."""
    a = np.column_stack([np.ones_like(x)] + [(x / x.max()) ** q for q in powers])
    w = (1.0 / x) / np.sum(1.0 / x) if weighted else np.full(len(x), 1.0 / len(x))
    sw = np.sqrt(w)
    c, *_ = np.linalg.lstsq(a * sw[:, None], phi * sw, rcond=None)
    fitted = a @ c
    dof = len(x) - a.shape[1] - extra_unknowns
    sd = math.sqrt(len(x) * float(np.sum(w * (phi - fitted) ** 2)) / dof) if dof > 0 else 0.0
    return float(c[0]), fitted, sd


def _best_fit(x, phi, powers):
    """The weighted or the unweighted fit, whichever has the smaller standard deviation."""
    fits = [_fit(x, phi, powers, weighted) for weighted in (False, True)]
    return min(fits, key=lambda f: f[2])


def _fit_order(x, phi):
    """The fit phi = phi0 + a x^p with p free (P_MIN <= p <= P_MAX), weighted or not (the smaller
    standard deviation; p counts as an unknown): a scan on a logarithmic grid, then golden-section
    refinement of the best bracket. Returns (p, phi0, fitted, sd)."""
    best = None
    for weighted in (False, True):
        def ssq(q):
            _, f, sd = _fit(x, phi, [q], weighted, extra_unknowns=1)
            return sd if len(x) > 3 else float(np.sum((phi - f) ** 2))
        grid = np.exp(np.linspace(math.log(P_MIN), math.log(P_MAX), 400))
        vals = [ssq(q) for q in grid]
        k = int(np.argmin(vals))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
        g = (math.sqrt(5.0) - 1.0) / 2.0
        c, d = hi - g * (hi - lo), lo + g * (hi - lo)
        fc, fd = ssq(c), ssq(d)
        for _ in range(60):         # one new point a step: the kept interior point is reused
            if fc < fd:
                hi, d, fd = d, c, fc
                c = hi - g * (hi - lo)
                fc = ssq(c)
            else:
                lo, c, fc = c, d, fd
                d = lo + g * (hi - lo)
                fd = ssq(d)
        p = 0.5 * (lo + hi)
        phi0, fitted, sd = _fit(x, phi, [p], weighted, extra_unknowns=1)
        if best is None or sd < best[3]:
            best = (p, phi0, fitted, sd)
    return best


def richardson(h, phi, assumed_order=None):
    """Discretisation error of phi[-1] (the finest grid) from its values phi on cells of side h
    (coarsest first), after Eca & Hoekstra, "A procedure for the estimation of the numerical
    uncertainty of CFD calculations based on grid refinement studies", J. Comput. Phys. 262 (2014)
    104-130:

    - the values are fitted by least squares by phi0 + a h^p with p free in P_MIN..P_MAX (an order
      at either end means that no power law fits), unweighted and with weights 1/h, and the fit
      with the smaller standard deviation is kept; its p is the observed order;
    - when 0.5 <= p < 2.1 that fit is used with safety factor Fs = 1.25; otherwise the one of
      phi0 + a h, phi0 + a h^2 and phi0 + a h + b h^2 (each weighted or not) whose standard
      deviation is smallest, with Fs = 3;
    - error = Fs |phi_1 - phi0| + s + |phi_1 - fit(h_1)|, with s the standard deviation of the
      fit's residuals; when s exceeds the data range (max - min)/(n - 1) the values scatter more
      than they converge, and the band becomes 3 s / range times (|phi_1 - phi0| + s +
      |phi_1 - fit(h_1)|).

    This project's addition: while five grids or more remain and the observed order is within
    2.1..P_MAX (the values converge faster than the method's order: the coarsest grid is outside
    the asymptotic range), the coarsest grid is left out. Three grids determine the free fit
    exactly (no scatter can be measured: Fs = 3; four or more are better); two grids use
    `assumed_order` with Fs = 3 (None: no band). Values that are not finite give no band. Returns
    a dict (see `Refinement.estimate`)."""
    h = np.asarray(h, float)
    phi = np.asarray(phi, float)
    n = len(h)
    if n < 2 or not np.all(np.isfinite(h)) or np.any(np.diff(h) >= 0):
        raise ValueError("richardson: need at least two grids, coarsest first (cell sides decreasing)")
    out = dict(finest=phi[-1], change=phi[-1] - phi[-2], observed_order=np.nan, extrapolated=np.nan,
               error=np.nan, relative_error=np.nan, note="")
    if not np.all(np.isfinite(phi)):
        out["note"] = "a value is not finite (grids %s): no band" % ", ".join(
            str(k + 1) for k in np.flatnonzero(~np.isfinite(phi)))
        return out
    if np.all(phi == phi[-1]):
        out.update(extrapolated=phi[-1], error=0.0, relative_error=0.0, note="the same on every grid")
        return out
    x = h / h[-1]                       # cell side in units of the finest: 1 on the finest grid
    notes = []
    free = _fit_order(x, phi) if n >= 3 else None      # the free-order fit of the grids kept
    dropped = 0
    while n - dropped >= 5 and 2.1 <= free[0] < P_MAX:
        dropped += 1
        free = _fit_order(x[dropped:], phi[dropped:])
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
        phi0, fitted, sd = _fit(x, phi, [p])
        safety = SAFETY_ASSUMED
        notes.append("two grids: order %g assumed" % p)
    else:
        p, phi0, fitted, sd = free
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
                f = _best_fit(x, phi, powers)
                if best is None or f[2] < best[2]:
                    best = f + (powers,)
            if best is None:
                notes.append("observed order %.3g outside 0.5..2.1 and too few grids for other fits" % p)
                out["note"] = "; ".join(notes)
                return out
            phi0, fitted, sd, powers = best
            safety = SAFETY_ASSUMED
            notes.append("observed order %.3g outside 0.5..2.1: fit in h^%s used"
                         % (p, " + h^".join("%g" % q for q in powers)))
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


def _is_study(nml):
    return "sweep" in nml and len(nml["sweep"]) > 0


def _check_refinable(nml):
    kind = str(nml.get("surface", {}).get("kind", "self_affine")).lower()
    if kind == "file":
        raise ValueError("refine: &surface kind = 'file' is a topography on one grid; refinement needs a surface "
                         "the program can sample on any grid (self_affine, cosine, bisinusoid, paraboloid, cylinder)")


def refine(params, sizes, output_dir=None, threads=None, exe=None, *, scalars=DEFAULT_SCALARS, assumed_order=None,
           reuse=True, overwrite=False, progress=print):
    """Run one case on grids of `sizes` cells along x (the same periodic domain, &grid lx_m and
    ly_m, divided into finer cells; ny scaled with nx, or kept at 1 for a profile) and return a
    `Refinement`.

    params      a dict of namelist groups or the path of a namelist file; with &sweep the study
                is run on every grid and a `StudyRefinement` returned (each case refined alone)
    sizes       nx of each grid, e.g. [256, 512, 768, 1024, 2048] (five or more: see `richardson`)
    output_dir  where the result files refine-NXxNY.h5 go (default: a new temporary directory,
                which is kept: its files are the refinement's)
    reuse       a result file already there from the same input and the same program version
                (`veslide --version` against the file's `veslide_version`) is read, not run again:
                a refinement interrupted on a cluster continues. A file of another input or
                version is an error (`veslide.OutputExistsError`, a FileExistsError). A program
                rebuilt without a new version is not detected: pass overwrite=True after changing
                it. The rule of `veslide.run(..., reuse=True)` (`veslide.runner.reuse_existing`).
    overwrite   run again and replace the files instead
    threads, exe, progress   as for `veslide.run`

    The finest grid's warnings (docs/validity.md) are raised as `veslide.VeslideWarning`s; the
    coarser grids', coarse by design, stay with their results (`.results[k].warnings`).
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
    if output_dir is None:
        out_dir, created = Path(tempfile.mkdtemp(prefix="veslide-refine-")), True
    else:
        out_dir = Path(output_dir)
        created = not out_dir.exists()
        out_dir.mkdir(parents=True, exist_ok=True)
    try:
        # each grid's warnings stay with its result (results[k].warnings); the coarser grids are
        # coarse by design, so only the finest grid's, the one the estimate quotes, are raised
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", VeslideWarning)
            results = _run_grids(base, grids, out_dir, threads, exe, reuse, overwrite, progress)
        for c in caught:
            if not isinstance(c.message, VeslideWarning):
                warnings.warn_explicit(c.message, c.category, c.filename, c.lineno)
        for w in _raised_warnings(results[-1]):
            warnings.warn(w, stacklevel=2)
    except BaseException:
        if created and not any(out_dir.iterdir()):
            out_dir.rmdir()             # nothing was written: leave no empty directory behind
        raise
    if _is_study(base):
        return StudyRefinement(results, scalars, assumed_order)
    return Refinement(results, scalars, assumed_order)


def _run_grids(base, grids, out_dir, threads, exe, reuse, overwrite, progress):
    results = []
    version = None
    for n, ny in grids:
        nml = copy.deepcopy(base)
        nml.setdefault("grid", f90nml.Namelist())
        nml["grid"]["nx"] = n
        nml["grid"]["ny"] = ny
        nml.setdefault("output", f90nml.Namelist())
        nml["output"].pop("file", None)
        out = out_dir / ("refine-%dx%d.h5" % (n, ny))
        if out.exists() and not overwrite:
            # veslide.run's rule, also where the namelist says &output overwrite (a refinement continues)
            r = reuse_existing(out, nml, exe, reuse, version)
            version = r.provenance.get("veslide_version")
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


def _grid_info(r):
    """nx, ny, length_x_m, length_y_m of a case, or of a study (its first row)."""
    src = r.scalars if r.scalars is not None else r.summary.iloc[0]
    return int(src["nx"]), int(src["ny"]), float(src["length_x_m"]), float(src["length_y_m"])


def convergence(results, scalars=DEFAULT_SCALARS, assumed_order=None):
    """A `Refinement` from runs of one case on different grids (Result objects or paths, any
    order): e.g. one cluster job per grid; a `StudyRefinement` from runs of one study. Every run
    must have the same input apart from &grid nx, ny and &output: the same periodic domain and the
    same aspect nx : ny."""
    rs = [r if isinstance(r, Result) else read(r) for r in results]
    if len(rs) < 2:
        raise ValueError("convergence: need at least two runs")
    studies = [r.is_study for r in rs]
    if any(studies) and not all(studies):
        raise ValueError("convergence: give single cases or studies, not both")
    for r in rs:
        if (r.summary is None or len(r.summary) == 0) if r.is_study else r.scalars is None:
            raise ValueError("convergence: %s holds no finished case" % r.path)
    rs.sort(key=lambda r: _grid_info(r)[0])
    nxs = [_grid_info(r)[0] for r in rs]
    if len(set(nxs)) != len(nxs):
        raise ValueError("convergence: two runs on the same grid (nx = %s)" % nxs)
    ref = _comparable(rs[-1].input)
    nx1, ny1, lx1, ly1 = _grid_info(rs[-1])
    for r in rs[:-1]:
        other = _comparable(r.input)
        for g in sorted(set(ref) | set(other)):
            a, b = ref.get(g, {}), other.get(g, {})
            for v in sorted(set(a) | set(b)):
                if a.get(v) != b.get(v):
                    raise ValueError("convergence: %s and %s differ in &%s %s (%r against %r)"
                                     % (r.path, rs[-1].path, g, v, b.get(v), a.get(v)))
        nx, ny, lx, ly = _grid_info(r)
        for name, a, b in (("length_x_m", lx, lx1),) + ((("length_y_m", ly, ly1),) if ny > 1 else ()):
            if not math.isclose(a, b, rel_tol=1e-12):
                raise ValueError("convergence: %s and %s have different domains (%s %g against %g)"
                                 % (r.path, rs[-1].path, name, a, b))
        if (ny1 == 1) != (ny == 1) or (ny1 > 1 and nx * ny1 != ny * nx1):
            raise ValueError("convergence: %s (%d x %d) and %s (%d x %d) are not refined alike along x and y"
                             % (r.path, nx, ny, rs[-1].path, nx1, ny1))
    if all(studies):
        return StudyRefinement(rs, scalars, assumed_order)
    return Refinement(rs, scalars, assumed_order)
