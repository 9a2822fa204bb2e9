"""&interface shear_coefficient: a full-slip Coulomb shear mu_f p on the solid along v (docs/interface.md).

What is checked:
- the coupling the program uses, u_z(q) = K_p(q) [p(q) - i beta (q.t(q))/|q|], beta = (1 - 2 nu)/(2 (1 - nu)),
  is the boundary-value problem of a surface mode of the half-space solved numerically here (the
  Navier equations of a mode exp(i q x), its decaying solutions the null space of (M + q)^2, two
  traction conditions): the coefficient and its sign, for nu = 0 to 0.499 (lam grows without
  bound towards 1/2, where beta = 0), independently of the program and of docs/interface.md;
- a single wave in full contact under that shear, solved by the program, has the pressure
  p0 + Re[h0 exp(i q.x)/K(q)] with K built from that boundary-value problem (not from the
  program's formula), and the friction parts the program writes are this pressure's: the
  hysteresis part -(h0^2/2) (q.v_hat) Im(1/K)/p0 (negative: the pressure sits on the trailing
  flank), the interfacial part mu_f, their sum the friction coefficient, the lateral force
  (h0^2/2) (q.(z x v_hat)) Im(1/K)/p0; the input echo and /scalars/shear_coefficient hold mu_f;
- on an incompressible solid (nu = 1/2) a study with the shear has the same contact as without it
  and every row's friction is mu_f higher, the parts as columns of /summary;
- a layer with shear, and pk with shear, are refused in one line.
"""
import numpy as np
import pytest

import veslide
from conftest import params

E, NU, MU_F = 1.0e7, 0.3, 0.5
L, H0, P0 = 0.01, 1.0e-6, 1.0e5


def surface_mode(nu, p, t):
    """u_z(0) of the half-space z > 0 (z into the solid; q = 1, E = 1) under the surface tractions
    p (along +z, a pressure) and t (along +x) of the mode exp(i x): the mode (U(z), W(z)) obeys
      mu U'' - (lam + 2 mu) U + (lam + mu) i W' = 0,  (lam + 2 mu) W'' - mu W + (lam + mu) i U' = 0,
    y' = M y in y = (U, W, U', W'); the solutions that decay into the solid are the null space of
    (M + 1)^2 (M's eigenvalues are +-1, each double); sigma_zz(0) = -p and sigma_xz(0) = -t (the
    traction on a surface whose outward normal is -z) fix the solution."""
    from scipy.linalg import null_space
    mu, lam = 0.5/(1.0 + nu), nu/((1.0 + nu)*(1.0 - 2.0*nu))
    m = np.zeros((4, 4), complex)
    m[0, 2] = m[1, 3] = 1.0
    m[2, 0], m[2, 3] = (lam + 2.0*mu)/mu, -1j*(lam + mu)/mu
    m[3, 1], m[3, 2] = mu/(lam + 2.0*mu), -1j*(lam + mu)/(lam + 2.0*mu)
    decaying = null_space((m + np.eye(4)) @ (m + np.eye(4)))
    assert decaying.shape == (4, 2)
    szz = np.array([1j*lam, 0.0, 0.0, lam + 2.0*mu])     # sigma_zz = lam (i U + W') + 2 mu W'
    sxz = np.array([0.0, 1j*mu, mu, 0.0])                # sigma_xz = mu (U' + i W)
    c = np.linalg.solve(np.array([szz @ decaying, sxz @ decaying]), np.array([-p, -t]))
    return (decaying @ c)[1]


@pytest.mark.parametrize("nu", [0.0, 0.2, 0.3, 0.45, 0.49, 0.499])
def test_the_coupling_is_the_boundary_value_problem(nu):
    """W(p = 1) is the half-space's 2 (1 - nu^2)/(E |q|); W(t = 1)/W(p = 1) = -i beta for the mode
    exp(+i q x), q > 0, with a shear along +x: the solid sinks ahead of a forward shear."""
    beta = (1.0 - 2.0*nu)/(2.0*(1.0 - nu))
    wp = surface_mode(nu, 1.0, 0.0)
    wt = surface_mode(nu, 0.0, 1.0)
    assert wp == pytest.approx(2.0*(1.0 - nu**2), rel=1e-12)
    assert wt/wp == pytest.approx(-1j*beta, abs=1e-12)


def kernel_of_mode(q, vhat):
    """K(q) [m/Pa] of the elastic half-space under the shear mu_f p vhat, from the boundary-value
    problem: the shear's component along q couples (the one across q moves the surface along
    itself only), so K = K_p (1 + mu_f (q.vhat)/|q| W(t = 1)/W(p = 1))."""
    qn = np.linalg.norm(q)
    coupling = surface_mode(NU, 0.0, 1.0)/surface_mode(NU, 1.0, 0.0)
    return 2.0*(1.0 - NU**2)/(E*qn)*(1.0 + MU_F*(q @ vhat)/qn*coupling)


@pytest.fixture(scope="module")
def wave(exe, tmp_path_factory):
    """A wave at 45 degrees (2 x 2 wavelengths on the cell), v at 30 degrees, full contact."""
    out = tmp_path_factory.mktemp("interface") / "wave.h5"
    p = params(grid={"nx": 32, "ny": 32, "lx_m": L},
               surface={"kind": "cosine", "amplitude_m": H0, "wavelength_m": L/(2.0*np.sqrt(2.0)),
                        "direction_deg": 45.0},
               material={"young_pa": E, "poisson": NU}, load={"mean_pressure_pa": P0},
               motion={"direction_deg": 30.0}, interface={"shear_coefficient": MU_F},
               solver={"tolerance": 1e-12})
    return veslide.run(p, output=out, exe=exe, progress=None)


def test_single_wave_pressure_is_the_boundary_value_problem(wave):
    q = 2.0*np.pi*2.0/L*np.array([1.0, 1.0])
    vhat = np.array([np.cos(np.pi/6), np.sin(np.pi/6)])
    k = kernel_of_mode(q, vhat)
    p = wave.fields.pressure_pa
    x, y = np.meshgrid(p.x.values, p.y.values, indexing="ij")
    expected = P0 + np.real(H0/k*np.exp(1j*(q[0]*x + q[1]*y)))
    assert wave.scalars["contact_area_fraction"] == 1.0
    assert np.max(np.abs(p.values - expected)) <= 1e-9*abs(H0/k)


def test_single_wave_friction_parts(wave):
    q = 2.0*np.pi*2.0/L*np.array([1.0, 1.0])
    vhat = np.array([np.cos(np.pi/6), np.sin(np.pi/6)])
    lat = np.array([-vhat[1], vhat[0]])
    k = kernel_of_mode(q, vhat)
    force = 0.5*H0**2*q*np.imag(1.0/k)                 # <p grad h> of that pressure
    s = wave.scalars
    hysteresis = -(force @ vhat)/P0
    assert hysteresis < 0.0
    assert s["friction_hysteresis"] == pytest.approx(hysteresis, rel=1e-9)
    assert s["friction_interfacial"] == pytest.approx(MU_F, abs=1e-9)
    assert s["friction_coefficient"] == pytest.approx(hysteresis + MU_F, abs=1e-9)
    assert s["lateral_force_ratio"] == pytest.approx((force @ lat)/P0, rel=1e-9)
    assert s.units["friction_hysteresis"] == "-" and s.units["friction_interfacial"] == "-"
    assert s["shear_coefficient"] == MU_F
    assert wave.input["interface"]["shear_coefficient"] == MU_F


def test_incompressible_study_adds_mu_f(exe, tmp_path):
    """nu = 1/2 (beta = 0): a study of speeds with and without the shear: the same contact, the
    friction mu_f higher in every row, the parts as columns."""
    def study(shear, name):
        groups = dict(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8, "eccentricity": 0.5},
                      material={"model": "one_term", "poisson": 0.5}, motion={"direction_deg": 20.0},
                      load={"mean_pressure_pa": 2e5},
                      sweep={"speeds_m_s": [0.01, 0.1]}, solver={"tolerance": 1e-12})
        if shear:
            groups["interface"] = {"shear_coefficient": shear}
        return veslide.run(params(**groups), output=tmp_path/name, exe=exe, progress=None).summary
    without, with_shear = study(0.0, "s0.h5"), study(0.4, "s1.h5")
    assert "friction_hysteresis" not in without.columns and "shear_coefficient" not in without.columns
    assert np.array_equal(with_shear["contact_area_fraction"], without["contact_area_fraction"])
    assert np.allclose(with_shear["friction_coefficient"] - without["friction_coefficient"], 0.4, rtol=0, atol=1e-9)
    assert np.array_equal(with_shear["friction_hysteresis"], without["friction_coefficient"])
    assert np.allclose(with_shear["friction_interfacial"], 0.4, rtol=0, atol=1e-9)


@pytest.mark.parametrize("groups, words", [
    ({"material": {"thickness_m": 1e-3}}, ["&interface shear_coefficient", "layer", "not available"]),
    ({"material": {"poisson": 0.3}, "solver": {"method": "pk"}}, ["'pk'", "not symmetric"]),
    ({"interface": {"shear_coefficient": -0.2}}, ["&interface shear_coefficient", "0 to 10"]),
])
def test_refused_in_one_line(exe, tmp_path, groups, words):
    g = {"grid": {"nx": 32, "ny": 32}, "surface": {"k_cut": 8}, "interface": {"shear_coefficient": 0.3}}
    for k, v in groups.items():
        g.setdefault(k, {}).update(v)
    with pytest.raises(veslide.InputError) as info:
        veslide.run(params(**g), output=tmp_path/"refused.h5", exe=exe, progress=None)
    message = str(info.value)
    assert "\n" not in message.strip() and all(w in message for w in words), message
