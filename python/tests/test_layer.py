"""Layered solids (&material thickness_m, base) against ContactMechanics' layered substrate.

ContactMechanics (PyPI, binary wheels; `pip install -e 'python[contactmechanics]'`) models a
layer of thickness d on a rigid flat in `PeriodicFFTElasticHalfSpace(..., thickness=d,
poisson=nu)`: its stiffness is the half-space's E* |q|/2 times
    (kappa cosh 2t + 2t^2 + (1 + kappa^2)/2)/(kappa sinh 2t - 2t),   t = |q| d, kappa = 3 - 4 nu
(its `off` = 4 nu (2 nu - 3) + 5 is (1 + kappa^2)/2), from Carbone & Mangialardi, JMPS 56 (2008)
eq. (A.30): the layer bonded to the rigid base, the reciprocal of our bonded S. It has no
frictionless base. Its q = 0 mode is the layer's confined compression (ours is the rigid-body
approach); a load-controlled solve does not see it.

What is checked:
- our two closed forms (written anew here in numpy) equal the boundary-value problem of a mode
  solved numerically (the Navier equations carried across the layer by a matrix exponential, four
  boundary conditions; measured 1.6e-13 for nu = 0 to 0.49, t = 0.05 to 4);
- ContactMechanics' stiffness is 1/S of our bonded base at every mode of a grid (to 1e-13 from t = 0.1,
  measured 7e-15 or less; 4e-13 at t = 0.01 for nu = 1/2, its own cancellation), and differs
  from the frictionless base by 15-100 % for nu >= 0.3 (so its base is the bonded one);
- the same rough surface (the program's heights, read back from /fields/height_m), grid, E, nu,
  thickness and load, solved by both, tolerances tight (veslide 1e-12; ContactMechanics'
  Polonsky-Keer CG with `external_force`, penetration 1e-14 h_rms, force 1e-14 of a cell's
  mean): the cells in contact are the same cells, the mean gap agrees to 1e-6 relative
  (measured 3e-14 or less), the pressure fields to 1e-8 of the mean pressure (measured 4e-11 or
  less). Cases, all at q0 d = 1 with 13-17 % of the cells in contact: the half-space (the
  control), a bonded layer of nu = 0.3 and one of nu = 0.5; and the frictionless base, with
  ContactMechanics' solver on its half-space Green's function times our S written anew in numpy
  (an independent factor and solver, not an independent model);
- the layer matters in these cases (the mean gap 29-51 % above the half-space's);
- docs/layers.md's example runs and prints what it says, without a warning.
"""
import doctest
import re
import warnings

import numpy as np
import pytest

import veslide

CM = pytest.importorskip("ContactMechanics", reason="ContactMechanics is not installed (binary wheels: "
                         "pip install --only-binary=:all: 'ContactMechanics>=1.8.3'; "
                         "the package's extra 'contactmechanics')")
from ContactMechanics import PeriodicFFTElasticHalfSpace  # noqa: E402
from ContactMechanics.Optimization import constrained_conjugate_gradients  # noqa: E402

N, LX, E = 64, 1.0e-3, 1.0e7
D = LX/(2.0*np.pi)                 # q0 d = 1
PRESSURE = 20.0e3


def s_bonded(t, nu):
    """S of a layer bonded to a rigid base: divided through by cosh 2t (no overflow), and
    kappa sinh 2t - 2t = (kappa - 1) sinh 2t + (sinh 2t - 2t) with the last from its series
    below 2t = 1/2 (no cancellation)."""
    k = 3.0 - 4.0*nu
    x = 2.0*np.asarray(t, dtype=float)
    xc = np.minimum(x, 700.0)
    sech = np.where(x < 700.0, 1.0/np.cosh(xc), 0.0)
    series = sum(xc**j/np.prod(np.arange(1.0, j + 1.0)) for j in range(19, 1, -2))   # sinh x - x to x^19
    num = np.where(x < 0.5, ((k - 1.0)*np.sinh(xc) + series)*sech, k*np.tanh(x) - x*sech)
    return num/(k + (x*x/2.0 + (1.0 + k*k)/2.0)*sech)


def s_frictionless(t):
    """S of a layer resting on a rigid base without friction: (cosh 2t - 1)/(sinh 2t + 2t)."""
    x = 2.0*np.asarray(t, dtype=float)
    sech = np.where(x < 700.0, 1.0/np.cosh(np.minimum(x, 700.0)), 0.0)
    return (1.0 - sech)/(np.tanh(x) + x*sech)


def wavenumbers(n, lx):
    """|q| [1/m] on ContactMechanics' half-spectrum (n//2 + 1, n): Nyquist counted positive."""
    qx = np.arange(n//2 + 1)/lx
    qy = np.abs(np.fft.fftfreq(n, lx/n))
    qy[n//2] = (n//2)/lx
    return 2.0*np.pi*np.hypot(qx[:, None], qy[None, :])


def substrate(nu, thickness, base="bonded"):
    with np.errstate(divide="ignore"):     # nu = 1/2: its q = 0 stiffness of the layer is infinite
        if base == "bonded":
            return PeriodicFFTElasticHalfSpace((N, N), E, (LX, LX), poisson=np.float64(nu),
                                               thickness=thickness or None)
        sub = PeriodicFFTElasticHalfSpace((N, N), E, (LX, LX), poisson=np.float64(nu))
    q = wavenumbers(N, LX)
    m = q > 0
    sub.greens_function[m] *= s_frictionless(q[m]*thickness)
    sub.surface_stiffness[m] = 1.0/sub.greens_function[m]
    return sub


def s_boundary_value(t, nu, base):
    """S from the boundary-value problem itself, solved numerically: the mode (U(z), W(z)) e^{iqx}
    of the layer 0 <= z <= d (z into the solid; q = 1, E = 1) obeys the Navier equations
      mu U'' - (lam + 2 mu) q^2 U + (lam + mu) i q W' = 0,
      (lam + 2 mu) W'' - mu q^2 W + (lam + mu) i q U' = 0,
    a first-order system y' = M y in y = (U, W, U', W') carried from z = 0 to d by expm(M d);
    four conditions (z = 0: sigma_zz = -1, sigma_xz = 0; z = d: U = W = 0 bonded, or W = 0 and
    sigma_xz = 0 frictionless) fix y(0), and S = W(0) over the half-space's 2 (1 - nu^2)."""
    from scipy.linalg import expm
    mu, lam = 0.5/(1.0 + nu), nu/((1.0 + nu)*(1.0 - 2.0*nu))
    m = np.zeros((4, 4), complex)
    m[0, 2] = m[1, 3] = 1.0
    m[2, 0], m[2, 3] = (lam + 2.0*mu)/mu, -1j*(lam + mu)/mu
    m[3, 1], m[3, 2] = mu/(lam + 2.0*mu), -1j*(lam + mu)/(lam + 2.0*mu)
    szz = np.array([1j*lam, 0.0, 0.0, lam + 2.0*mu])     # sigma_zz = lam (i q U + W') + 2 mu W'
    sxz = np.array([0.0, 1j*mu, mu, 0.0])                # sigma_xz = mu (U' + i q W)
    carry = expm(m*t)
    rows = [szz, sxz] + ([carry[0], carry[1]] if base == "bonded" else [carry[1], sxz @ carry])
    y0 = np.linalg.solve(np.array(rows), np.array([-1.0, 0.0, 0.0, 0.0]))
    assert abs(y0[1].imag) < 1e-12
    return y0[1].real/(2.0*(1.0 - nu**2))


@pytest.mark.parametrize("base", ["bonded", "frictionless"])
@pytest.mark.parametrize("nu", [0.0, 0.25, 0.3, 0.45, 0.49])
def test_s_is_the_boundary_value_problem(nu, base):
    """The closed forms (written anew here) against the boundary-value problem solved numerically,
    over the range where expm stays well conditioned (measured 1.6e-13 at most)."""
    for t in (0.05, 0.2, 0.5, 1.0, 2.0, 4.0):
        closed = s_bonded(t, nu) if base == "bonded" else s_frictionless(t)
        assert s_boundary_value(t, nu, base) == pytest.approx(closed, rel=1e-11)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.49, 0.5])
@pytest.mark.parametrize("qd", [0.01, 1.0, 30.0])
def test_contactmechanics_layer_is_the_bonded_base(nu, qd):
    d = qd*LX/(2.0*np.pi)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        half = PeriodicFFTElasticHalfSpace((N, N), E, (LX, LX), poisson=np.float64(nu))
        layer = PeriodicFFTElasticHalfSpace((N, N), E, (LX, LX), poisson=np.float64(nu), thickness=d)
    q = wavenumbers(N, LX)
    m = q > 0
    ratio = (layer.greens_function[m]/half.greens_function[m]).real
    t = q[m]*d
    # ContactMechanics forms kappa sinh 2t - 2t as it stands: for nu = 1/2 it cancels to
    # (2t)^3/6, a relative error ~1.5 eps/t^2 (measured 4e-13 at t = 0.01; 1e-15 from t = 0.1)
    assert np.all(np.abs(ratio/s_bonded(t, nu) - 1.0) < 1e-13 + 7e-16/t**2)
    if qd <= 1.0 and nu >= 0.3:         # thick layers are both the half-space; for nu = 0 thin
        assert np.max(np.abs(ratio/s_frictionless(t) - 1.0)) > 0.1    # ones both t/2


def solve_both(nu, thickness, base="bonded"):
    case = {"grid": {"nx": N, "ny": N, "lx_m": LX}, "surface": {"k_cut": 8, "seed": 3},
            "material": {"young_pa": E, "poisson": nu, "thickness_m": thickness, "base": base},
            "load": {"mean_pressure_pa": PRESSURE},
            "solver": {"tolerance": 1e-12, "fft_planner": "estimate", "method": "bccg"}}
    r = veslide.run(case, progress=None, threads=1)
    assert r.converged
    h = r.fields.height_m.transpose("x", "y").values           # [ix, iy], as ContactMechanics
    sub = substrate(nu, thickness, base)
    force = PRESSURE*LX*LX
    res = constrained_conjugate_gradients(sub, h, external_force=force, pentol=1e-14*h.std(),
                                          forcetol=1e-14*force/N**2, thermotol=1e-14, maxiter=10000)
    assert res.success
    return r, h, res


CASES = {"half-space": (0.3, 0.0, "bonded"), "bonded nu 0.3": (0.3, D, "bonded"),
         "bonded nu 0.5": (0.5, D, "bonded"), "frictionless nu 0.5": (0.5, D, "frictionless")}
_SOLVED = {}


def solved(name):
    if name not in _SOLVED:
        _SOLVED[name] = solve_both(*CASES[name])
    return _SOLVED[name]


@pytest.mark.parametrize("name", list(CASES))
def test_equals_contactmechanics(name):
    r, h, res = solved(name)
    s = r.scalars
    assert s.get("layer_thickness_m", 0.0) == CASES[name][1]     # written for a layer only
    p_cm = res.jac/(LX*LX/N**2)                                  # forces -> pressures [Pa]
    p = r.fields.pressure_pa.transpose("x", "y").values
    assert np.array_equal(p > 0, p_cm > 0)                       # the same cells in contact
    assert s["contact_area_fraction_cells"] == np.count_nonzero(p_cm > 0)/N**2
    assert 0.05 < s["contact_area_fraction_cells"] < 0.20
    gap_cm = (res.x - h - res.offset).mean()                     # its gap: u - h - offset
    assert s["mean_separation_m"] == pytest.approx(gap_cm, rel=1e-6)
    assert np.max(np.abs(p - p_cm)) < 1e-8*PRESSURE


def test_the_layer_matters_here():
    half = solved("half-space")[0].scalars["mean_separation_m"]
    for name in ("bonded nu 0.3", "bonded nu 0.5", "frictionless nu 0.5"):
        assert solved(name)[0].scalars["mean_separation_m"] > 1.25*half


def test_readme_layered_example(tmp_path, monkeypatch, exe):
    """docs/layers.md's block, a doctest, checked as test_readme checks the README's (warnings
    included: the example gives none)."""
    from test_readme import DOCS, NumberChecker
    page = DOCS / "layers.md"
    blocks = re.findall(r"^```python\n(.*?)^```$", page.read_text(), re.M | re.S)
    assert len(blocks) == 1 and blocks[0].startswith(">>> ")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("VESLIDE_EXE", str(exe))
    monkeypatch.setenv("OMP_NUM_THREADS", "1")
    runner = doctest.DocTestRunner(checker=NumberChecker(),
                                   optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    test = doctest.DocTestParser().get_doctest(blocks[0], {}, "docs/layers.md", str(page), 0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", veslide.VeslideWarning)
        runner.run(test)
    assert runner.summarize(verbose=False).failed == 0
