"""veslide.refine / veslide.convergence: the error band of a scalar from several grids."""
import math

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import veslide
from veslide.refinement import richardson
from conftest import params
from test_run import fake_exe

H = np.array([8.0, 4.0, 2.0, 1.0])          # cell sides, coarsest first


def test_exact_power_law_gives_its_order_and_limit():
    for p in (1.0, 1.5, 2.0):
        r = richardson(H, 1.0 + 0.3 * H ** p)
        assert r["observed_order"] == pytest.approx(p, abs=1e-6)
        assert r["extrapolated"] == pytest.approx(1.0, abs=1e-9)
        assert r["note"] == ""
        # no scatter: the band is 1.25 times the distance to the limit
        assert r["error"] == pytest.approx(1.25 * 0.3, rel=1e-6)
    # unequal ratios (nx = 256, 384, 512, 1024)
    h = 1.0 / np.array([256.0, 384.0, 512.0, 1024.0])
    r = richardson(h, 2.0 - 5.0 * h ** 1.5)
    assert r["observed_order"] == pytest.approx(1.5, abs=1e-6) and r["extrapolated"] == pytest.approx(2.0, abs=1e-9)


def test_scattered_values_widen_the_band_to_cover_the_error():
    rng = np.random.default_rng(5)
    h = 1.0 / np.array([64.0, 96.0, 128.0, 192.0, 256.0, 384.0])
    covered = 0
    for _ in range(200):
        # first order with a scatter of the size of the change over the grids (as the contact area)
        phi = 0.19 + 0.02 * h + 2e-4 * rng.standard_normal(len(h))
        r = richardson(h, phi)
        covered += r["error"] >= abs(phi[-1] - 0.19)
    assert covered >= 190           # a band, not a guarantee: 95 % of the draws at least


def test_few_grids_and_no_change():
    r = richardson(H[1:], 1.0 + H[1:] ** 2)
    assert r["observed_order"] == pytest.approx(2.0, abs=1e-6) and "three grids" in r["note"]
    assert r["error"] == pytest.approx(3.0, rel=1e-6)        # factor 3: no scatter can be measured
    r = richardson(H[2:], 1.0 + H[2:] ** 2)
    assert math.isnan(r["error"]) and "give assumed_order" in r["note"]
    r = richardson(H[2:], 1.0 + H[2:] ** 2, assumed_order=2)
    assert r["extrapolated"] == pytest.approx(1.0, abs=1e-12) and r["error"] == pytest.approx(3.0, rel=1e-12)
    r = richardson(H, np.full(4, 0.25))
    assert r["error"] == 0.0 and r["extrapolated"] == 0.25
    # faster than the method's orders on five grids: the coarsest left out, the fits in h, h^2
    h5 = np.array([16.0, 8.0, 4.0, 2.0, 1.0])
    r = richardson(h5, 1.0 + 1e-3 * h5 ** 3)
    assert r["note"].startswith("coarsest 1 grid left out (order above 2.1 with it); observed order 3 ")
    assert r["error"] >= abs(r["finest"] - 1.0)           # covers the error, conservatively
    # values that are not finite give no band
    r = richardson(H, np.array([1.0, np.nan, 0.5, 0.4]))
    assert math.isnan(r["error"]) and r["note"] == "a value is not finite (grids 2): no band"
    with pytest.raises(ValueError, match="coarsest first"):
        richardson(H[::-1], H)


def _bisinusoid(p_ratio=0.1):
    e_star = 1e7 / (1 - 0.5 ** 2)
    d, l = 1e-5, 0.01
    p_star = math.sqrt(2) * math.pi * e_star * d / l
    return params(surface={"kind": "bisinusoid", "amplitude_m": d, "wavelength_m": l},
                  load={"mean_pressure_pa": p_ratio * p_star}, solver={"tolerance": 1e-12},
                  output={"fields": False})


def test_refine_band_covers_a_finer_solve(tmp_path, exe):
    sizes = [128, 192, 256, 384]
    ref = veslide.refine(_bisinusoid(), sizes, tmp_path / "r", exe=exe, progress=None)
    t = ref.table
    assert list(t.index) == sizes and list(t["ny"]) == sizes
    assert np.allclose(t["cell_m"], 0.01 / t.index.to_numpy()) and t["converged"].all()
    assert sorted(p.name for p in (tmp_path / "r").iterdir()) == ["refine-128x128.h5", "refine-192x192.h5",
                                                                   "refine-256x256.h5", "refine-384x384.h5"]
    fine = veslide.run(dict(_bisinusoid(), grid={"nx": 1024, "ny": 1024}), output=tmp_path / "fine.h5", exe=exe,
                       progress=None)
    for name in ("contact_area_fraction", "contact_area_fraction_cells", "mean_separation_m"):
        e = ref.estimate.loc[name]
        assert e["finest"] == t[name].iloc[-1]
        assert e["error"] >= abs(e["finest"] - fine.scalars[name]), name
    # the band is a band: within 1 % of the value for the area, 1e-3 for the separation
    e = ref.estimate
    assert e.loc["contact_area_fraction", "relative_error"] <= 0.01
    assert e.loc["mean_separation_m", "relative_error"] <= 1e-3
    # the cell count converges to the same area, more slowly: its band is the wider
    assert e.loc["contact_area_fraction", "error"] < e.loc["contact_area_fraction_cells", "error"]
    assert e.loc["contact_area_fraction_cells", "error"] >= abs(t["contact_area_fraction_cells"].iloc[-1]
                                                               - fine.scalars["contact_area_fraction"])
    assert e.loc["contact_area_fraction", "units"] == "-" and e.loc["mean_separation_m", "units"] == "m"

    # the same input again reads the files (the executable is not run)
    import subprocess
    version = subprocess.run([str(exe), "--version"], capture_output=True, text=True).stdout.strip()
    fails = fake_exe(tmp_path / "fails", 'if [ "$1" = --version ]; then echo "%s"; exit 0; fi; exit 3' % version)
    again = veslide.refine(_bisinusoid(), sizes, tmp_path / "r", exe=fails, progress=None)
    assert again.estimate.equals(ref.estimate)
    # another input in the same directory is refused, nothing replaced
    other = _bisinusoid(0.2)
    with pytest.raises(FileExistsError, match="another input"):
        veslide.refine(other, [128, 192], tmp_path / "r", exe=fails, progress=None)
    newer = fake_exe(tmp_path / "newer", 'if [ "$1" = --version ]; then echo "veslide 99.0.0"; exit 0; fi; exit 3')
    with pytest.raises(FileExistsError, match="written by veslide .* the program is 99.0.0"):
        veslide.refine(_bisinusoid(), sizes, tmp_path / "r", exe=newer, progress=None)
    with pytest.raises(veslide.VeslideError, match="exit status 3"):       # overwrite runs again
        veslide.refine(_bisinusoid(), sizes, tmp_path / "r", exe=fails, overwrite=True, progress=None)
    with pytest.raises(FileExistsError, match="reuse=True"):
        veslide.refine(_bisinusoid(), [128, 192], tmp_path / "r", exe=fails, reuse=False, progress=None)

    # the same files through convergence(), in any order
    files = sorted((tmp_path / "r").glob("*.h5"))
    assert veslide.convergence(files).estimate.equals(ref.estimate)
    # and through its table written to CSV and read back
    ref.table.to_csv(tmp_path / "t.csv")
    back = veslide.Refinement.from_table(pd.read_csv(tmp_path / "t.csv", index_col="nx"),
                                         units=ref.estimate["units"].to_dict())
    assert back.estimate.equals(ref.estimate)

    # the plot: the values on each grid, the band on the finest, the limit dashed
    import matplotlib.pyplot as plt
    import veslide.plot as vp
    ax = vp.refinement(ref, "contact_area_fraction")
    np.testing.assert_array_equal(ax.lines[0].get_xdata(), sizes)
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), t["contact_area_fraction"])
    bar = ax.collections[0].get_segments()[0]                 # the error bar at the finest grid
    assert bar[0][0] == sizes[-1]
    assert (bar[1][1] - bar[0][1]) / 2 == pytest.approx(e.loc["contact_area_fraction", "error"])
    assert ax.get_xscale() == "log" and "A/A_0" in ax.get_ylabel()
    plt.close("all")


def test_a_study_is_refined_case_by_case(tmp_path, exe):
    base = _bisinusoid()
    pressures = [0.5 * base["load"]["mean_pressure_pa"], base["load"]["mean_pressure_pa"]]
    study = dict(base, sweep={"pressures_pa": pressures})
    sizes = [64, 96, 128, 192]
    ref = veslide.refine(study, sizes, tmp_path / "s", exe=exe, progress=None)
    assert isinstance(ref, veslide.StudyRefinement) and ref.converged and sorted(ref.cases) == [1, 2]
    assert len(ref.table) == 8 and sorted(set(ref.table.index.get_level_values("nx"))) == sizes
    e = ref.estimate
    assert list(e.loc[(2, "contact_area_fraction"), ["pressure_pa"]]) == [pressures[1]]
    # each case is the single case at its pressure, refined alone
    one = veslide.refine(dict(base, load={"mean_pressure_pa": pressures[0]}), sizes, tmp_path / "one", exe=exe,
                         progress=None)
    for name in ("contact_area_fraction", "mean_separation_m"):
        a, b = e.loc[(1, name)], one.estimate.loc[name]
        assert a["finest"] == pytest.approx(b["finest"], rel=1e-9)
        assert a["error"] == pytest.approx(b["error"], rel=1e-3, abs=1e-12 * abs(b["finest"]))
    assert ref.cases[1].estimate.loc["contact_area_fraction", "error"] == e.loc[(1, "contact_area_fraction"), "error"]
    # the same study files through convergence()
    again = veslide.convergence(sorted((tmp_path / "s").glob("*.h5")))
    assert again.estimate.equals(ref.estimate)
    with pytest.raises(ValueError, match="not both"):
        veslide.convergence(ref.results[:2] + one.results[2:])


def test_refine_refuses_what_it_cannot_refine(tmp_path, exe):
    with pytest.raises(ValueError, match="kind = 'file'"):
        veslide.refine(params(surface={"kind": "file", "file": "x.h5"}), [32, 64], tmp_path, exe=exe, progress=None)
    with pytest.raises(ValueError, match="aspect"):
        veslide.refine(params(grid={"nx": 32, "ny": 16}), [32, 33], tmp_path, exe=exe, progress=None)
    with pytest.raises(ValueError, match="at least two"):
        veslide.refine(params(), [64], tmp_path, exe=exe, progress=None)


def test_convergence_refuses_runs_of_different_cases(tmp_path, exe):
    # a profile (ny = 1) keeps ny = 1; two seeds are two different cases
    base = params(grid={"nx": 32, "ny": 1}, surface={"k_cut": 4}, output={"fields": False})
    ref = veslide.refine(base, [32, 64], tmp_path / "a", exe=exe, progress=None)
    assert list(ref.table["ny"]) == [1, 1]
    other = veslide.refine(dict(base, surface={"k_cut": 4, "seed": 7}), [128, 256], tmp_path / "b", exe=exe,
                           progress=None)
    with pytest.raises(ValueError, match="&surface seed"):
        veslide.convergence(ref.results + other.results)
    with pytest.raises(ValueError, match="same grid"):
        veslide.convergence([ref.results[0], ref.results[0]])
    wider = veslide.run(dict(base, grid={"nx": 128, "ny": 1, "lx_m": 0.02}), output=tmp_path / "w.h5", exe=exe,
                        progress=None)
    with pytest.raises(ValueError, match="&grid lx_m"):
        veslide.convergence(ref.results + [wider])
    # a rectangle refined along x only is not a refinement
    rect = params(grid={"nx": 32, "ny": 16, "ly_m": 0.005}, surface={"k_cut": 4}, output={"fields": False})
    a = veslide.refine(rect, [32, 64], tmp_path / "c", exe=exe, progress=None)
    assert list(a.table["ny"]) == [16, 32]
    b = veslide.run(dict(rect, grid={"nx": 128, "ny": 16, "ly_m": 0.005}), output=tmp_path / "b.h5", exe=exe,
                    progress=None)
    with pytest.raises(ValueError, match="not refined alike"):
        veslide.convergence(a.results + [b])


def test_command_line(tmp_path, exe, monkeypatch):
    import subprocess
    import sys
    nml = veslide.write_namelist(params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 4},
                                        output={"fields": False}), tmp_path / "case.nml")
    monkeypatch.setenv("VESLIDE_EXE", str(exe))
    cmd = [sys.executable, "-m", "veslide", "refine", str(nml), "32", "48", "64", "--output-dir", str(tmp_path / "r")]
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert "contact_area_fraction" in out.stdout and "observed_order" in out.stdout
    assert sorted(p.name for p in (tmp_path / "r").iterdir()) == ["refine-32x32.h5", "refine-48x48.h5",
                                                                   "refine-64x64.h5"]
    assert "Traceback" not in out.stderr
    # k_cut = 4 is not below the Nyquist wavenumber of 8 cells: the program's message, nothing left
    bad = subprocess.run(cmd[:5] + ["8", "16", "--output-dir", str(tmp_path / "s")], capture_output=True,
                         text=True, cwd=tmp_path)
    assert bad.returncode == 1 and "&surface k_cut" in bad.stderr and not (tmp_path / "s").exists()


def test_figure_script_on_the_committed_tables(tmp_path):
    import subprocess
    import sys
    repo = Path(veslide.__file__).resolve().parents[2]
    default, bis = repo / "docs/figures/refinement-default.csv", repo / "docs/figures/refinement-bisinusoid.csv"
    t = pd.read_csv(bis, index_col="nx")
    r = veslide.Refinement.from_table(t.loc[[512, 1024, 2048, 4096]])
    a = t["contact_area_fraction"]
    assert r.estimate.loc["contact_area_fraction", "error"] >= abs(a[4096] - a[8192])
    out = subprocess.run([sys.executable, str(repo / "postproc/plot_refinement.py"), str(default), str(bis),
                          str(tmp_path / "f.png")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "f.png").stat().st_size > 10000


def test_refine_raises_the_finest_grids_warnings_only(tmp_path, exe):
    """The coarse grids of a refinement are coarse by design: their contact-resolution warnings
    stay with their results; the finest grid's would be raised (here it has none)."""
    import warnings
    base = {"grid": {"nx": 32, "ny": 32}, "surface": {"k_cut": 8}, "material": {"model": "one_term"},
            "motion": {"speed_m_s": 0.13}, "solver": {"fft_planner": "estimate"}}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ref = veslide.refine(base, [32, 64, 128], tmp_path, exe=exe, progress=None)
    assert [w for w in caught if isinstance(w.message, veslide.VeslideWarning)] == []
    assert [w.code for w in ref.results[0].warnings] == ["contact-resolution"]
    assert ref.results[-1].warnings == []
