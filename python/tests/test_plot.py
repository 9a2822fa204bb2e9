"""veslide.plot: every helper draws from a result, labels with units, and maps are not transposed."""
import os

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


def test_map_window_wraps_around_the_periodic_cell(case):
    p = case.fields.pressure_pa.values                       # [ix, iy], 32 x 16
    lx, ly = case.scalars["length_x_m"], case.scalars["length_y_m"]
    dx, dy = lx / 32, ly / 16
    ax = vp.pressure_map(case, window=(-2 * dx, 14 * dy, 6 * dx, 4 * dy), unit="Pa", zero_color="white")
    image = ax.images[0].get_array()
    want = p[np.ix_(np.arange(-2, 4) % 32, np.arange(14, 18) % 16)].T
    np.testing.assert_allclose(image.filled(0.0), want)
    assert np.ma.getmaskarray(image).tolist() == (want <= 0).tolist()     # no contact: the 'bad' colour
    x0, x1, y0, y1 = ax.images[0].get_extent()
    assert (x0, x1) == pytest.approx((-2.5 * dx * 1e3, 3.5 * dx * 1e3))
    assert (y0, y1) == pytest.approx((13.5 * dy * 1e3, 17.5 * dy * 1e3))
    vp.contact_map(case, window=(0, 0, lx / 2, ly / 2), arrow=False)
    ax = vp.gap_map(case, contact_color="deepskyblue")
    assert np.ma.getmaskarray(ax.images[0].get_array()).tolist() == (p.T > 0).tolist()


def test_psd_options():
    n, L = 32, 0.01
    h = np.random.default_rng(1).normal(size=(n, n)) * 1e-6
    ax = vp.psd(h, length_m=L, relative=True, hurst=0.8)
    assert ax.get_xlabel() == "$q/q_0$" and len(ax.lines) == 2            # the curve and the slope
    x = ax.lines[0].get_xdata()
    assert x[0] == pytest.approx(1.0)
    ax = vp.psd(h, length_m=L, relative=True, q_max=10)
    assert ax.lines[0].get_xdata().max() == pytest.approx(10)
    ax = vp.psd_2d(h, length_m=L, q_max=5)
    assert ax.get_xlim() == (-5, 5) and ax.get_ylim() == (-5, 5)


def test_against_speed_scaled_with_theory_and_a_function_of_the_cases(study):
    ax = vp.force_vs_speed(study, "friction_coefficient", speed_scale=2.0, speed_label="s", by=["alpha_deg"],
                           formats={"alpha_deg": lambda a: "a%g" % a})
    x = ax.containers[0].lines[0].get_xdata()
    np.testing.assert_allclose(x, 2.0 * np.sort(study.ensemble.speed_m_s.unique()))
    assert ax.get_xlabel() == "s" and ax.get_legend_handles_labels()[1] == ["a0", "a90"]
    s = study.summary
    ax = vp.force_vs_speed(study, lambda t: t.mean_separation_m / t.rms_height_m, ylabel="ratio")
    e = vp.seed_means(s, s.mean_separation_m / s.rms_height_m)
    e = e[e.alpha_deg == 0].sort_values("speed_m_s")
    np.testing.assert_allclose(ax.containers[0].lines[0].get_ydata(), e["mean_value"])
    seeds = s[(s.alpha_deg == 0) & (s.speed_m_s == e.speed_m_s.iloc[0])]
    ratio = seeds.mean_separation_m / seeds.rms_height_m
    assert e["sem_value"].iloc[0] == pytest.approx(ratio.std(ddof=1) / np.sqrt(len(ratio)))
    assert ax.get_ylabel() == "ratio" and "2 seeds" in ax.get_title()
    ax = vp.force_vs_speed(study, "max_pressure_pa", unit="kPa")
    e = study.ensemble
    np.testing.assert_allclose(ax.containers[0].lines[0].get_ydata(),
                               e[e.alpha_deg == 0].sort_values("speed_m_s")["mean_max_pressure_pa"] / 1e3)
    assert ax.get_ylabel() == r"$p_\mathrm{max}$ [kPa]"
    assert vp.label("phi_rad", "deg") == r"$\phi$ [$^\circ$]" and vp._SCALE["deg"] == pytest.approx(180 / np.pi)


def test_theory_dashed_in_the_colour_of_its_line(exe, tmp_path):
    from conftest import params
    p = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, material={"model": "one_term"},
               output={"fields": False}, analysis={"persson": True},
               sweep={"speeds_m_s": [0.01, 0.1], "eccentricities": [1.0, 0.5]})
    s = veslide.run(p, output=tmp_path / "t.h5", exe=exe, progress=None)
    ax = vp.friction_vs_speed(s, theory="persson_friction_coefficient", theory_label="theory")
    dashed = [line for line in ax.lines if line.get_linestyle() == "--" and len(line.get_xdata())]
    assert len(dashed) == 2
    assert dashed[0].get_color() == ax.containers[0].lines[0].get_color()
    assert "theory" in ax.get_legend_handles_labels()[1]


def test_friction_polar_mirrored_around_the_circle(study):
    ax = vp.friction_polar(study, speeds=[study.summary.speed_m_s.min()], mirror=True)
    filled, images = ax.containers[0], ax.containers[1]
    assert sorted(np.degrees(filled.lines[0].get_xdata())) == pytest.approx([-90.0, 0.0])
    assert sorted(np.degrees(images.lines[0].get_xdata())) == pytest.approx([90.0, 180.0])
    np.testing.assert_allclose(sorted(images.lines[0].get_ydata()), sorted(filled.lines[0].get_ydata()))
    theta, r = vp._mirrored(np.array([-30.0]), np.array([1.0]), np.array([0.1]), odd=True)[:2]
    assert dict(zip(np.round(theta), r)) == {-150.0: -1.0, 30.0: -1.0, 150.0: 1.0}


def test_save_writes_png_pdf_and_svg(tmp_path):
    with vp.paper_style():
        fig, ax = plt.subplots(figsize=(3.4, 2.5))
        ax.plot([0, 1], [0, 1])
        ax.set_xlabel(r"$v\tau/L_0$")
        paths = vp.save(fig, tmp_path / "f.png")
    assert [p[-3:] for p in paths] == ["png", "pdf", "svg"]
    assert all(os.path.getsize(p) > 0 for p in paths)
    from PIL import Image
    with Image.open(paths[0]) as im:
        assert im.info["dpi"] == pytest.approx((300, 300), abs=0.01)
        assert 900 < im.size[0] <= 1020 and 650 < im.size[1] <= 750     # 3.4 x 2.5 in, trimmed to the ink
    assert b"CreationDate" not in open(paths[1], "rb").read()


def _overlaps(boxes):
    """Pairs of display boxes that overlap (each a matplotlib Bbox)."""
    return [(i, j) for i in range(len(boxes)) for j in range(i + 1, len(boxes))
            if boxes[i].overlaps(boxes[j])]


def _angle_labels(axes):
    """(texts, boxes) of the drawn angle tick labels of polar axes, all together."""
    fig = axes[0].figure
    fig.draw_without_rendering()
    r = fig.canvas.get_renderer()
    texts, boxes = [], []
    for ax in axes:
        for tick in ax.xaxis.get_major_ticks():
            if tick.label1.get_visible() and tick.label1.get_text():
                texts.append(tick.label1.get_text())
                boxes.append(tick.label1.get_window_extent(r))
    return texts, boxes


def test_default_polar_plots_have_clear_angle_labels_and_one_stated_radial_scale(case, study):
    pair = vp.anisotropy_polar(case)                         # returns the pair of axes it made
    assert len(pair) == 2 and pair[0].figure is pair[1].figure
    texts, boxes = _angle_labels(list(pair))
    assert len(texts) == 16 and len(set(texts[:8])) == 8      # 8 distinct angles per axes
    assert _overlaps(boxes) == []                             # no "0°180°" between the two axes
    for ax, base in zip(pair, ("m2_surface", "mu2_deformed")):
        e = int(np.floor(np.log10(case.anisotropy[base].max())))
        assert r"10^{%d}" % e in ax.get_title()              # the one factor, stated in the title
        assert not ax.yaxis.offsetText.get_visible()
        ticks = [t for t in ax.yaxis.get_major_ticks() if t.label1.get_text()]
        assert ticks
        for t in ticks:                                      # plain numbers: the radius / 10^e
            text = t.label1.get_text().replace(r"\mathdefault{", "").strip("${}").replace("\u2212", "-")
            assert float(text) == pytest.approx(t.get_loc() / 10.0 ** e)
        assert len(ax.get_title().split("\n")) <= 2 and max(len(t) for t in ax.get_title().split("\n")) < 60
    ax = vp.friction_polar(study, mirror=True)
    texts, boxes = _angle_labels([ax])
    assert len(set(texts)) == 8 and _overlaps(boxes) == []
    assert "\n" not in ax.get_title() and len(ax.get_title()) < 60


def test_radial_labels_are_put_clear_of_the_curves():
    fig, ax = plt.subplots(subplot_kw=dict(projection="polar"))
    theta = np.linspace(0, 2 * np.pi, 361)
    ax.plot(theta, 1.0 + 0.5 * np.cos(2 * theta))             # a peanut: long along 0 and 180 deg
    ax.set_rmax(1.6)
    ax.set_rgrids([0.5, 1.0, 1.5])
    angle = vp.place_radial_labels(ax)
    fig.draw_without_rendering()
    r = fig.canvas.get_renderer()
    xy = ax.transData.transform(np.column_stack([theta, 1.0 + 0.5 * np.cos(2 * theta)]))
    for tick in ax.yaxis.get_major_ticks():
        b = tick.label1.get_window_extent(r)
        inside = (xy[:, 0] >= b.x0) & (xy[:, 0] <= b.x1) & (xy[:, 1] >= b.y0) & (xy[:, 1] <= b.y1)
        assert not inside.any(), (angle, tick.get_loc())
    assert vp.radial_scale(ax) == 0                            # radii near 1: labelled as they are


def test_contact_map_names_its_area():
    p = np.zeros((8, 8))
    p[:2, :2] = 1.0
    ax = vp.contact_map(p, length_m=0.01)
    assert "0.0625 (fraction of cells)" in ax.get_title()
