"""Height files for `&surface kind='file'`, measured scans made into them, and the spectral
measures of a surface (PSD, slope tensor).

Heights are indexed [ix, iy] throughout (numpy's and SurfaceTopography's order). An instrument's
matrix is [iy, ix] (one row per scan line along x): pass `matrix.T`, or `Scan.from_matrix`. The
height file holds the solver's Fortran (nx, ny) array: h5py shape (ny, nx), index [iy, ix].

Measured scans (`veslide.measured`, needs SurfaceTopography): `read(path, ...)` -> `Scan`,
`prepare(scan, nx, ny, detrend, periodic, taper, k_cut, fill, crop_valid)` -> `PreparedSurface`
(`.write(path)`); line scans make height files of ny = 1.
"""
import json
from pathlib import Path

import h5py
import numpy as np

from ._h5 import open_file

LAYOUT = "Fortran order (nx, ny): h5py shape (ny, nx), index [iy, ix]"


def _as_xy(heights):
    """heights as a float64 array indexed [ix, iy]; an xarray DataArray is put in (x, y) order by
    its dimension names, so that a (y, x) array cannot be written transposed."""
    dims = getattr(heights, "dims", None)
    if dims is not None and set(dims) == {"x", "y"}:
        heights = heights.transpose("x", "y")
    elif dims is not None and len(dims) == 2 and not isinstance(heights, np.ndarray):
        raise ValueError("heights has dimensions %s: name them x and y (or pass a numpy array "
                         "indexed [ix, iy])" % (tuple(dims),))
    h = np.asarray(getattr(heights, "values", heights), dtype=np.float64)
    if h.ndim != 2:
        raise ValueError("heights must be a 2-D array indexed [ix, iy], got %d dimensions" % h.ndim)
    return h


def _lengths(length_m, nx, ny):
    """(lx, ly) [m] from a number (the side along x; square cells: ly = lx ny / nx) or a pair."""
    if np.ndim(length_m) == 0:
        lx = float(length_m)
        ly = lx * ny / nx
    else:
        if len(length_m) != 2:
            raise ValueError("length_m must be a number or a pair (lx, ly) [m], got %r" % (length_m,))
        lx, ly = (float(v) for v in length_m)
    for name, v in (("length_m", lx), ("length_m (y)", ly)):
        if not (v > 0 and np.isfinite(v)):
            raise ValueError("%s must be > 0, got %r" % (name, v))
    return lx, ly


def _prepared_number(preparation, keys):
    """preparation[keys[0]][keys[1]] as a float, or None (no such entry; a text that is not JSON)."""
    if isinstance(preparation, str):
        try:
            preparation = json.loads(preparation)
        except ValueError:
            return None
    try:
        return float(preparation[keys[0]][keys[1]])
    except (KeyError, TypeError, ValueError, IndexError):
        return None


def _same_dataset(path, dataset, data, attrs):
    """True when the file at path holds `dataset` with bitwise the same data and exactly these attributes."""
    if not (path.is_file() and h5py.is_hdf5(path)):
        return False
    with h5py.File(path, "r") as f:
        ds = f.get(dataset)
        if not isinstance(ds, h5py.Dataset) or ds.shape != data.shape or ds.dtype != data.dtype:
            return False
        if ds[()].tobytes() != data.tobytes():
            return False
        got = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in ds.attrs.items()}
    if set(got) != set(attrs):
        return False
    for k, v in attrs.items():
        g = got[k]
        if isinstance(v, str):
            if g != v:
                return False
        elif np.asarray(g).tobytes() != np.asarray(v, dtype=np.float64).tobytes():
            return False
    return True


def write_topography(path, heights, length_m, dataset="/height_m", *, preparation=None, overwrite=False,
                     filled_fraction=None, band_slope_variance_removed=None):
    """Write heights [m] for `&surface kind='file', file=path, dataset=dataset`.

    heights      2-D, indexed [ix, iy] (x first; an xarray DataArray with dims x and y in any
                 order); nx >= 2, ny >= 1 (ny = 1: a line scan, heights (nx, 1)), nx and ny may
                 differ. An instrument's matrix [iy, ix] (rows along x) is written as `matrix.T`.
    length_m     the cell's side along x [m] (square cells: ly = lx ny / nx), or the pair
                 (lx, ly); stored as the attributes `length_x_m`, `length_y_m` and `length_m`
                 (= length_x_m, for older readers). The solver uses them unless &grid sets lx_m.
    preparation  how the heights were made (a dict, written as JSON text, or a text): the
                 attribute `preparation`, which the solver copies into its output
                 (`veslide.topography.prepare` fills it).
    filled_fraction, band_slope_variance_removed
                 float attributes of the same names for the solver: the share of the scan's points
                 that were filled (invented) and the fraction of the cell's slope variance the band
                 removed. None (default): the preparation's undefined_points.filled_fraction and
                 costs.band_slope_variance_removed, 0 where it has none (heights not prepared from a
                 scan: nothing filled, no band).
    The solver reads a Fortran (nx, ny) array h(ix, iy): HDF5 stores it with dims (ny, nx), so the
    array written by h5py is the transpose, heights.T, with a `layout` attribute saying so.
    The file is created or appended to. A dataset already there with bitwise the same heights and
    attributes (sides, preparation, ...) is left as it is (the path returned: writing it again is
    a no-op); a different one is replaced only with overwrite=True."""
    h = _as_xy(heights)
    nx, ny = h.shape
    if nx < 2 or ny < 1:
        raise ValueError("heights must have nx >= 2 and ny >= 1 points, got %d x %d" % (nx, ny))
    if not np.all(np.isfinite(h)):
        raise ValueError("heights contain NaN or infinite values")
    lx, ly = _lengths(length_m, nx, ny)
    if filled_fraction is None:
        filled_fraction = _prepared_number(preparation, ("undefined_points", "filled_fraction"))
    if band_slope_variance_removed is None:
        band_slope_variance_removed = _prepared_number(preparation, ("costs", "band_slope_variance_removed"))
    if preparation is not None and not isinstance(preparation, str):
        preparation = json.dumps(preparation, sort_keys=False)
    attrs = {"length_x_m": lx, "length_y_m": ly, "length_m": lx, "units": "m", "layout": LAYOUT,
             "filled_fraction": float(filled_fraction or 0.0),
             "band_slope_variance_removed": float(band_slope_variance_removed or 0.0)}
    for name in ("filled_fraction", "band_slope_variance_removed"):
        if not 0 <= attrs[name] <= 1:
            raise ValueError("%s must be a fraction in [0, 1], got %r" % (name, attrs[name]))
    if preparation is not None:
        attrs["preparation"] = preparation
    data = np.ascontiguousarray(h.T)                 # [iy, ix] on disk
    path = Path(path)
    if _same_dataset(path, dataset, data, attrs):
        return path
    with h5py.File(path, "a") as f:
        if dataset in f:
            if not overwrite:
                raise FileExistsError("%s: dataset %s exists with other heights or attributes: overwrite=True "
                                      "(--overwrite) replaces it" % (path, dataset))
            del f[dataset]
        ds = f.create_dataset(dataset, data=data)
        for k, v in attrs.items():
            ds.attrs[k] = v
    return path


def read_topography(path, dataset="/height_m"):
    """(heights indexed [ix, iy], length_m or None) from a height file as the solver reads it
    (length_m: the side along x; `load` gives both sides and the preparation)."""
    with open_file(path) as f:
        ds = f[dataset]
        h = np.ascontiguousarray(ds[()].T)
        length = ds.attrs.get("length_x_m", ds.attrs.get("length_m"))
    return h, (float(length) if length is not None else None)


def load(path, dataset="/height_m"):
    """A height file as a `HeightFile`: heights [ix, iy] (the transpose of h5py's (ny, nx)),
    length_x_m, length_y_m (None when the file has none; ly from lx ny / nx when only length_m),
    preparation (the dict of its `preparation` JSON; {} without one) and attrs."""
    with open_file(path) as f:
        ds = f[dataset]
        h = np.ascontiguousarray(ds[()].T)
        attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in ds.attrs.items()}
    nx, ny = h.shape
    lx = attrs.get("length_x_m", attrs.get("length_m"))
    ly = attrs.get("length_y_m", None if lx is None else float(lx) * ny / nx)
    prep = attrs.get("preparation")
    try:
        prep = json.loads(prep) if prep else {}
    except ValueError:
        prep = {"text": prep}
    return HeightFile(h, None if lx is None else float(lx), None if ly is None else float(ly), prep, attrs)


class HeightFile:
    """A height file read back by `load`: heights [ix, iy] [m], length_x_m, length_y_m,
    preparation (dict), attrs (the dataset's attributes)."""

    def __init__(self, heights, length_x_m, length_y_m, preparation, attrs):
        self.heights, self.length_x_m, self.length_y_m = heights, length_x_m, length_y_m
        self.preparation, self.attrs = preparation, attrs

    def __repr__(self):
        return "<HeightFile %d x %d, %s x %s m>" % (*self.heights.shape, self.length_x_m, self.length_y_m)


def _heights_and_sizes(heights, length_x_m, length_y_m):
    h = _as_xy(heights)
    nx, ny = h.shape
    lx = float(length_x_m)
    ly = float(length_y_m) if length_y_m is not None else lx * ny / nx
    return h, lx, ly


def _wavevectors(nx, ny, lx, ly):
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=lx / nx)
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=ly / ny)
    return qx, qy


def psd_2d(heights, length_x_m, length_y_m=None):
    """(qx [1/m], qy [1/m], C [m^4]) with C[ix, iy] the 2-D power spectral density of the heights
    [ix, iy] in the normalisation <h^2> = sum C(q) dq^2 (dq^2 = (2 pi)^2 / (Lx Ly)), i.e.
    C(q) = Lx Ly / (2 pi)^2 |h_q|^2 with h_q = fft(h)/N. Arrays in fft order (np.fft.fftshift to plot)."""
    h, lx, ly = _heights_and_sizes(heights, length_x_m, length_y_m)
    nx, ny = h.shape
    hq = np.fft.fft2(h) / (nx * ny)
    qx, qy = _wavevectors(nx, ny, lx, ly)
    return qx, qy, lx * ly / (2 * np.pi) ** 2 * np.abs(hq) ** 2


def psd_radial(heights, length_x_m, length_y_m=None):
    """(q [1/m], C(q) [m^4]): the 2-D PSD averaged over shells of width q0 = 2 pi/max(Lx, Ly)
    centred on multiples of q0 (q = 0 excluded; empty shells dropped)."""
    qx, qy, c = psd_2d(heights, length_x_m, length_y_m)
    q = np.hypot(*np.meshgrid(qx, qy, indexing="ij"))
    h, lx, ly = _heights_and_sizes(heights, length_x_m, length_y_m)
    q0 = 2 * np.pi / max(lx, ly)
    shell = np.rint(q / q0).astype(int).ravel()
    counts = np.bincount(shell)
    sums = np.bincount(shell, weights=c.ravel())
    k = np.nonzero(counts)[0]
    k = k[k > 0]
    return k * q0, sums[k] / counts[k]


def slope_tensor(heights, length_x_m, length_y_m=None, q_min=None, q_max=None):
    """The slope tensor M_ij = <d_i h d_j h> (2 x 2) of heights [ix, iy] from their spectrum,
    optionally over the band q_min <= |q| <= q_max [1/m]; Nyquist lines carry no slope (as in the
    solver). Its major axis: 0.5 * atan2(2 M_xy, M_xx - M_yy)."""
    qx, qy, c = psd_2d(heights, length_x_m, length_y_m)
    h, lx, ly = _heights_and_sizes(heights, length_x_m, length_y_m)
    nx, ny = h.shape
    kx, ky = np.meshgrid(qx, qy, indexing="ij")
    if nx % 2 == 0:
        kx[nx // 2, :] = 0.0
    if ny % 2 == 0:
        ky[:, ny // 2] = 0.0
    w = c * (2 * np.pi) ** 2 / (lx * ly)     # |h_q|^2
    q = np.hypot(*np.meshgrid(qx, qy, indexing="ij"))
    band = np.ones_like(q, dtype=bool)
    if q_min is not None:
        band &= q >= q_min * (1 - 1e-12)
    if q_max is not None:
        band &= q <= q_max * (1 + 1e-12)
    w = np.where(band, w, 0.0)
    mxx, myy, mxy = (w * kx * kx).sum(), (w * ky * ky).sum(), (w * kx * ky).sum()
    return np.array([[mxx, mxy], [mxy, myy]])


def major_axis_deg(tensor):
    """Direction [deg, 0..180) of the major axis of a symmetric 2 x 2 tensor."""
    t = np.asarray(tensor)
    return np.degrees(0.5 * np.arctan2(2 * t[0, 1], t[0, 0] - t[1, 1])) % 180.0


# measured scans: read through SurfaceTopography (imported when first used), prepared here
from .measured import PreparedSurface, Scan, prepare, read  # noqa: E402
