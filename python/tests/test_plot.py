"""veslide.plot: every helper draws from a result, labels with units, and maps are not transposed."""
import matplotlib.pyplot as plt
import numpy as np
import pytest

import veslide
import veslide.plot as vp


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def test_maps_put_x_across_and_y_up(case):
    ax = vp.pressure_map(case)
    image = ax.images[0].get_array()
    p = case.fields.pressure_pa.values                       # [ix, iy], 32 x 16
    np.testing.assert_allclose(image, p.T * 1e-3)            # rows are y
    x0, x1, y0, y1 = ax.images[0].get_extent()
    assert x1 - x0 == pytest.approx(case.scalars["length_x_m"] * 1e3)
    assert y1 - y0 == pytest.approx(case.scalars["length_y_m"] * 1e3)
    assert ax.get_xlabel() == "$x$ [mm]" and ax.images[0].colorbar.ax.get_ylabel() == "$p$ [kPa]"
    ax = vp.contact_map(case)
    np.testing.assert_array_equal(ax.images[0].get_array(), (p.T > 0).astype(float))
    assert "A/A_0" in ax.get_title()
    ax = vp.gap_map(case)
    assert ax.images[0].colorbar.ax.get_ylabel() == r"$g$ [$\mu$m]"
    with pytest.raises(ValueError, match="length_m"):
        vp.pressure_map(p)
    vp.pressure_map(p, length_m=0.01)


def test_psd_of_a_cosine_peaks_at_its_wavevector():
    n, L = 32, 0.01
    x = np.arange(n) * L / n
    h = 1e-6 * np.cos(2 * np.pi * 3 * x / L)[:, None] * np.ones(n)    # h[ix, iy], along x
    qx, qy, c = veslide.psd_2d(h, L)
    ix, iy = np.unravel_index(np.argmax(c), c.shape)
    assert abs(qx[ix]) == pytest.approx(3 * 2 * np.pi / L) and qy[iy] == 0
    assert c.sum() * (2 * np.pi / L) ** 2 == pytest.approx(np.mean(h ** 2))   # <h^2> = sum C dq^2
    q, cr = veslide.psd_radial(h, L)
    assert q[np.argmax(cr)] == pytest.approx(3 * 2 * np.pi / L)
    ax = vp.psd(h, length_m=L)
    assert "m$^4$" in ax.get_ylabel() and ax.get_xscale() == "log"
    ax = vp.psd_2d(h, length_m=L)
    assert ax.get_xlabel() == "$q_x/q_0$"


def test_surface_plots_from_a_result(case):
    vp.psd(case)
    vp.psd_2d(case)
    pair = vp.anisotropy_polar(case)
    assert len(pair) == 2 and all(a.name == "polar" for a in pair)
    assert "rigid surface" in pair[0].get_title() and "deformed solid" in pair[1].get_title()
    one = plt.figure().add_subplot(projection="polar")
    assert vp.anisotropy_polar(case, one, normalise=True) is one and len(one.get_legend().texts) == 2
    with pytest.raises(ValueError, match="polar"):
        vp.anisotropy_polar(case, plt.figure().add_subplot())


def test_forces_against_speed_with_ensemble_error_bars(study):
    ax = vp.friction_vs_speed(study)
    assert ax.get_xscale() == "log" and ax.get_xlabel() == "$v$ [m/s]"
    assert ax.get_ylabel().startswith(r"$\mu") and "2 seeds" in ax.get_title()
    assert len(ax.containers) == 2                               # one line per alpha
    bars = ax.containers[0]
    assert bars.has_yerr
    y = bars.lines[0].get_ydata()
    e = study.ensemble.sort_values("speed_m_s")
    np.testing.assert_allclose(y, e[e.alpha_deg == 0]["mean_friction_coefficient"])
    ax = vp.lateral_vs_speed(study)
    assert ax.get_ylabel().startswith(r"$F_\perp")
    ax = vp.force_vs_speed(study.summary, "contact_area_fraction")   # a DataFrame, per seed
    assert len(ax.containers) == 4 and ax.get_ylabel() == "$A/A_0$"


def test_friction_against_the_direction_of_sliding(study):
    ax = vp.friction_polar(study)
    assert ax.name == "polar" and len(ax.containers) == 2         # one curve per speed
    theta = ax.containers[0].lines[0].get_xdata()
    np.testing.assert_allclose(sorted(np.degrees(theta)), [-90.0, 0.0])   # v along x, alpha 0 and 90
    ax = vp.friction_polar([study.cases[1], study.cases[3]])      # single cases
    assert len(ax.lines) >= 1
