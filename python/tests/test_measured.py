"""Measured topographies: instrument files written here in their documented layouts, read through
SurfaceTopography, prepared, written and read back with h5py; the solver on a prepared file."""
import json
import subprocess
import sys
import warnings
import zipfile
from pathlib import Path

import h5py
import numpy as np
import pytest

import veslide
from veslide.topography import prepare, read, Scan
from conftest import params

pytest.importorskip("SurfaceTopography")

NX, NY = 24, 16                      # a rectangle: x and y cannot be confused
MARK = (5, 12)                       # [ix, iy] of the raised point, away from the taper


def marker_heights():
    """heights [ix, iy] [m]: a ramp along x only (1 um over the scan) and one raised point."""
    h = np.repeat((1e-6 * np.arange(NX) / NX)[:, None], NY, axis=1)
    h[MARK] += 5e-6
    return h


def write_x3p(path, matrix, dx, dy):
    """An ISO 5436-2 (X3P) file written from the standard's layout, not by SurfaceTopography:
    main.xml with the axes (CX, CY incremental, CZ absolute, metres) and the matrix dimension, and
    bindata/data.bin, float64 little-endian with x running fastest -- the matrix [iy, ix] (one
    row per scan line along x) in C order."""
    ny, nx = matrix.shape
    xml = f"""<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>SUR</FeatureType>
    <Axes>
      <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx!r}</Increment><Offset>0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy!r}</Increment><Offset>0</Offset></CY>
      <CZ><AxisType>A</AxisType><DataType>D</DataType></CZ>
    </Axes>
  </Record1>
  <Record2>
    <Date>2026-01-01T00:00:00</Date>
    <Instrument><Manufacturer>veslide tests</Manufacturer><Model>hand-written</Model>
      <Serial>not available</Serial><Version>1</Version></Instrument>
  </Record2>
  <Record3>
    <MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
    <DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink>
  </Record3>
</p:ISO5436_2>
"""
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("main.xml", xml)
        z.writestr("bindata/data.bin", np.ascontiguousarray(matrix, dtype="<f8").tobytes())
    return path


def write_asc(path, matrix, width_um, height_um):
    """A Gwyddion plain-text export: '# Width', '# Height' (um), '# Value units: m', then one line
    per scan line along x (the matrix [iy, ix] as written)."""
    lines = ["# Channel: Height", "# Width: %r um" % width_um, "# Height: %r um" % height_um,
             "# Value units: m"]
    lines += [" ".join(repr(float(v)) for v in row) for row in matrix]
    Path(path).write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("fmt", ["x3p", "asc"])
def test_asymmetric_marker_round_trips_through_an_instrument_file(tmp_path, fmt):
    h = marker_heights()
    lx, ly = 48e-6, 32e-6                                   # square points of 2 um
    if fmt == "x3p":
        f = write_x3p(tmp_path / "scan.x3p", h.T, lx / NX, ly / NY)
    else:
        f = write_asc(tmp_path / "scan.txt", h.T, 48.0, 32.0)
    scan = read(f)
    assert scan.source["format"] == fmt
    assert (scan.nx, scan.ny) == (NX, NY)
    assert scan.length_x_m == pytest.approx(lx, rel=1e-12) and scan.length_y_m == pytest.approx(ly, rel=1e-12)
    np.testing.assert_allclose(scan.heights, h, rtol=1e-14, atol=0)      # [ix, iy], in metres
    np.testing.assert_array_equal(scan.matrix, scan.heights.T)            # [iy, ix] as it was stored
    assert np.unravel_index(np.argmax(scan.heights - h[:, :1]), h.shape) == MARK
    s = prepare(scan, detrend="plane", periodic="tukey", taper=0.1, k_cut=10)
    assert s.heights.shape == (NX, NY)
    assert np.unravel_index(np.argmax(s.heights), s.heights.shape) == MARK
    assert s.preparation["source"]["format"] == fmt
    out = s.write(tmp_path / "surf.h5")
    with h5py.File(out, "r") as f5:
        ds = f5["/height_m"]
        assert ds.shape == (NY, NX)                                        # Fortran (nx, ny) on disk
        assert np.unravel_index(np.argmax(ds[()]), ds.shape) == MARK[::-1]  # h5py [iy, ix]
        np.testing.assert_array_equal(ds[()].T, s.heights)
        assert ds.attrs["length_x_m"] == s.length_x_m == pytest.approx(lx)
        assert ds.attrs["length_y_m"] == s.length_y_m == pytest.approx(ly)
        assert ds.attrs["length_m"] == ds.attrs["length_x_m"] and ds.attrs["units"] == "m"
        prep = json.loads(ds.attrs["preparation"])
    assert prep["source"]["path"] == str(Path(f).resolve()) and len(prep["source"]["sha256"]) == 64
    assert prep["detrend"]["mode"] == "plane" and prep["periodic"]["method"] == "tukey"
    assert prep["periodic"]["taper"] == 0.1 and prep["band"]["k_cut"] == 10.0
    assert prep["band"]["resample"]["to"] == [NX, NY]
    back = veslide.load_topography(out)
    np.testing.assert_array_equal(back.heights, s.heights)
    assert back.preparation == prep and (back.length_x_m, back.length_y_m) == (s.length_x_m, s.length_y_m)


def test_units_come_from_the_file(tmp_path):
    """the x3p is in metres by its standard; the text file says um for the sides and m for the
    values: both give the same scan in metres, and the record says the factor."""
    h = marker_heights()
    f = write_asc(tmp_path / "scan.txt", h.T * 1e6, 48.0, 32.0)
    text = f.read_text().replace("# Value units: m", "# Value units: um")
    f.write_text(text)
    scan = read(f)
    assert scan.source["unit"] == "um" and scan.source["factor_to_m"] == pytest.approx(1e-6)
    np.testing.assert_allclose(scan.heights, h, rtol=1e-12)
    assert scan.length_x_m == pytest.approx(48e-6)
    s = prepare(scan, k_cut=4)
    assert s.preparation["units"] == {"from": "um", "factor_to_m": pytest.approx(1e-6),
                                      "by": "SurfaceTopography to_unit('m')"}


def test_undefined_points_are_filled_and_counted(tmp_path):
    h = rough(30, 20)
    m = h.T.copy()
    m[7, 11] = m[8, 11] = np.nan                                   # [iy, ix]: two points the instrument missed
    scan = read(write_x3p(tmp_path / "holes.x3p", m, 1e-6, 1e-6))
    assert scan.topography.has_undefined_data
    s = prepare(scan, k_cut=4)
    assert s.preparation["undefined_points"]["count"] == 2
    assert s.preparation["undefined_points"]["fraction"] == pytest.approx(2 / 600)
    assert np.all(np.isfinite(s.heights)) and np.all(np.isfinite(s.detrended))
    with pytest.raises(ValueError, match="2 undefined points"):
        prepare(scan, k_cut=4, fill=None)


def rough(nx=50, ny=40, seed=3):
    """a smooth random non-periodic scan [ix, iy] (a few long waves, random phases, off-grid)"""
    rng = np.random.default_rng(seed)
    x, y = np.meshgrid(np.arange(nx) / nx, np.arange(ny) / ny, indexing="ij")
    h = np.zeros((nx, ny))
    for _ in range(12):
        kx, ky = rng.uniform(-4.5, 4.5, 2)
        h += rng.standard_normal() * np.cos(2 * np.pi * (kx * x + ky * y) + rng.uniform(0, 2 * np.pi))
    return 1e-7 * h


def test_detrending_removes_a_plane_or_a_curvature_exactly():
    nx, ny = 50, 40
    s0 = rough(nx, ny)
    x, y = np.meshgrid(np.arange(nx) / nx, np.arange(ny) / ny, indexing="ij")
    plane = 3e-6 + 2e-6 * x - 5e-6 * y
    quad = plane + 4e-6 * x ** 2 - 1e-6 * y ** 2 + 3e-6 * x * y
    base = {m: prepare(Scan.from_heights(s0, 1e-4), detrend=m, k_cut=5).detrended for m in ("plane", "curvature")}
    for mode, added in (("plane", plane), ("curvature", plane), ("curvature", quad)):
        d = prepare(Scan.from_heights(s0 + added, 1e-4), detrend=mode, k_cut=5).detrended
        np.testing.assert_allclose(d, base[mode], rtol=0, atol=1e-12 * np.abs(added).max())
    # a plane fit leaves the curvature (the test has teeth)
    d = prepare(Scan.from_heights(s0 + quad, 1e-4), detrend="plane", k_cut=5).detrended
    assert np.abs(d - base["plane"]).max() > 1e-8
    # 'none' removes the mean only
    d = prepare(Scan.from_heights(s0 + plane, 1e-4), detrend="none", k_cut=5).detrended
    np.testing.assert_allclose(d, s0 + plane - (s0 + plane).mean(), rtol=0, atol=1e-20)


@pytest.mark.parametrize("taper", [0.1, 0.25])
def test_tukey_area_fraction_is_its_window(taper):
    nx, ny = 50, 40
    h = rough(nx, ny)
    s = prepare(Scan.from_heights(h, 1e-4, 0.8e-4), periodic="tukey", taper=taper, k_cut=5)
    changed = np.mean(s.periodised != s.detrended)                  # the cells the window touched
    assert s.costs["area_fraction_changed"] == pytest.approx(changed, abs=1e-15)
    fx, fy = s.preparation["periodic"]["tapered_fraction_x"], s.preparation["periodic"]["tapered_fraction_y"]
    assert abs(fx - taper) <= 1.5 / nx and abs(fy - taper) <= 1.5 / ny   # taper/2 of each side, +1 point
    assert changed == pytest.approx(1 - (1 - fx) * (1 - fy), abs=1e-15)
    assert changed == pytest.approx(1 - (1 - taper) ** 2, abs=2 * (1.5 / nx + 1.5 / ny))
    # the edges close: the jumps across them fall to a fraction (a taper of 2.5 points per edge
    # on 50 still steps by w[1] = 0.35 of the edge height)
    c = s.costs
    for a in "xy":
        assert c["edge_jump_%s_before" % a] > 3 * c["edge_step_%s_before" % a]
        assert c["edge_jump_%s_after" % a] < 0.4 * c["edge_jump_%s_before" % a]
    assert -1 < c["slope_variance_change"] < 0.5


def test_band_filter_keeps_nothing_above_k_cut_and_aliases_nothing():
    """a periodic scan with waves at k = 3 (kept), k = 11 (above k_cut = 8) and k = 20 (above the
    32-point grid's Nyquist: decimating would alias it to k = 12); the prepared surface on 32 x 16
    points is the k = 3 wave alone, exactly."""
    n = 128
    lx, ly = 1e-4, 0.5e-4
    x, y = np.meshgrid(np.arange(n) * lx / n, np.arange(n // 2) * ly / (n // 2), indexing="ij")
    keep = 1e-6 * np.cos(2 * np.pi * (3 * x / lx + 2 * y / ly) + 0.3)
    h = keep + 0.5e-6 * np.cos(2 * np.pi * 11 * x / lx) + 0.7e-6 * np.sin(2 * np.pi * 20 * x / lx)
    s = prepare(Scan.from_heights(h, lx, ly, periodic=True), nx=32, ny=16, detrend="none", periodic="none",
                k_cut=8)
    xs, ys = np.meshgrid(np.arange(32) * lx / 32, np.arange(16) * ly / 16, indexing="ij")
    np.testing.assert_allclose(s.heights, 1e-6 * np.cos(2 * np.pi * (3 * xs / lx + 2 * ys / ly) + 0.3),
                               rtol=0, atol=1e-18)
    assert s.costs["band_height_variance_removed"] == pytest.approx(1 - 1 / (1 + 0.25 + 0.49), rel=1e-12)
    # a rough scan, up- and down-sampled: no power above k_cut q0 in the prepared spectrum
    r = rough(50, 40) + 1e-8 * np.random.default_rng(0).standard_normal((50, 40))
    for nx in (32, 50, 96):
        s = prepare(Scan.from_heights(r, 1e-4, 0.8e-4), nx=nx, k_cut=7)
        qx, qy, c = veslide.psd_2d(s.heights, s.length_x_m, s.length_y_m)
        q = np.hypot(*np.meshgrid(qx, qy, indexing="ij"))
        above = q > 7 * 2 * np.pi / s.length_x_m * (1 + 1e-9)
        assert above.any() and c[above].max() <= 1e-24 * c.max()
        assert s.heights.shape == (nx, round(nx * 0.8))
    with pytest.raises(ValueError, match="Nyquist"):
        prepare(Scan.from_heights(r, 1e-4, 0.8e-4), nx=32, k_cut=16)


def test_mirror_and_crop_report_their_costs():
    h = rough(50, 40)
    scan = Scan.from_heights(h, 1e-4, 0.8e-4)
    m = prepare(scan, periodic="mirror", k_cut=10)
    assert (m.length_x_m, m.length_y_m) == pytest.approx((2e-4, 1.6e-4))
    assert m.periodised.shape == (100, 80) and m.heights.shape == (100, 80)
    np.testing.assert_allclose(m.periodised[:50, :40], m.detrended, atol=1e-22)
    np.testing.assert_array_equal(m.periodised[50:, :40], m.periodised[49::-1, :40])   # the image in x
    assert m.costs["area_fraction_changed"] == 0.75 and m.costs["area_fraction_dropped"] == 0
    assert m.costs["edge_jump_x_after"] == 0 and m.costs["edge_jump_y_after"] == 0
    # a periodic surface of 40 x 32 points scanned over 46 x 37: the crop finds its period
    per = rough(40, 32)
    scan = np.tile(per, (2, 2))[3:49, 5:42]
    c = prepare(Scan.from_heights(scan, 46e-6, 37e-6, periodic=False), detrend="none", periodic="crop",
                taper=0.2, k_cut=6)
    assert c.preparation["periodic"]["points"] == [40, 32]
    assert (c.length_x_m, c.length_y_m) == pytest.approx((40e-6, 32e-6))
    assert c.costs["area_fraction_dropped"] == pytest.approx(1 - 40 * 32 / (46 * 37))
    assert c.costs["edge_jump_x_after"] == pytest.approx(c.costs["edge_step_x_after"], rel=0.5)


def test_costs_are_reported_and_written(tmp_path):
    f = write_x3p(tmp_path / "scan.x3p", rough(50, 40).T, 2e-6, 2e-6)
    out = tmp_path / "surf.h5"
    p = subprocess.run([sys.executable, "-m", "veslide", "topography", str(f), "--out", str(out), "--nx", "32",
                        "--ny", "32", "--detrend", "plane", "--periodic", "tukey", "--taper", "0.2", "--k-cut", "8"],
                       capture_output=True, text=True, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert [ln.split(":")[0] for ln in lines] == ["read", "units", "undefined", "detrend", "periodic", "band",
                                                 "resample", "surface", "written", "use"]
    prep = veslide.load_topography(out).preparation
    keys = ["area_fraction_changed", "area_fraction_dropped", "slope_variance_change", "edge_jump_x_before",
            "edge_jump_x_after", "edge_jump_y_before", "edge_jump_y_after", "band_height_variance_removed",
            "band_slope_variance_removed"]
    for k in keys:
        assert np.isfinite(prep["costs"][k])
    periodic_line = next(ln for ln in lines if ln.startswith("periodic:"))
    assert "area changed %.4f" % prep["costs"]["area_fraction_changed"] in periodic_line
    assert "edge jump x %.3g -> %.3g" % (prep["costs"]["edge_jump_x_before"],
                                         prep["costs"]["edge_jump_x_after"]) in periodic_line
    assert "nx = 32, ny = 32" in lines[-1]
    # bad input: exit status 1, one line, no file
    p = subprocess.run([sys.executable, "-m", "veslide", "topography", str(f), "--out", str(tmp_path / "bad.h5"),
                        "--nx", "32", "--k-cut", "20"], capture_output=True, text=True, cwd=tmp_path)
    assert p.returncode == 1 and "Nyquist" in p.stderr and not (tmp_path / "bad.h5").exists()


def test_a_text_matrix_without_sizes_needs_them(tmp_path):
    f = tmp_path / "plain.txt"
    np.savetxt(f, rough(20, 12).T * 1e6)                             # rows along x, no header
    with pytest.raises(ValueError, match="physical_sizes"):
        read(f)
    with pytest.raises(ValueError, match="no length unit: pass unit="):
        read(f, physical_sizes=(40, 24))
    scan = read(f, unit="um", physical_sizes=(40, 24))
    assert (scan.nx, scan.ny) == (20, 12) and scan.length_x_m == pytest.approx(40e-6)
    np.testing.assert_allclose(scan.heights, rough(20, 12), rtol=1e-12)


def _solve(tmp_path, exe, scan_points, nx, ny, name):
    f = write_x3p(tmp_path / ("%s.x3p" % name), rough(*scan_points).T, 2e-6, 2e-6)
    s = prepare(read(f), nx=nx, ny=ny, k_cut=6)
    path = s.write(tmp_path / ("%s.h5" % name))
    p = params(surface={"kind": "file", "file": str(path)}, load={"mean_pressure_pa": 1e5})
    r = veslide.run(p, output=tmp_path / ("%s-solve.h5" % name), exe=exe, progress=None)
    assert r.converged and (r.scalars["nx"], r.scalars["ny"]) == (nx, ny)
    assert r.scalars["length_x_m"] == pytest.approx(s.length_x_m, rel=1e-12)
    assert r.scalars["length_y_m"] == pytest.approx(s.length_y_m, rel=1e-12)
    np.testing.assert_array_equal(r.fields.height_m.transpose("x", "y").values, s.heights)
    return r


def test_solver_runs_a_prepared_square_scan(tmp_path, exe):
    _solve(tmp_path, exe, (60, 60), 32, 32, "square")


def test_solver_runs_a_prepared_rectangular_scan(tmp_path, exe):
    _solve(tmp_path, exe, (60, 45), 32, 24, "rect")


ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "measured.md"


def _readme_section(title="## From a scan to a run"):
    """docs/measured.md's walk-through (the README's quick start 2 is a part of it)"""
    text = PAGE.read_text()
    start = text.index("\n" + title + "\n")
    end = text.index("\n## ", start + len(title) + 2)
    return text[start:end]


def _blocks(section, lang):
    import re
    return [m.group(1) for m in re.finditer(r"^```%s\n(.*?)^```$" % lang, section, re.M | re.S)]


def test_readme_quick_start_is_the_walk_through():
    """The README's quick start 2 runs the walk-through's commands (which the next test runs)."""
    readme = (ROOT / "README.md").read_text()
    qs = readme[readme.index("## Quick start 2"):readme.index("## Quick start 3")]
    sh, = _blocks(qs, "sh")
    walk = "\n".join(_blocks(_readme_section(), "sh"))
    for line in sh.splitlines():
        assert line in walk, line


def test_readme_measured_scan_example_runs_as_written(tmp_path, exe, monkeypatch):
    """the walk-through's shell commands (the venv's python and ./dev.sh run replaced by this
    interpreter and the program under test) print what it shows, warn of nothing, and its
    Python block runs."""
    import os
    import re
    sec = _readme_section()
    sh = _blocks(sec, "sh")
    text, = _blocks(sec, "text")
    py, = _blocks(sec, "python")
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]), OMP_NUM_THREADS="1")
    script = sh[0].replace(".venv/bin/python", sys.executable)
    p = subprocess.run(["bash", "-e", "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    got = p.stdout.splitlines()
    want = text.splitlines()
    assert len(got) == len(want)
    for w, g in zip(want, got):
        if "..." in w:
            head, tail = w.split("...")
            assert g.startswith(head) and g.endswith(tail), (w, g)
        else:
            assert g == w
    run = sh[1].replace("./dev.sh run", str(exe))
    p = subprocess.run(["bash", "-e", "-c", run], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "warning" not in p.stderr, p.stderr
    area, mu = (float(v) for v in re.search(r"contact area ([0-9.]+), friction coefficient ([0-9.]+)", sh[1]).groups())
    r = veslide.read(tmp_path / "measured.h5")
    assert r.converged
    assert r.scalars["contact_area_fraction"] == pytest.approx(area, abs=5e-5)
    assert r.scalars["friction_coefficient"] == pytest.approx(mu, abs=5e-5)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("VESLIDE_EXE", str(exe))
    (tmp_path / "surf.h5").unlink()
    ns = {}
    exec(compile(py, "docs/measured.md", "exec"), ns)
    assert ns["r"].converged
    assert ns["r"].scalars["friction_coefficient"] == r.scalars["friction_coefficient"]
    assert ns["scan"].heights[3, 7] == ns["scan"].matrix[7, 3]


# --- unmeasured points: filled up to 2 %, else refused unless cropped or filled on request ---------

def _cli(tmp_path, *args):
    return subprocess.run([sys.executable, "-m", "veslide", "topography", *map(str, args)],
                          capture_output=True, text=True, cwd=tmp_path)


def holes(n_strip_x, extra=0):
    """rough(50, 40) [ix, iy] with the points ix < n_strip_x, iy >= 30 undefined (a strip of
    10 n_strip_x points at one corner) and `extra` (<= n_strip_x) more along iy = 0 from ix = 0:
    the largest measured rectangle is ix >= n_strip_x, all iy."""
    h = rough(50, 40)
    h[:n_strip_x, 30:] = np.nan
    h[:extra, 0] = np.nan
    return h


def test_largest_measured_rectangle_is_the_brute_force_one():
    from veslide.measured import largest_measured_rectangle
    rng = np.random.default_rng(5)
    for trial in range(400):
        nx, ny = rng.integers(1, 9, 2)
        valid = rng.random((nx, ny)) < rng.uniform(0.2, 1.0)
        best = 0
        for i0 in range(nx):
            for i1 in range(i0 + 1, nx + 1):
                for j0 in range(ny):
                    for j1 in range(j0 + 1, ny + 1):
                        if valid[i0:i1, j0:j1].all():
                            best = max(best, (i1 - i0) * (j1 - j0))
        (i0, j0), (mx, my) = largest_measured_rectangle(valid)
        assert mx * my == best, (valid, best)
        assert valid[i0:i0 + mx, j0:j0 + my].all() and i0 + mx <= nx and j0 + my <= ny
    assert largest_measured_rectangle(np.zeros((3, 4), bool)) == ((0, 0), (0, 0))
    assert largest_measured_rectangle(np.ones((3, 4), bool)) == ((0, 0), (3, 4))
    assert largest_measured_rectangle(np.array([1, 1, 0, 1, 1, 1, 0], bool)) == ((3, 0), (3, 1))   # a line


def test_up_to_two_percent_undefined_is_filled_and_recorded(tmp_path):
    scan = read(write_x3p(tmp_path / "s.x3p", holes(4).T, 1e-6, 1e-6))       # 40 of 2000 points: 2 %
    with warnings.catch_warnings():
        warnings.simplefilter("error", veslide.VeslideWarning)
        s = prepare(scan, k_cut=6)
    u = s.preparation["undefined_points"]
    assert u["count"] == 40 and u["fraction"] == 0.02 and u["filled_fraction"] == 0.02
    assert u["fill"] == "auto" and u["filled_by"].startswith("SurfaceTopography interpolate_undefined_data")
    assert u["crop_valid"] is False and u["measured_rectangle"] is None
    assert s.heights.shape == (50, 40) and np.all(np.isfinite(s.heights)) and s.preparation["warnings"] == []


def test_more_than_two_percent_undefined_is_refused_naming_both_ways(tmp_path):
    f = write_x3p(tmp_path / "s.x3p", holes(4, extra=1).T, 1e-6, 1e-6)     # 41 of 2000 points: 2.05 %
    scan = read(f)
    with pytest.raises(ValueError) as e:
        prepare(scan, k_cut=6)
    msg = str(e.value)
    assert "\n" not in msg
    assert msg == ("%s: 2.05 %% of its 50 x 40 points are unmeasured: crop_valid=True (--crop-valid) keeps the "
                   "largest measured rectangle (46 x 40 points, 92 %% of the scan), or fill='harmonic' "
                   "(--fill harmonic) fills them (the filled heights are invented)" % f.resolve())
    with pytest.raises(ValueError, match="41 undefined points"):
        prepare(scan, k_cut=6, fill=None)
    out = tmp_path / "surf.h5"
    p = _cli(tmp_path, f, "--out", out, "--k-cut", 6)
    assert p.returncode == 1 and not out.exists() and p.stdout == ""
    err, = p.stderr.splitlines()
    assert "--crop-valid keeps the largest measured rectangle (46 x 40 points" in err and "--fill harmonic" in err


def test_an_explicit_fill_above_two_percent_warns(tmp_path):
    f = write_x3p(tmp_path / "s.x3p", holes(4, extra=1).T, 1e-6, 1e-6)
    with pytest.warns(veslide.VeslideWarning) as got:
        s = prepare(read(f), k_cut=6, fill="harmonic")
    w, = [w.message for w in got]
    assert (w.code, w.value, w.threshold, w.source) == ("filled-scan", 0.0205, 0.02, "preparation")
    assert "2.05 % of its 50 x 40 points were unmeasured" in w.text and "invented" in w.text
    assert s.preparation["undefined_points"]["filled_fraction"] == 0.0205
    assert s.preparation["warnings"] == [{"code": "filled-scan", "value": 0.0205, "threshold": 0.02, "text": w.text}]
    with warnings.catch_warnings():                      # 2 %, asked for: no warning
        warnings.simplefilter("error", veslide.VeslideWarning)
        prepare(read(write_x3p(tmp_path / "t.x3p", holes(4).T, 1e-6, 1e-6)), k_cut=6, fill="harmonic")
    out = tmp_path / "surf.h5"
    p = _cli(tmp_path, f, "--out", out, "--k-cut", 6, "--fill", "harmonic")
    assert p.returncode == 0, p.stderr
    err, = p.stderr.splitlines()                         # the options in the command line's words
    assert err == "warning: [filled-scan] %s" % w.text.replace("crop_valid=True (--crop-valid)", "--crop-valid")
    assert veslide.load_topography(out).preparation["undefined_points"]["filled_fraction"] == 0.0205


def test_crop_valid_keeps_the_largest_measured_rectangle(tmp_path):
    h = holes(4, extra=1)                                 # largest measured: ix 4..49, iy 0..39
    f = write_x3p(tmp_path / "s.x3p", h.T, 1e-6, 2e-6)
    with warnings.catch_warnings():
        warnings.simplefilter("error", veslide.VeslideWarning)
        s = prepare(read(f), detrend="none", periodic="none", k_cut=6, crop_valid=True)
    u = s.preparation["undefined_points"]
    assert u["measured_rectangle"] == {"start": [4, 0], "points": [46, 40], "fraction_kept": 0.92,
                                       "scan_points": [50, 40]}
    assert u["count"] == 41 and u["filled_fraction"] == 0 and u["filled_by"] is None and u["crop_valid"] is True
    np.testing.assert_allclose(s.detrended, h[4:] - h[4:].mean(), rtol=0, atol=1e-20)   # before the detrending
    assert (s.length_x_m, s.length_y_m) == pytest.approx((46e-6, 80e-6)) and s.heights.shape == (46, 40)
    assert "cropped to the largest measured rectangle, 46 x 40 points from [4, 0] (0.92 of the scan)" in s.lines[2]
    # nothing to crop: the scan whole, recorded
    s = prepare(Scan.from_heights(rough(50, 40), 1e-4), k_cut=6, crop_valid=True)
    assert s.preparation["undefined_points"]["measured_rectangle"]["points"] == [50, 40]
    out = tmp_path / "surf.h5"
    p = _cli(tmp_path, f, "--out", out, "--k-cut", 6, "--crop-valid")
    assert p.returncode == 0 and p.stderr == "", p.stderr
    assert veslide.load_topography(out).heights.shape == (46, 40)


# --- the band: a warning when it removes more than half of the cell's slope variance -------------

def two_waves(removed):
    """a periodic 128 x 64 scan over 100 x 50 um: waves along x at k = 3 and k = 11 whose slope
    variances make the k = 11 one the fraction `removed` of the whole."""
    lx, ly = 1e-4, 0.5e-4
    x = np.arange(128)[:, None] * lx / 128 + np.zeros((1, 64))
    b = np.sqrt(9 * removed / (1 - removed) / 121)        # 121 b^2 / (9 + 121 b^2) = removed
    return 1e-7 * (np.cos(2 * np.pi * 3 * x / lx + 0.2) + b * np.cos(2 * np.pi * 11 * x / lx + 0.5)), lx, ly


@pytest.mark.parametrize("removed", [0.6, 0.4])
def test_band_removing_more_than_half_the_slope_variance_warns(removed, tmp_path):
    h, lx, ly = two_waves(removed)
    scan = Scan.from_heights(h, lx, ly, periodic=True)
    kw = dict(nx=32, detrend="none", periodic="none", k_cut=8)
    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always")
        s = prepare(scan, **kw)
    assert s.costs["band_slope_variance_removed"] == pytest.approx(removed, rel=1e-9)
    if removed < 0.5:
        assert got == [] and s.preparation["band"]["half_slope"] is None and s.warnings == []
        return
    w, = [g.message for g in got]
    assert isinstance(w, veslide.VeslideWarning)
    assert (w.code, w.value, w.threshold) == ("band-slope-removed", s.costs["band_slope_variance_removed"], 0.5)
    # half the slope variance lies at k >= 11: a 48-point grid (its Nyquist 24, default k_cut 12) keeps it
    assert w.text == ("the scan: the band (k_cut 8 q0 on 32 x 16 points) removes 0.6 of the cell's slope variance, "
                      "which the solve then lacks: nx=48 (--nx 48) with its default k_cut 12 (half its Nyquist) "
                      "keeps at least half, as does k_cut=11 (--k-cut 11) on this grid")
    assert s.preparation["band"]["half_slope"] == {"k_cut": 11.0, "grid": [48, 24], "kept_max": pytest.approx(1.0)}
    assert s.warnings == [{"code": "band-slope-removed", "value": w.value, "threshold": 0.5, "text": w.text}]
    with warnings.catch_warnings():                      # what it says keeps half
        warnings.simplefilter("error", veslide.VeslideWarning)
        assert prepare(scan, **dict(kw, nx=48, k_cut=None)).costs["band_slope_variance_removed"] < 0.5
        assert prepare(scan, **dict(kw, k_cut=11)).costs["band_slope_variance_removed"] < 0.5
    f = write_x3p(tmp_path / "s.x3p", h.T, lx / 128, ly / 64)
    out = tmp_path / "surf.h5"
    p = _cli(tmp_path, f, "--out", out, "--nx", 32, "--detrend", "none", "--periodic", "none", "--k-cut", 8)
    assert p.returncode == 0 and out.exists()
    err, = p.stderr.splitlines()
    assert err.startswith("warning: [band-slope-removed] %s: the band (k_cut 8 q0 on 32 x 16 points)" % f.resolve())
    assert err.endswith(": --nx 48 with its default k_cut 12 (half its Nyquist) keeps at least half, as does "
                        "--k-cut 11 on this grid")


def test_band_warning_says_when_the_scan_cannot_keep_half():
    """the slopes at the scan's own Nyquist (a row-to-row alternation, as noise gives): no band keeps them"""
    h, lx, ly = two_waves(0.1)
    h = h + 1e-7 * (-1.0) ** np.arange(128)[:, None]
    with pytest.warns(veslide.VeslideWarning, match="band-slope-removed") as got:
        s = prepare(Scan.from_heights(h, lx, ly, periodic=True), detrend="none", periodic="none")
    w = got[0].message
    assert w.value == s.costs["band_slope_variance_removed"] > 0.99
    assert w.text.endswith("the scan's own points cannot keep half of it (every mode below its Nyquist 64 keeps "
                           "%.3g)" % s.preparation["band"]["half_slope"]["kept_max"])
    assert s.preparation["band"]["half_slope"]["grid"] is None


# --- absurd heights: an rms slope above 10 is refused --------------------------------------------

def wave(rms_slope, n=64, lx=1e-4, k=3):
    """a periodic n x n scan over lx x lx: one wave along x of the given rms slope"""
    x = np.arange(n)[:, None] * lx / n + np.zeros((1, n))
    amp = rms_slope * np.sqrt(2) * lx / (2 * np.pi * k)
    return amp * np.cos(2 * np.pi * k * x / lx)


@pytest.mark.parametrize("rms_slope", [11.0, 9.0])
def test_an_rms_slope_above_ten_is_refused(rms_slope):
    scan = Scan.from_heights(wave(rms_slope), 1e-4, periodic=True)
    kw = dict(detrend="none", periodic="none", k_cut=8)
    if rms_slope < 10:
        assert prepare(scan, **kw).preparation["result"]["rms_slope"] == pytest.approx(rms_slope, rel=1e-9)
        return
    with pytest.raises(ValueError) as e:
        prepare(scan, **kw)
    assert str(e.value) == ("the scan: the rms slope of the heights is 11 (a contact of small slopes needs well below "
                            "1): heights in another unit (unit= (--unit), or height_scale_factor= (--height-scale) "
                            "for the heights alone), or an array that is not heights")


def test_heights_in_the_wrong_unit_are_refused_naming_the_options(tmp_path):
    """a text export that says its heights are metres but holds micrometres: slopes of 1e5"""
    f = write_asc(tmp_path / "scan.txt", rough(50, 40).T * 1e6, 100.0, 80.0)
    out = tmp_path / "surf.h5"
    p = _cli(tmp_path, f, "--out", out, "--k-cut", 8)
    assert p.returncode == 1 and not out.exists() and p.stdout == ""
    err, = p.stderr.splitlines()
    assert err.startswith("veslide topography: %s: the rms slope of the heights is " % f.resolve())
    assert err.endswith("e4 (a contact of small slopes needs well below 1): heights in another unit (--height-scale "
                        "rescales them, the file giving its unit m), or a channel that is not heights (--channel; "
                        "channels: Height)")
    p = _cli(tmp_path, f, "--out", out, "--k-cut", 8, "--height-scale", 1e-6)
    assert p.returncode == 0, p.stderr
    assert veslide.load_topography(out).preparation["result"]["rms_slope"] < 1


# --- the readers' refusals name the options ------------------------------------------------------

def test_reader_refusals_are_one_line_naming_the_options(tmp_path):
    plain = tmp_path / "plain.txt"
    np.savetxt(plain, rough(20, 12).T * 1e6)
    x3p = write_x3p(tmp_path / "scan.x3p", rough(20, 12).T, 1e-6, 1e-6)
    junk = tmp_path / "junk.dat"
    junk.write_bytes(b"\x00\x01not a scan" * 20)
    cases = [
        ((plain,), "the file gives neither its size nor its length unit: pass --size LX LY and --unit um, or what "
                   "they are (channels: Default): "),
        ((plain, "--size", 40, 24), "the file gives no length unit: pass --unit um, or what it is (channels: Default)"),
        ((plain, "--unit", "um"),
         "the file gives no physical size: pass --size LX LY, in its unit (channels: Default)"),
        ((plain, "--unit", "um", "--size", 40), "channel Default is a 2-D topography: --size LX LY, got 1 numbers"),
        ((x3p, "--channel", "Phase"), "no channel 'Phase': --channel takes a name or an index (channels: Default)"),
        ((x3p, "--channel", 2), "no channel 2: --channel takes a name or an index 0 to 0 (channels: Default)"),
        ((x3p, "--unit", "um"), "the file gives its unit itself: leave out --unit (channels: Default): Value for "
                                "keyword 'unit' is already fixed by file contents"),
        ((x3p, "--format", "sdf"), "SurfaceTopography cannot read it as 'sdf': --format names another: "),
        ((x3p, "--format", "nope"), "SurfaceTopography has no format 'nope': --format takes one of sdf, "),
        ((junk,), "SurfaceTopography cannot tell its format from its content (no reader takes it): --format names "
                  "it, one of "),
    ]
    out = tmp_path / "surf.h5"
    for args, want in cases:
        p = _cli(tmp_path, *args, "--out", out)
        assert p.returncode == 1 and not out.exists() and p.stdout == "", (args, p.stderr)
        assert len(p.stderr.splitlines()) == 1, p.stderr
        err = p.stderr.strip()
        assert err.startswith("veslide topography: %s: " % args[0]) and want in err, (args, err)
    with pytest.raises(ValueError, match=r"no channel 'Phase': channel= \(--channel\)"):
        read(x3p, channel="Phase")
    assert read(plain, unit="um", physical_sizes=(40, 24)).source["channels"] == ["Default"]


# --- line scans: height files of ny = 1 ----------------------------------------------------------

def profile(n=200, seed=4):
    """a smooth random non-periodic profile [ix] (a few long waves) plus a slope and a bow [um]"""
    rng = np.random.default_rng(seed)
    x = np.arange(n) / n
    z = sum(rng.standard_normal() * np.cos(2 * np.pi * rng.uniform(0.5, 9) * x + rng.uniform(0, 6.3))
            for _ in range(10))
    return 0.05 * z + 0.3 * x - 0.2 * x ** 2


def test_a_line_scan_becomes_a_height_file_of_ny_1(tmp_path, exe):
    """a stylus profile as a two-column text file (x, z in um, 0.5 um apart): read as a line scan,
    prepared, written with ny = 1 and length_y_m the solve grid's spacing, and solved"""
    n, dx = 200, 0.5
    z = profile(n)
    f = tmp_path / "profile.txt"
    np.savetxt(f, np.c_[np.arange(n) * dx, z])
    scan = read(f, unit="um")
    assert scan.line_scan and (scan.nx, scan.ny) == (n, 1) and scan.heights.shape == (n, 1)
    assert scan.length_x_m == pytest.approx(n * dx * 1e-6) and scan.length_y_m == pytest.approx(dx * 1e-6)
    np.testing.assert_allclose(scan.heights[:, 0], z * 1e-6, rtol=1e-12)
    out = tmp_path / "line.h5"
    p = _cli(tmp_path, f, "--unit", "um", "--out", out, "--nx", 64, "--k-cut", 12)
    assert p.returncode == 0 and p.stderr == "", p.stderr
    assert "a line scan of 200 points, 100 um" in p.stdout and "nx = 64, ny = 1 /" in p.stdout
    with h5py.File(out, "r") as f5:
        ds = f5["/height_m"]
        assert ds.shape == (1, 64)                                   # h5py (ny, nx)
        assert ds.attrs["length_x_m"] == pytest.approx(100e-6)
        assert ds.attrs["length_y_m"] == pytest.approx(100e-6 / 64)      # square cells of the solve grid
        prep = json.loads(ds.attrs["preparation"])
        assert prep["line_scan"]["length_y_m"] == ds.attrs["length_y_m"] and "square" in prep["line_scan"]["why"]
    assert prep["source"]["line_scan"] is True and prep["result"]["ny"] == 1
    back = veslide.load_topography(out)
    assert back.heights.shape == (64, 1)
    qx, qy, c = veslide.psd_2d(back.heights, back.length_x_m, back.length_y_m)     # nothing above k_cut
    above = np.abs(qx) > 12 * 2 * np.pi / back.length_x_m * (1 + 1e-9)
    assert above.any() and c[above].max() <= 1e-24 * c.max()
    pr = params(surface={"kind": "file", "file": str(out)}, load={"mean_pressure_pa": 1e5})
    r = veslide.run(pr, output=tmp_path / "solve.h5", exe=exe, progress=None)
    assert r.converged and (r.scalars["nx"], r.scalars["ny"]) == (64, 1)
    assert r.scalars["length_y_m"] == pytest.approx(back.length_y_m, rel=1e-12)
    np.testing.assert_array_equal(r.fields.height_m.transpose("x", "y").values, back.heights)


def test_a_one_column_profile_needs_its_length(tmp_path):
    f = tmp_path / "z.txt"
    np.savetxt(f, profile(120))
    p = _cli(tmp_path, f, "--out", tmp_path / "o.h5")
    assert p.returncode == 1 and "--size LX and --unit um" in p.stderr and not (tmp_path / "o.h5").exists()
    p = _cli(tmp_path, f, "--out", tmp_path / "o.h5", "--unit", "um", "--size", 60, 1)
    assert p.returncode == 1 and "a line scan: --size LX, got 2 numbers" in p.stderr
    p = _cli(tmp_path, f, "--out", tmp_path / "o.h5", "--unit", "um", "--size", 60)
    assert p.returncode == 0, p.stderr
    assert veslide.load_topography(tmp_path / "o.h5").heights.shape == (120, 1)


@pytest.mark.parametrize("periodic", ["tukey", "mirror", "crop", "none"])
def test_line_scans_are_detrended_periodised_and_banded(periodic):
    n, lx = 200, 1e-4
    z = 1e-6 * profile(n)
    x = np.arange(n) / n
    scan = Scan.from_heights(z, lx)
    assert scan.line_scan and scan.heights.shape == (n, 1)
    s = prepare(scan, nx=64, periodic=periodic, taper=0.2, k_cut=10)
    assert s.detrended.shape == (n, 1) and s.heights.shape == (64, 1) and s.ny == 1
    assert s.length_y_m == pytest.approx(s.length_x_m / 64)
    assert s.preparation["line_scan"]["length_y_m"] == s.length_y_m
    m = s.periodised.shape[0]
    assert s.periodised.shape == (m, 1)
    if periodic == "mirror":                                        # the image in x only
        assert m == 2 * n and s.length_x_m == pytest.approx(2 * lx)
        np.testing.assert_array_equal(s.periodised[n:, 0], s.periodised[n - 1::-1, 0])
        assert s.costs["area_fraction_changed"] == 0.5 and s.costs["edge_jump_x_after"] == 0
    elif periodic == "crop":
        assert 0.8 * n <= m < n and s.length_x_m == pytest.approx(lx * m / n)
    elif periodic == "tukey":
        assert s.periodised[0, 0] == 0 and s.costs["area_fraction_changed"] == pytest.approx(0.2, abs=1.5 / n)
        assert s.costs["edge_jump_x_after"] < 0.1 * s.costs["edge_jump_x_before"]
    qx, qy, c = veslide.psd_2d(s.heights, s.length_x_m, s.length_y_m)
    above = np.abs(qx) > 10 * 2 * np.pi / s.length_x_m * (1 + 1e-9)
    assert c[above].max() <= 1e-24 * c.max()
    # the detrending removes a line and a parabola exactly, as on a topography
    for mode, added in (("plane", 3e-6 * x - 1e-6), ("curvature", 2e-6 * x ** 2 - 3e-6 * x)):
        a = prepare(Scan.from_heights(z, lx), detrend=mode, periodic=periodic, taper=0.2, k_cut=10).detrended
        b = prepare(Scan.from_heights(z + added, lx), detrend=mode, periodic=periodic, taper=0.2, k_cut=10).detrended
        np.testing.assert_allclose(b, a, rtol=0, atol=1e-12 * np.abs(added).max())
    with pytest.raises(ValueError, match=r"a line scan makes a grid of ny = 1, got ny=8 \(--ny 8\)"):
        prepare(scan, nx=64, ny=8, periodic=periodic, taper=0.2, k_cut=10)


def test_line_scan_undefined_points_crop_to_the_longest_measured_run():
    z = 1e-6 * profile(200)
    z[[30, 31, 150]] = np.nan                                       # runs 0..29, 32..149, 151..199
    scan = Scan.from_heights(z, 1e-4)
    assert scan.topography.has_undefined_data
    s = prepare(scan, crop_valid=True, detrend="none", periodic="none", k_cut=10)
    assert s.preparation["undefined_points"]["measured_rectangle"]["start"] == [32, 0]
    assert s.preparation["undefined_points"]["measured_rectangle"]["points"] == [118, 1]
    np.testing.assert_allclose(s.detrended[:, 0], z[32:150] - z[32:150].mean(), rtol=0, atol=1e-20)
    s = prepare(scan, k_cut=10)                                     # 1.5 %: filled
    assert s.preparation["undefined_points"]["filled_fraction"] == 0.015 and np.all(np.isfinite(s.heights))


# --- the height file: attributes for the solver; writing the same content again ------------------

def test_height_file_carries_filled_fraction_and_band_slope_removed(tmp_path):
    f = write_x3p(tmp_path / "s.x3p", holes(4, extra=1).T, 1e-6, 1e-6)
    with pytest.warns(veslide.VeslideWarning):
        s = prepare(read(f), nx=32, k_cut=3, fill="harmonic")
    out = s.write(tmp_path / "surf.h5")
    with h5py.File(out, "r") as f5:
        a = f5["/height_m"].attrs
        assert a["filled_fraction"] == 0.0205 and a["filled_fraction"].dtype == np.float64
        assert a["band_slope_variance_removed"] == s.costs["band_slope_variance_removed"] > 0.5
        assert a["band_slope_variance_removed"].dtype == np.float64
        prep = json.loads(a["preparation"])
    old_keys = {"format", "layouts", "source", "units", "undefined_points", "detrend", "periodic", "band", "result",
                "costs", "costs_note", "veslide_python"}
    assert old_keys <= set(prep)                                     # the JSON keeps its keys
    # heights not prepared from a scan: nothing filled, no band
    veslide.write_topography(tmp_path / "raw.h5", rough(8, 4), 1e-4)
    with h5py.File(tmp_path / "raw.h5", "r") as f5:
        a = f5["/height_m"].attrs
        assert (a["filled_fraction"], a["band_slope_variance_removed"]) == (0.0, 0.0)
    with pytest.raises(ValueError, match=r"filled_fraction must be a fraction in \[0, 1\]"):
        veslide.write_topography(tmp_path / "bad.h5", rough(8, 4), 1e-4, filled_fraction=2.0)
    assert not (tmp_path / "bad.h5").exists()


def test_writing_the_same_surface_again_is_a_no_op(tmp_path):
    scan = Scan.from_heights(rough(50, 40), 1e-4)
    s = prepare(scan, nx=32, k_cut=6)
    out = s.write(tmp_path / "surf.h5")
    before = (out.read_bytes(), out.stat().st_mtime_ns)
    assert prepare(scan, nx=32, k_cut=6).write(out) == out        # the same content: nothing written
    assert (out.read_bytes(), out.stat().st_mtime_ns) == before
    for other in (prepare(scan, nx=32, k_cut=5),                    # other heights and preparation
                  prepare(Scan.from_heights(rough(50, 40), 2e-4), nx=32, k_cut=6)):   # other sides
        with pytest.raises(FileExistsError, match="exists with other heights or attributes"):
            other.write(out)
        assert out.read_bytes() == before[0]
    s5 = prepare(scan, nx=32, k_cut=5)
    s5.write(out, overwrite=True)
    np.testing.assert_array_equal(veslide.load_topography(out).heights, s5.heights)
    # the same preparation text with heights one bit off: refused
    h = s5.heights.copy()
    h[3, 4] = np.nextafter(h[3, 4], 1.0)
    with pytest.raises(FileExistsError):
        veslide.write_topography(out, h, (s5.length_x_m, s5.length_y_m), preparation=s5.preparation)
    # the command line run twice: the second finds its file and says so by exiting 0
    f = write_x3p(tmp_path / "scan.x3p", rough(50, 40).T, 2e-6, 2e-6)
    for word in ("written:  ", "unchanged:"):
        p = _cli(tmp_path, f, "--out", tmp_path / "cli.h5", "--nx", 32, "--k-cut", 6)
        assert p.returncode == 0, p.stderr
        assert p.stdout.splitlines()[-2].startswith(word + " %s:/height_m (32 x 26" % (tmp_path / "cli.h5"))
    p = _cli(tmp_path, f, "--out", tmp_path / "cli.h5", "--nx", 32, "--k-cut", 5)
    assert p.returncode == 1 and "exists with other heights or attributes" in p.stderr
