"""write_topography: the layout the solver reads, checked through a solve and back."""
import h5py
import numpy as np
import pytest
import xarray as xr

import veslide
from conftest import params

N, L = 32, 0.01


def anisotropic_heights(alpha_deg=30.0, eps=0.3, hurst=0.8, k_max=8, seed=7):
    """Heights [ix, iy] whose spectrum is elongated along alpha_deg: C(q) ~ (eps^2 u^2 + w^2)^-(1+H)
    with u along alpha, for q0 <= |q| <= k_max q0; random phases, exact amplitudes (so the
    realised slope tensor is the spectrum's)."""
    k = np.fft.fftfreq(N, 1.0 / N)
    kx, ky = np.meshgrid(k, k, indexing="ij")
    a = np.radians(alpha_deg)
    u, w = kx * np.cos(a) + ky * np.sin(a), -kx * np.sin(a) + ky * np.cos(a)
    kk = np.hypot(kx, ky)
    c = np.where((kk >= 1) & (kk <= k_max), np.maximum(np.hypot(eps * u, w), 0.5) ** (-2 * (1 + hurst)), 0.0)
    noise = np.fft.fft2(np.random.default_rng(seed).standard_normal((N, N)))
    h = np.fft.ifft2(np.sqrt(c) * noise / np.abs(noise)).real
    return 1e-5 * h / h.std()


def test_anisotropic_surface_at_30_degrees_round_trip(tmp_path, exe):
    h = anisotropic_heights(30.0)
    expected = veslide.major_axis_deg(veslide.slope_tensor(h, L))
    assert abs(expected - 30.0) < 1.0                        # the generated surface itself
    assert abs(veslide.major_axis_deg(veslide.slope_tensor(h.T, L)) - 60.0) < 1.0   # what a swap gives
    topo = veslide.write_topography(tmp_path / "topo.h5", h, L)
    p = params(surface={"kind": "file", "file": str(topo)},
               analysis={"anisotropy": True, "zeta1": 1, "zeta2": 8})
    r = veslide.run(p, output=tmp_path / "solve.h5", exe=exe, progress=None)
    assert r.converged and r.scalars["nx"] == r.scalars["ny"] == N
    assert r.scalars["length_x_m"] == L                       # from the length_m attribute
    back = r.fields.height_m
    np.testing.assert_array_equal(back.transpose("x", "y").values, h)   # [ix, iy], bit for bit
    assert back.sel(x=back.x[3], y=back.y[11]).item() == h[3, 11]
    # the solver's realised slope tensor has its major axis at 30 degrees, not 60
    theta_s = np.degrees(r.scalars["theta_s_rad"])
    assert abs(theta_s - 30.0) < 1.0 and abs(theta_s - 60.0) > 25.0
    assert theta_s == pytest.approx(expected, abs=1e-9)
    m = r.anisotropy["surface_tensor"]                      # [M11, M21, M12, M22]
    np.testing.assert_allclose(m, veslide.slope_tensor(back.values, L, q_min=2 * np.pi / L,
                                                      q_max=8 * 2 * np.pi / L).ravel(order="F"), rtol=1e-10)
    # and the major axis of m2(theta) as the polar plot draws it
    a = r.anisotropy
    assert abs(np.degrees(a["theta_rad"][np.argmax(a["m2_surface"])]) - 30.0) <= 2.5


def test_file_holds_the_transpose_with_its_attributes(tmp_path):
    h = np.arange(16.0).reshape(4, 4) * 1e-6                  # h[ix, iy]
    path = veslide.write_topography(tmp_path / "t.h5", h, 2e-3, dataset="/scan/h")
    with h5py.File(path, "r") as f:
        ds = f["/scan/h"]
        assert ds.dtype == np.float64 and ds.shape == (4, 4)
        assert ds[1, 3] == h[3, 1]                            # h5py [iy, ix]
        assert ds.attrs["length_m"] == 2e-3 and ds.attrs["units"] == "m"
        assert "[iy, ix]" in ds.attrs["layout"]
    back, length = veslide.read_topography(path, "/scan/h")
    np.testing.assert_array_equal(back, h)
    assert length == 2e-3


def test_dataarray_is_ordered_by_its_dimension_names(tmp_path):
    h = anisotropic_heights(30.0)
    da = xr.DataArray(h.T, dims=("y", "x"))                   # [iy, ix] but labelled
    veslide.write_topography(tmp_path / "a.h5", da, L)
    np.testing.assert_array_equal(veslide.read_topography(tmp_path / "a.h5")[0], h)
    with pytest.raises(ValueError, match="x and y"):
        veslide.write_topography(tmp_path / "b.h5", xr.DataArray(h, dims=("row", "col")), L)


def test_rectangles_are_written_with_both_sides(tmp_path):
    h = np.arange(32.0).reshape(8, 4) * 1e-6                  # h[ix, iy], nx = 8, ny = 4
    veslide.write_topography(tmp_path / "r.h5", h, L)         # one side: square cells, ly = lx ny/nx
    veslide.write_topography(tmp_path / "r.h5", h, (L, 2 * L), dataset="/pair", preparation={"detrend": "plane"})
    with h5py.File(tmp_path / "r.h5", "r") as f:
        a, b = f["/height_m"], f["/pair"]
        assert a.shape == (4, 8) and a[1, 6] == h[6, 1]
        assert (a.attrs["length_x_m"], a.attrs["length_y_m"], a.attrs["length_m"]) == (L, L / 2, L)
        assert (b.attrs["length_x_m"], b.attrs["length_y_m"], b.attrs["length_m"]) == (L, 2 * L, L)
        assert "preparation" not in a.attrs and b.attrs["preparation"] == '{"detrend": "plane"}'
    back = veslide.load_topography(tmp_path / "r.h5", "/pair")
    np.testing.assert_array_equal(back.heights, h)
    assert (back.length_x_m, back.length_y_m, back.preparation) == (L, 2 * L, {"detrend": "plane"})
    assert veslide.read_topography(tmp_path / "r.h5", "/pair")[1] == L


def test_bad_topographies_are_refused(tmp_path):
    with pytest.raises(ValueError, match="nx >= 2"):
        veslide.write_topography(tmp_path / "t.h5", np.zeros((1, 4)), L)
    with pytest.raises(ValueError, match="pair"):
        veslide.write_topography(tmp_path / "t.h5", np.zeros((4, 4)), (L, L, L))
    with pytest.raises(ValueError, match="NaN"):
        veslide.write_topography(tmp_path / "t.h5", np.full((4, 4), np.nan), L)
    with pytest.raises(ValueError, match="length_m"):
        veslide.write_topography(tmp_path / "t.h5", np.zeros((4, 4)), 0.0)
    veslide.write_topography(tmp_path / "t.h5", np.zeros((4, 4)), L)
    with pytest.raises(FileExistsError):
        veslide.write_topography(tmp_path / "t.h5", np.ones((4, 4)), L)
    veslide.write_topography(tmp_path / "t.h5", np.ones((4, 4)), L, overwrite=True)
    assert veslide.read_topography(tmp_path / "t.h5")[0].sum() == 16
