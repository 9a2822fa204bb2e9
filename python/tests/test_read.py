"""veslide.read on a single case and on a study: every part of the result against the file."""
from collections.abc import Mapping

import f90nml
import h5py
import numpy as np
import pandas as pd
import pytest
import xarray as xr

import veslide


def test_scalars_are_the_files_with_units_and_python_types(case):
    assert case.converged is True and case.returncode == 0
    with h5py.File(case.path, "r") as f:
        g = f["/scalars"]
        assert set(case.scalars) == set(g)
        for name, ds in g.items():
            assert case.scalars[name] == ds[()], name
            assert case.scalars.units[name] == ds.attrs["units"], name
            want = int if ds.dtype.kind == "i" else float
            assert type(case.scalars[name]) is want, name
        want = {"solver_method": g.attrs["solver_method"], "kernel_variant": g.attrs["kernel_variant"],
                "device": g.attrs["device"]}
        if "device_transfer_seconds" in g.attrs:       # a solve on a GPU
            want["device_transfer_seconds"] = float(g.attrs["device_transfer_seconds"])
        assert case.scalars.attrs == want and want["device"] in ("cpu", "gpu")
    assert case.scalars["nx"] == 32 and case.scalars["ny"] == 16
    assert case.scalars.units["friction_force_pa"] == "Pa"
    assert case.residual == case.scalars["residual"] < case.scalars["tolerance"]


def test_fields_are_indexed_by_x_and_y_in_metres(case):
    fields = case.fields
    assert isinstance(fields, xr.Dataset)
    assert set(fields.data_vars) == {"height_m", "pressure_pa", "displacement_m", "gap_m"}
    assert dict(fields.sizes) == {"x": 32, "y": 16}
    lx, ly = case.scalars["length_x_m"], case.scalars["length_y_m"]
    np.testing.assert_allclose(fields.x.values, np.arange(32) * lx / 32)
    np.testing.assert_allclose(fields.y.values, np.arange(16) * ly / 16)
    assert fields.x.attrs["units"] == "m" and fields.pressure_pa.attrs["units"] == "Pa"
    with h5py.File(case.path, "r") as f:
        p = f["/fields/pressure_pa"][()]             # [iy, ix]
    assert p.shape == (16, 32)
    iy, ix = np.unravel_index(np.argmax(p), p.shape)
    for i, j in [(ix, iy), (3, 11), (30, 2)]:
        sel = fields.pressure_pa.sel(x=fields.x[i], y=fields.y[j]).item()
        assert sel == p[j, i]
        assert fields.pressure_pa.values[i, j] == p[j, i]
    # the gap relation of the README holds on the read arrays: g = w - h + D with the
    # approach max(h) - D, and the mean separation D - mean(h)
    d = float(fields.height_m.max()) - case.scalars["approach_m"]
    g = fields.displacement_m - fields.height_m + d
    np.testing.assert_allclose(case.scalars["mean_separation_m"], d - float(fields.height_m.mean()),
                               rtol=1e-9)
    np.testing.assert_allclose(fields.gap_m, g, atol=1e-9 * float(abs(fields.height_m).max()))


def test_input_is_parsed_with_f90nml_and_provenance_read(case):
    assert isinstance(case.input, f90nml.Namelist)
    assert case.input["grid"]["nx"] == 32 and case.input["surface"]["alpha_deg"] == 30.0
    assert case.input["analysis"]["persson"] is True
    with h5py.File(case.path, "r") as f:
        assert case.input_text == f["/input/namelist"].asstr()[()]
        assert set(case.provenance) == set(f.attrs)
    pv = case.provenance
    for key in ("veslide_version", "git_revision", "compiler", "compiler_options", "hdf5_version", "created",
                "input_file"):
        assert isinstance(pv[key], str) and pv[key], key
    assert type(pv["seed"]) is int and pv["seed"] == 1


def test_optional_groups_with_units(case):
    a = case.anisotropy
    assert a.units["theta_rad"] == "rad" and a["theta_rad"].shape == a["m2_surface"].shape == (72,)
    assert a.attrs["surface_tensor"]["layout"] == "[M11, M21, M12, M22]"
    assert case.patches["orientation_tensor"].shape == (4,)
    assert case.persson.units["q_per_m"] == "1/m"
    assert len(case.persson["q_per_m"]) == len(case.persson["area_fraction"]) > 1
    assert case.summary is None and case.ensemble is None and len(case.cases) == 0 and not case.is_study


def test_study_summary_keeps_integer_columns_and_units(study):
    s = study.summary
    assert isinstance(s, pd.DataFrame) and len(s) == 8 and study.is_study
    for col in ("case", "seed", "iterations", "operator_applications", "converged", "nx", "ny"):
        assert s[col].dtype == np.int64, col
    for col in ("eccentricity", "speed_m_s", "friction_coefficient", "residual"):
        assert s[col].dtype == np.float64, col
    with h5py.File(study.path, "r") as f:
        units = f["/summary"].attrs["units"]
        names = f["/summary"].dtype.names
    assert list(s.columns) == list(names)
    assert s.attrs["units"] == dict(zip(names, [str(u) for u in units]))
    assert s.attrs["units"]["speed_m_s"] == "m/s" and s.attrs["units"]["alpha_deg"] == "degree"
    assert list(s["case"]) == list(range(1, 9))
    # the program names its parameter columns (no temperature without a material shift)
    assert s.attrs["parameters"] == ["case", "seed", "eccentricity", "alpha_deg", "pressure_pa", "speed_m_s"]
    assert study.ensemble.attrs["parameters"] == ["eccentricity", "alpha_deg", "pressure_pa", "speed_m_s"]
    assert study.converged is True
    assert list(study.provenance["seeds"]) == [1, 2] and "seed" not in study.provenance


def test_study_ensemble_is_the_mean_and_sem_over_seeds(study):
    e, s = study.ensemble, study.summary
    assert len(e) == 4 and e["n_seeds"].dtype == np.int64 and (e["n_seeds"] == 2).all()
    assert e.attrs["units"]["mean_friction_coefficient"] == "-"
    keys = ["eccentricity", "alpha_deg", "pressure_pa", "speed_m_s"]
    grouped = s.groupby(keys)
    for col in ("friction_coefficient", "contact_area_fraction"):
        mean = grouped[col].mean().reset_index()
        sem = (grouped[col].std(ddof=1) / np.sqrt(2)).reset_index()
        m = e.merge(mean, on=keys).merge(sem, on=keys, suffixes=("_mean", "_sem"))
        np.testing.assert_allclose(m["mean_" + col], m[col + "_mean"], rtol=1e-12)
        np.testing.assert_allclose(m["sem_" + col], m[col + "_sem"], rtol=1e-9, atol=1e-15)


def test_cases_are_read_lazily_and_match_the_summary(study):
    fresh = veslide.read(study.path)
    cases = fresh.cases
    assert isinstance(cases, Mapping) and list(cases) == list(range(1, 9))
    assert cases._cache == {}                      # nothing read until asked for
    c3 = cases[3]
    assert list(cases._cache) == [3]
    row = fresh.summary.set_index("case").loc[3]
    assert c3.parameters == {"case": 3, "seed": int(row["seed"]), "eccentricity": row["eccentricity"],
                             "alpha_deg": row["alpha_deg"], "pressure_pa": row["pressure_pa"],
                             "speed_m_s": row["speed_m_s"]}
    for name, value in c3.scalars.items():
        if name in row.index:
            assert row[name] == value, name
    assert c3.fields is None                       # &output fields = .false.
    assert c3.provenance is fresh.provenance and c3.input["sweep"]["n_seeds"] == 2
    assert not c3.is_study
    with pytest.raises(KeyError):
        cases[99]


def test_missing_file_names_the_running_reader(tmp_path):
    (tmp_path / "s.h5.part").write_bytes(b"")
    with pytest.raises(FileNotFoundError, match="read_running"):
        veslide.read(tmp_path / "s.h5")


def test_seed_statistics_is_the_programs_ensemble(exe, tmp_path):
    """veslide.results.seed_statistics (the one Python copy of the rule, used by plot.seed_means
    and postproc) gives /ensemble's mean and standard error of every scalar, the axes averaged
    as axial data, from the /summary rows of each combination of parameters."""
    from conftest import params
    from veslide.results import AXIAL, parameter_columns, seed_statistics
    p = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8, "eccentricity": 0.4}, material={"model": "one_term"},
               motion={"speed_m_s": 0.05}, output={"fields": False},
               analysis={"anisotropy": True, "zeta2": 8, "patches": True},
               sweep={"alphas_deg": [0.0, 90.0], "n_seeds": 3})
    r = veslide.run(p, output=tmp_path / "s.h5", exe=exe, progress=None)
    keys = [k for k in parameter_columns(r.summary) if k not in ("case", "seed")]
    ens = r.ensemble.set_index(keys)
    checked = set()
    for group, part in r.summary.groupby(keys):
        row = ens.loc[group]
        for name in r.summary.columns:
            if "mean_" + name not in ens.columns or name in keys:
                continue
            mean, sem, _, _ = seed_statistics(part[name].to_numpy(float), name)
            assert np.isclose(mean, row["mean_" + name], rtol=1e-13, atol=1e-300), name
            assert np.isclose(sem, row["sem_" + name], rtol=1e-12, atol=1e-300), name
            checked.add(name)
    assert set(AXIAL) <= checked                  # the axes were among them
