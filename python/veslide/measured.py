"""Measured topographies: read an instrument's scan through SurfaceTopography, make it a periodic
height file for `&surface kind='file'`, and record every choice made and what it cost.

    scan = veslide.topography.read("scan.x3p")                   # any format SurfaceTopography reads
    s = veslide.topography.prepare(scan, nx=256, ny=256, detrend="curvature",
                                   periodic="tukey", taper=0.1, k_cut=64)
    print("\\n".join(s.lines)); s.costs["area_fraction_changed"]
    s.write("surf.h5")                                           # &surface kind='file', file='surf.h5'

The same from the shell: `python -m veslide topography scan.x3p --out surf.h5 --nx 256 ...`.

No silent wrong answer: a scan with more than 2 % of its points unmeasured is refused unless
`crop_valid=True` (the largest measured rectangle) or `fill='harmonic'` (warned: 'filled-scan');
a prepared rms slope above 10 is refused (heights in another unit, a channel that is not
heights); a band that removes more than half of the slope variance is warned
('band-slope-removed', naming the grid that keeps half). A line scan (a profile) becomes a
height file of ny = 1.

Three orders of the same heights, and which array has which:

    instrument matrix  [iy, ix]  one row per scan line: a row runs along x, the rows along y (as
                                 instruments, images and text matrices store them). `Scan.matrix`,
                                 `Scan.from_matrix`.
    numpy, this package [ix, iy]  x first: `Scan.heights`, `PreparedSurface.heights` and every
                                 other array here, as SurfaceTopography's `heights()`.
    height file        Fortran (nx, ny), h(ix, iy): h5py shape (ny, nx), index [iy, ix] (the
                                 instrument's order again); `write_topography` transposes.

SurfaceTopography does the reading (every format it knows; no reader is written here), the unit
conversion (`to_unit('m')`), the detrending (`detrend`: its 'mean', 'height' = plane, 'curvature'
= second-order polynomial, least squares), mirror stitching (`mirror_stitch`) and the filling of
undefined points (`interpolate_undefined_data`). Written here, with numpy, what it lacks for this:

* the taper. Its `window` scales the windowed heights back to the scan's rms (the normalisation a
  spectrum estimate wants) and its 2-D window is radial (it lowers the corners and most of the
  area); a periodic cell wants a separable Tukey window that leaves the inside as measured and only
  brings the edges to the mean.
* the crop to the sub-rectangle whose opposite edges match best (it has none).
* band filter and resampling in one step. Its `shortcut` filters on the scan's own grid and its
  `interpolate_fourier` only enlarges a grid, and `downsample` picks or averages points (aliasing
  what lies above the new Nyquist); here the spectrum is cut at k_cut and copied to the solve
  grid, which gives any grid without aliasing.
"""
import hashlib
import json
import logging
import re
from pathlib import Path

import numpy as np

from ._warning import warn

#: detrend choices -> SurfaceTopography's detrend_mode
DETREND_MODES = {"none": "center", "plane": "height", "curvature": "curvature"}
PERIODIC_METHODS = ("tukey", "mirror", "crop", "none")
#: fill choices: 'auto' fills up to FILL_MAX_AUTO of the points and refuses more, 'harmonic' fills
#: any share (warning above FILL_MAX_AUTO), None refuses any undefined point
FILL_CHOICES = ("auto", "harmonic", None)
#: the largest share of undefined points filled without being asked to ('filled-scan' above it)
FILL_MAX_AUTO = 0.02
#: the largest share of the cell's slope variance the band may remove without a warning
#: ('band-slope-removed' above it)
BAND_SLOPE_REMOVED_MAX = 0.5
#: a prepared surface of a larger rms slope is refused: no contact model of small slopes holds, and
#: heights in the wrong unit or a channel that is not heights give such numbers
SLOPE_REFUSED = 10.0

LAYOUTS = {
    "instrument matrix": "[iy, ix]: one row per scan line along x (Scan.matrix)",
    "numpy (this package, SurfaceTopography)": "[ix, iy] (Scan.heights, PreparedSurface.heights)",
    "height file": "Fortran (nx, ny) h(ix, iy): h5py shape (ny, nx), index [iy, ix]",
}


def _st():
    try:
        import SurfaceTopography
    except ImportError as e:          # an optional dependency: pip install 'veslide[measured]'
        raise ImportError("measured topographies need SurfaceTopography: pip install SurfaceTopography "
                          "(or the extra: pip install -e 'python[measured]')") from e
    return SurfaceTopography


def _jsonable(x):
    """x with numpy scalars and arrays, tuples and paths made JSON's types."""
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return _jsonable(x.tolist())
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, float) and not np.isfinite(x):
        return str(x)
    if isinstance(x, (str, int, float, bool)) or x is None:
        return x
    return str(x)


class Scan:
    """A measured topography in metres: `topography` (a SurfaceTopography topography or line scan,
    unit 'm'), `heights` [ix, iy] (m; masked where the instrument marked points undefined), `matrix`
    the same as [iy, ix], `length_x_m`, `length_y_m`, `nx`, `ny`, `line_scan`, and `source` (a
    dict: the file, its format and reader, the channel, the unit and the factor that made it
    metres). A line scan (a stylus profile along x) has heights of shape (nx, 1), ny = 1 and
    length_y_m its point spacing, length_x_m / nx (square cells)."""

    def __init__(self, topography, source):
        self.topography = topography
        self.source = source

    @property
    def line_scan(self):
        return self.topography.dim == 1

    @property
    def heights(self):
        h = self.topography.heights()
        return h[:, None] if h.ndim == 1 else h

    @property
    def matrix(self):
        """The heights [iy, ix], rows along x, as instruments store them."""
        return self.heights.T

    @property
    def nx(self):
        return int(self.topography.nb_grid_pts[0])

    @property
    def ny(self):
        return 1 if self.line_scan else int(self.topography.nb_grid_pts[1])

    @property
    def length_x_m(self):
        return float(self.topography.physical_sizes[0])

    @property
    def length_y_m(self):
        if self.line_scan:
            return self.length_x_m / self.nx
        return float(self.topography.physical_sizes[1])

    @classmethod
    def from_heights(cls, heights, length_x_m, length_y_m=None, unit="m", periodic=False):
        """A scan from heights [ix, iy] in `unit` (lengths in the same unit; length_y_m None:
        square points, length_x_m * ny / nx). 1-D heights, or ny = 1, make a line scan (a
        SurfaceTopography UniformLineScan; length_y_m must be None)."""
        st = _st()
        h = np.asarray(heights, dtype=np.float64)
        if h.ndim == 2 and h.shape[1] == 1:
            h = h[:, 0]
        if h.ndim == 1:
            if length_y_m is not None:
                raise ValueError("a line scan has no y side: leave length_y_m None (it becomes the point spacing)")
            t = st.UniformLineScan(h, float(length_x_m), unit=unit, periodic=periodic)
        elif h.ndim == 2:
            ly = length_x_m * h.shape[1] / h.shape[0] if length_y_m is None else length_y_m
            t = st.Topography(h, (float(length_x_m), float(ly)), unit=unit, periodic=periodic)
        else:
            raise ValueError("heights must be 2-D [ix, iy] (or 1-D, a line scan), got %d dimensions" % h.ndim)
        return _in_metres(t, {"path": None, "format": "array", "reader": "Scan.from_heights [ix, iy]"})

    @classmethod
    def from_matrix(cls, matrix, length_x_m, length_y_m=None, unit="m", periodic=False):
        """A scan from an instrument matrix [iy, ix] (one row per scan line along x)."""
        s = cls.from_heights(np.asarray(matrix).T, length_x_m, length_y_m, unit, periodic)
        s.source["reader"] = "Scan.from_matrix [iy, ix]"
        return s

    def __repr__(self):
        if self.line_scan:
            return "<Scan %s: a line scan of %d points, %.4g m>" % (
                self.source.get("path") or self.source.get("reader"), self.nx, self.length_x_m)
        return "<Scan %s: %d x %d points, %.4g x %.4g m>" % (
            self.source.get("path") or self.source.get("reader"), self.nx, self.ny, self.length_x_m,
            self.length_y_m)


def _in_metres(topo, source):
    st = _st()
    from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor
    if topo.dim not in (1, 2):
        raise ValueError("%s: a topography of %d dimensions; a scan has 2 (or 1: a line scan)"
                         % (source.get("path"), topo.dim))
    if not topo.is_uniform:
        raise ValueError("%s: not on a uniform grid" % source.get("path"))
    if topo.unit is None:
        raise ValueError("%s: the file gives no length unit: pass unit='um' (or what it is; --unit)"
                         % source.get("path"))
    factor = float(get_unit_conversion_factor(topo.unit, "m"))
    source.update(unit=topo.unit, factor_to_m=factor, nb_grid_pts=[int(n) for n in topo.nb_grid_pts],
                  physical_sizes=[float(s) for s in topo.physical_sizes],
                  periodic=bool(topo.is_periodic), surfacetopography=st.__version__, line_scan=topo.dim == 1)
    return Scan(topo.to_unit("m") if topo.unit != "m" else topo, source)


def _reader_words(e, limit=240):
    """The first line of a reader's exception, shortened: its own words, kept after ours."""
    lines = [ln.strip() for ln in str(e).strip().splitlines() if ln.strip()]
    text = lines[0] if lines else type(e).__name__
    return text if len(text) <= limit else text[:limit] + " ..."


def _formats():
    from SurfaceTopography.IO import lookup_reader_by_format
    return ", ".join(lookup_reader_by_format)


def read(path, format=None, channel=None, *, unit=None, physical_sizes=None, height_scale_factor=None,
         **reader_kwargs):
    """A `Scan` (heights [ix, iy] in metres) from any file SurfaceTopography reads (x3p, sdf, sur,
    datx, opd, plu, gwy, nc, Bruker, Keyence, ... and plain-text matrices; its
    `SurfaceTopography.IO.readers`): the format is found from the content unless `format` names
    it (e.g. 'x3p', 'asc'). `channel` picks a channel by index or name (default: the reader's
    default). `unit` (e.g. 'um') and `physical_sizes` (lx, ly in that unit) for files that do not
    say them, `height_scale_factor` (multiplies the heights) likewise; other keywords go to the
    reader's `topography()`. The file's matrix is [iy, ix] (rows along x), which the reader turns
    to [ix, iy]. What the reader cannot do is refused in one line (a ValueError) that names the
    keyword and the command line's option that would help (format= --format, channel= --channel,
    unit= --unit, physical_sizes= --size, height_scale_factor= --height-scale) and lists the
    file's channels, with the reader's own words last."""
    st = _st()
    from SurfaceTopography.Exceptions import CannotDetectFileFormat, MetadataAlreadyFixedByFile, UnknownFileFormat
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError("%s: no such file" % path)
    root = logging.getLogger()
    hush = None if root.handlers else logging.NullHandler()    # the readers tried and refused log their
    if hush is not None:                                        # reasons (logging's last resort: stderr)
        root.addHandler(hush)
    try:
        reader = st.open_topography(str(path), format=format)
    except UnknownFileFormat:
        raise ValueError("%s: SurfaceTopography has no format %r: format= (--format) takes one of %s"
                         % (path, format, _formats())) from None
    except CannotDetectFileFormat:
        raise ValueError("%s: SurfaceTopography cannot tell its format from its content (no reader takes it): "
                         "format= (--format) names it, one of %s" % (path, _formats())) from None
    except Exception as e:                    # an explicit format whose reader refused the file, or a damaged file
        raise ValueError("%s: SurfaceTopography cannot read it%s: %s"
                         % (path, " as %r: format= (--format) names another" % format if format else "",
                            _reader_words(e))) from None
    finally:
        if hush is not None:
            root.removeHandler(hush)
    channels = reader.channels
    names = [str(c.name) for c in channels]
    listing = "channels: " + ", ".join(names)
    if channel is None:
        index = reader.default_channel.index
    elif isinstance(channel, str):
        if channel not in names:
            raise ValueError("%s: no channel %r: channel= (--channel) takes a name or an index (%s)"
                             % (path, channel, listing))
        index = names.index(channel)
    else:
        index = int(channel)
        if not 0 <= index < len(channels):
            raise ValueError("%s: no channel %d: channel= (--channel) takes a name or an index 0 to %d (%s)"
                             % (path, index, len(channels) - 1, listing))
    ch = channels[index]
    line = getattr(ch, "dim", 2) == 1
    sides = "physical_sizes=(lx,) (--size LX)" if line else "physical_sizes=(lx, ly) (--size LX LY)"
    if physical_sizes is not None:
        physical_sizes = tuple(float(v) for v in np.atleast_1d(physical_sizes))
        if len(physical_sizes) != (1 if line else 2):
            raise ValueError("%s: channel %s is %s: %s, got %d numbers" % (
                path, names[index], "a line scan" if line else "a 2-D topography", sides, len(physical_sizes)))
    kwargs = dict(reader_kwargs, channel_index=index)
    for k, v in (("unit", unit), ("physical_sizes", physical_sizes),
                 ("height_scale_factor", height_scale_factor)):
        if v is not None:
            kwargs[k] = v
    need_size = physical_sizes is None and getattr(ch, "physical_sizes", None) is None
    need_unit = unit is None and getattr(ch, "unit", None) is None
    no_size = "the file gives no physical size: pass %s, in its unit" % sides
    no_unit = "the file gives no length unit: pass unit='um' (--unit um), or what it is"
    try:
        topo = reader.topography(**kwargs)
    except MetadataAlreadyFixedByFile as e:
        key = (re.search(r"keyword '(\w+)'", str(e)) or [None, "a keyword"])[1]
        option = {"unit": "--unit", "physical_sizes": "--size", "height_scale_factor": "--height-scale"}.get(key)
        raise ValueError("%s: the file gives its %s itself: leave out %s=%s (%s): %s"
                         % (path, key, key, " (%s)" % option if option else "", listing, _reader_words(e))) from None
    except Exception as e:
        if need_size and need_unit:
            what = ("the file gives neither its size nor its length unit: pass %s and unit='um' (--unit um), "
                    "or what they are" % sides)
        elif need_size or need_unit:
            what = no_size if need_size else no_unit
        else:
            what = ("SurfaceTopography cannot read channel %s (format= (--format) names the format if it is another, "
                    "channel= (--channel) another channel)" % names[index])
        raise ValueError("%s: %s (%s): %s" % (path, what, listing, _reader_words(e))) from None
    if topo.physical_sizes is None:
        raise ValueError("%s: %s (%s)" % (path, no_size, listing))
    if topo.unit is None:
        raise ValueError("%s: %s (%s)" % (path, no_unit, listing))
    info = topo.info or {}
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    source = {"path": str(path.resolve()), "sha256": digest.hexdigest(), "bytes": path.stat().st_size,
              "format": reader.format(), "reader": reader.name(),
              "channel": {"index": index, "name": names[index]},
              "reader_kwargs": {k: v for k, v in kwargs.items() if k != "channel_index"},
              "instrument": (info.get("instrument") or {}).get("name"),
              "acquisition_time": info.get("acquisition_time"),
              "matrix_layout": "the file's matrix [iy, ix] (rows along x), read as heights [ix, iy]",
              "channels": names, "unit_from": "given" if unit is not None else "file"}
    return _in_metres(topo, source)


def largest_measured_rectangle(valid):
    """The largest axis-aligned rectangle of True points in the mask `valid` [ix, iy] (1-D: a
    line): ((ix0, iy0), (mx, my)), the start and the size in points; ((0, 0), (0, 0)) when no
    point is True. Of several of the same size, the first found (rows ix in order). O(nx ny):
    for each row ix the column heights of the True runs ending there (a histogram), whose
    largest rectangle one pass with a stack finds."""
    v = np.asarray(valid, dtype=bool)
    if v.ndim == 1:
        v = v[:, None]
    if v.ndim != 2:
        raise ValueError("the mask must be 1-D or 2-D [ix, iy], got %d dimensions" % v.ndim)
    nx, ny = v.shape
    run = np.zeros(ny, dtype=np.int64)
    best_area, best = 0, ((0, 0), (0, 0))
    for ix in range(nx):
        run = np.where(v[ix], run + 1, 0)
        hist = run.tolist() + [0]
        stack = []                    # (first column, height), heights increasing
        for j, hj in enumerate(hist):
            start = j
            while stack and stack[-1][1] >= hj:
                s, hh = stack.pop()
                if hh * (j - s) > best_area:
                    best_area, best = hh * (j - s), ((ix - hh + 1, s), (hh, j - s))
                start = s
            stack.append((start, hj))
    return best


def _tukey(n, alpha):
    """The periodic (DFT-even) Tukey window of n points: 0 at index 0 only, a cosine taper over a
    fraction alpha of the period (alpha/2 each side of index 0), 1 elsewhere."""
    from scipy.signal.windows import tukey    # SurfaceTopography's dependency
    return tukey(n, alpha, sym=False)


def _edge_stats(h, hrms):
    """Rms over the rows (columns) of the jump between the last and first point along x (y), and
    the rms step between neighbours inside, in h_rms (as the solver measures them on reading)."""
    out = {}
    for axis, name in ((0, "x"), (1, "y")):
        if h.shape[axis] < 2:
            out["edge_jump_" + name] = out["edge_step_" + name] = 0.0
            continue
        first, last = np.take(h, 0, axis), np.take(h, -1, axis)
        out["edge_jump_" + name] = float(np.sqrt(np.mean((last - first) ** 2)) / hrms)
        out["edge_step_" + name] = float(np.sqrt(np.mean(np.diff(h, axis=axis) ** 2)) / hrms)
        out["edge_jump_max_" + name] = float(np.max(np.abs(last - first)) / hrms)
    return out


def _slope_variance(h, lx, ly, periodic):
    """<|grad h|^2> from forward differences: over the pairs inside the scan (periodic False) or
    over every pair of the periodic cell, the wrap-around ones included (periodic True)."""
    nx, ny = h.shape
    dx, dy = lx / nx, ly / ny
    if periodic:
        gx = (np.roll(h, -1, 0) - h) / dx
        gy = (np.roll(h, -1, 1) - h) / dy
    else:
        gx = np.diff(h, axis=0) / dx
        gy = np.diff(h, axis=1) / dy
    return float((np.mean(gx ** 2) if gx.size else 0.0) + (np.mean(gy ** 2) if gy.size else 0.0))


def _best_crop(h, axis, keep_min):
    """(start, length) along `axis`, length >= keep_min, whose next period's first row, the row at
    start + length, differs least in rms from its first: the periodic repetition of
    h[start:start+length] then steps from its last row to its first as the scan steps from that
    row to the next. Ties: the longest."""
    n = h.shape[axis]
    a = np.moveaxis(h, axis, 0)
    best = None
    for m in range(n - 1, min(keep_min, n - 1) - 1, -1):
        d = np.sqrt(np.mean((a[m:] - a[:n - m]) ** 2, axis=tuple(range(1, a.ndim))))   # start i: i+m - i
        i = int(np.argmin(d))
        if best is None or d[i] < best[0] * (1 - 1e-12):
            best = (float(d[i]), i, m)
    return best[1], best[2]


def _periodise(h, lx, ly, method, taper, detrended_topography):
    """(heights, lx, ly, record, costs) of the periodic cell made from the detrended scan h [ix, iy]."""
    nx, ny = h.shape
    rec = {"method": method}
    costs = {"area_fraction_changed": 0.0, "area_fraction_dropped": 0.0}
    if method == "tukey":
        if not 0 < taper <= 1:
            raise ValueError("taper must be in (0, 1] (the fraction of each side in the window's taper), got %r"
                             % taper)
        wx, wy = _tukey(nx, taper), _tukey(ny, taper)
        w = wx[:, None] * wy[None, :]
        out = h * w
        fx, fy = float(np.mean(wx < 1)), float(np.mean(wy < 1))
        rec.update(window="separable periodic Tukey w(ix) w(iy), scipy.signal.windows.tukey(n, taper, "
                          "sym=False): 0 at the first point, a cosine over taper/2 of each side at each edge",
                   taper=taper, tapered_fraction_x=fx, tapered_fraction_y=fy,
                   window_area_mean=float(np.mean(w)))
        costs["area_fraction_changed"] = float(np.mean(w < 1))        # = 1 - (1 - fx)(1 - fy)
    elif method == "mirror" and ny == 1:              # a line scan: the mirror image in x only
        out = np.concatenate([h, h[::-1]], axis=0)
        lx = 2 * lx
        rec.update(how="a line scan and its mirror image in x (as SurfaceTopography's mirror_stitch in x, which "
                       "takes no line scan), a cell of twice the length; the spectrum is that of an even profile",
                   taper=None)
        costs["area_fraction_changed"] = 0.5                           # the image
    elif method == "mirror":
        out = np.asarray(detrended_topography.mirror_stitch().heights(), dtype=np.float64)
        out = out - out.mean()                                         # as h: about the mean
        lx, ly = 2 * lx, 2 * ly
        rec.update(how="SurfaceTopography mirror_stitch: the scan and its mirror images in x, y and both, "
                       "a cell of twice the sides; the spectrum becomes symmetric in qx and qy (an "
                       "anisotropy at angle a becomes a cross at +-a)", taper=None)
        costs["area_fraction_changed"] = 0.75                          # the three images
    elif method == "crop":
        if not 0 < taper < 1:
            raise ValueError("taper must be in (0, 1) for crop (the largest fraction of each side cut), got %r"
                             % taper)
        kx, ky = max(2, int(np.ceil((1 - taper) * nx))), max(1, int(np.ceil((1 - taper) * ny)))
        j0, my = 0, ny
        for _ in range(2):      # x on the columns kept, then y on the rows kept; twice
            i0, mx = _best_crop(h[:, j0:j0 + my], 0, kx)
            j0, my = _best_crop(h[i0:i0 + mx], 1, ky) if ny > 1 else (0, 1)
        out = h[i0:i0 + mx, j0:j0 + my]
        rec.update(how="the sub-rectangle, at least (1 - taper) of each side, whose next period's first "
                       "row (column) differs least in rms from its first (x, then y, twice)", taper=taper, start=[i0, j0],
                   points=[mx, my], scan_points=[nx, ny])
        lx, ly = lx * mx / nx, ly * my / ny
        costs["area_fraction_dropped"] = 1.0 - mx * my / (nx * ny)
    elif method == "none":
        out = h
        rec.update(how="none: the scan is taken as periodic as it is", taper=None)
    else:
        raise ValueError("periodic must be one of %s, got %r" % (", ".join(PERIODIC_METHODS), method))
    return np.ascontiguousarray(out, dtype=np.float64), lx, ly, rec, costs


def _band_resample(h, lx, ly, nx, ny, k_cut):
    """Heights on an (nx, ny) grid over the same cell keeping the Fourier modes |q| <= k_cut q0
    (q0 = 2 pi / lx) of h [ix, iy], none on either grid's Nyquist lines, and not the mean. Only
    modes below both grids' Nyquist are copied, so nothing is aliased. Returns (g, record)."""
    sx, sy = h.shape
    q0x, q0y = 2 * np.pi / lx, 2 * np.pi / ly
    kx = np.rint(np.fft.fftfreq(sx, 1.0 / sx)).astype(int)
    ky = np.rint(np.fft.fftfreq(sy, 1.0 / sy)).astype(int)
    KX, KY = np.meshgrid(kx, ky, indexing="ij")
    q2 = (KX * q0x) ** 2 + (KY * q0y) ** 2
    H = np.fft.fft2(h)
    keep = q2 <= (k_cut * q0x) ** 2 * (1 + 1e-12)
    keep &= (2 * np.abs(KX) < min(sx, nx)) & (2 * np.abs(KY) < min(sy, ny))
    keep[0, 0] = False
    p = np.abs(H) ** 2
    p[0, 0] = 0.0
    total, total_slope = p.sum(), (p * q2).sum()
    G = np.zeros((nx, ny), dtype=complex)
    G[KX[keep] % nx, KY[keep] % ny] = H[keep]
    g = np.fft.ifft2(G) * (nx * ny) / (sx * sy)
    imag = float(np.abs(g.imag).max()) if g.size else 0.0
    g = np.ascontiguousarray(g.real)
    rec = {"k_cut": float(k_cut), "q_cut_per_m": float(k_cut * q0x), "wavelength_cut_m": float(lx / k_cut),
           "filter": "circular step: Fourier modes with |q| <= k_cut q0 (q0 = 2 pi/length_x_m) kept, the rest, "
                     "the mean and both grids' Nyquist lines set to zero, before the resampling",
           "resample": {"from": [sx, sy], "to": [nx, ny],
                        "method": "Fourier: the kept modes copied into the solve grid's spectrum (numpy fft2/ifft2)"},
           "modes_kept": int(keep.sum()), "imaginary_part_max_m": imag,
           "scan_nyquist_k": float(_nyquist_k(sx, sy, lx, ly)),
           "grid_nyquist_k": float(_nyquist_k(nx, ny, lx, ly))}
    kept = float(p[keep].sum())
    costs = {"band_height_variance_removed": float(1 - kept / total) if total > 0 else 0.0,
             "band_slope_variance_removed": float(1 - (p[keep] * q2[keep]).sum() / total_slope)
             if total_slope > 0 else 0.0}
    return g, rec, costs


def _nyquist_k(nx, ny, lx, ly):
    """The Nyquist of an (nx, ny) grid over lx x ly in q0 = 2 pi/lx (as prepare's k_cut check)."""
    return min(nx / 2, ny / 2 * lx / ly) if ny > 1 else nx / 2


def _half_slope_k(h, lx, ly):
    """(k, kept): the smallest k_cut (in q0 = 2 pi/lx) whose band keeps at least half of the slope
    variance of the cell h [ix, iy] (lx x ly), and the share kept by every mode below the cell's
    Nyquist lines (the most any band can keep); k None when that is below half."""
    sx, sy = h.shape
    kx = np.rint(np.fft.fftfreq(sx, 1.0 / sx))
    ky = np.rint(np.fft.fftfreq(sy, 1.0 / sy))
    KX, KY = np.meshgrid(kx, ky, indexing="ij")
    k2 = KX ** 2 + (KY * lx / ly) ** 2
    w = np.abs(np.fft.fft2(h)) ** 2 * k2          # the slope variance of each mode, in q0^2
    total = w.sum()
    if not total > 0:
        return None, 0.0
    eligible = (2 * np.abs(KX) < sx) & (2 * np.abs(KY) < sy)
    k = np.sqrt(k2[eligible])
    order = np.argsort(k, kind="stable")
    cum = np.cumsum(w[eligible][order])
    kept = float(cum[-1] / total)
    if kept < BAND_SLOPE_REMOVED_MAX:
        return None, kept
    return float(k[order][np.argmax(cum >= BAND_SLOPE_REMOVED_MAX * total * (1 - 1e-12))]), kept


def _fft_size(n):
    """The smallest even number >= n whose prime factors are 2, 3 and 5 (a fast FFT size)."""
    m = max(2, int(n) + int(n) % 2)
    while True:
        r = m
        for p in (2, 3, 5):
            while r % p == 0:
                r //= p
        if r == 1:
            return m
        m += 2


def _grid_for_k(k, lx, ly, line=False):
    """The smallest solve grid of a fast FFT size along x (ny from the aspect ratio, as prepare's)
    whose default k_cut, half its Nyquist, is at least k."""
    nx = _fft_size(np.ceil(4 * k * (1 - 1e-12)))
    while True:
        ny = 1 if line else max(1, int(round(nx * ly / lx)))
        if _nyquist_k(nx, ny, lx, ly) / 2 >= k * (1 - 1e-12):
            return nx, ny
        nx = _fft_size(nx + 1)


def _band_note(name, removed, k_cut, nx, ny, lx, ly, h1, line):
    """The text of the 'band-slope-removed' warning, and the record of what would keep half."""
    k_half, kept_max = _half_slope_k(h1, lx, ly)
    head = ("%s: the band (k_cut %.4g q0 on %s points) removes %.3g of the cell's slope variance, which the solve "
            "then lacks" % (name, k_cut, _points(nx, ny), removed))
    if k_half is None:
        return (head + ": the scan's own points cannot keep half of it (every mode below its Nyquist %.4g keeps %.3g)"
                % (_nyquist_k(*h1.shape, lx, ly), kept_max)), {"k_cut": None, "grid": None, "kept_max": kept_max}
    gx, gy = _grid_for_k(k_half, lx, ly, line)
    text = head + ": nx=%d (--nx %d) with its default k_cut %.4g (half its Nyquist) keeps at least half" % (
        gx, gx, _nyquist_k(gx, gy, lx, ly) / 2)
    if gx > h1.shape[0]:
        text += " (finer than the cell's %d points along x: interpolated)" % h1.shape[0]
    k_show = np.ceil(k_half * 1000) / 1000
    if k_show < _nyquist_k(nx, ny, lx, ly):
        text += ", as does k_cut=%.6g (--k-cut %.6g) on this grid" % (k_show, k_show)
    return text, {"k_cut": k_half, "grid": [gx, gy], "kept_max": kept_max}


class PreparedSurface:
    """A periodic surface made from a scan for `&surface kind='file'`: `heights` [ix, iy] [m] on
    the solve grid, `length_x_m`, `length_y_m`, `preparation` (a dict: every choice, also written
    to the file as JSON), `costs` (a dict of fractions and h_rms units, see `prepare`), `lines`
    (one line per choice, as the command line prints them), `detrended` and `periodised` (the
    scan's grid [ix, iy] after the detrending and after the periodisation), `warnings` (the
    VeslideWarnings `prepare` issued, as dicts: code, value, threshold, text), `write(path)`."""

    def __init__(self, heights, length_x_m, length_y_m, preparation, costs, lines, detrended, periodised):
        self.heights = heights
        self.length_x_m = length_x_m
        self.length_y_m = length_y_m
        self.preparation = preparation
        self.costs = costs
        self.lines = lines
        self.detrended = detrended
        self.periodised = periodised

    @property
    def warnings(self):
        return self.preparation.get("warnings", [])

    @property
    def nx(self):
        return self.heights.shape[0]

    @property
    def ny(self):
        return self.heights.shape[1]

    def write(self, path, dataset="/height_m", *, overwrite=False):
        """Write the heights for `&surface kind='file', file=path, dataset=dataset` with the
        attributes length_x_m, length_y_m, length_m (= length_x_m), preparation (JSON), and for
        the solver filled_fraction and band_slope_variance_removed (floats). A file that holds
        the dataset with bitwise the same heights and attributes is left as it is (a no-op; as
        `veslide.run` reuses an identical result); a different one is refused unless overwrite."""
        from .topography import write_topography
        return write_topography(path, self.heights, (self.length_x_m, self.length_y_m), dataset,
                                preparation=self.preparation, overwrite=overwrite)

    def __repr__(self):
        return "<PreparedSurface %d x %d, %.4g x %.4g m>" % (self.nx, self.ny, self.length_x_m, self.length_y_m)


def _grid(nx, ny, sx, sy, lx, ly, line=False):
    if line:
        if ny not in (None, 1):
            raise ValueError("a line scan makes a grid of ny = 1, got ny=%d (--ny %d)" % (ny, ny))
        ny = 1
        if nx is None:
            return sx, 1
    if nx is None and ny is None:
        return sx, sy
    if ny is None:
        ny = max(1, int(round(nx * ly / lx)))
    if nx is None:
        nx = max(2, int(round(ny * lx / ly)))
    nx, ny = int(nx), int(ny)
    if nx < 2 or ny < 1:
        raise ValueError("the solve grid must have nx >= 2 and ny >= 1, got %d x %d" % (nx, ny))
    return nx, ny


def _crop(topo, start, size, lx, ly):
    """The topography (in metres) of the sub-rectangle start, size [ix, iy] in points of topo."""
    st = _st()
    (i0, j0), (mx, my) = start, size
    nx, ny = topo.nb_grid_pts if topo.dim == 2 else (topo.nb_grid_pts[0], 1)
    h = np.ma.getdata(topo.heights())
    h = np.array(h[:, None] if h.ndim == 1 else h, dtype=np.float64)[i0:i0 + mx, j0:j0 + my]
    if topo.dim == 1:
        return st.UniformLineScan(h[:, 0], lx * mx / nx, unit="m", periodic=False)
    return st.Topography(h, (lx * mx / nx, ly * my / ny), unit="m", periodic=False)


def _points(nx, ny):
    return "%d" % nx if ny == 1 else "%d x %d" % (nx, ny)


def prepare(scan, nx=None, ny=None, detrend="curvature", periodic="tukey", taper=0.1, k_cut=None,
            fill="auto", crop_valid=False):
    """A `PreparedSurface` from a `Scan` (or a SurfaceTopography topography), in this order:

    1. units: metres (done by `read`; the factor is recorded).
    2. undefined points (NaN, the instrument's mask): with `crop_valid` the scan is cropped to the
       largest fully measured axis-aligned rectangle (`largest_measured_rectangle`; its start,
       size and share of the scan recorded), so none is left. Else `fill` -- 'auto' (default):
       up to FILL_MAX_AUTO (2 %) of the points filled by SurfaceTopography's
       `interpolate_undefined_data('harmonic')`, more refused (the refusal names the rectangle
       crop_valid would keep); 'harmonic': filled whatever their share, with a VeslideWarning
       'filled-scan' above 2 % (the filled heights are invented); None: any undefined point
       refused. Their count and the fraction filled are recorded.
    3. detrend: 'curvature' (the least-squares second-order polynomial), 'plane' (the least-squares
       plane) or 'none' (the mean only), by SurfaceTopography's `detrend`.
    4. periodic: how the scan becomes one periodic cell --
       'tukey': multiplied by a separable periodic Tukey window whose taper covers the fraction
       `taper` of each side (taper/2 at each edge), so the edges go to the mean;
       'mirror': the scan and its three mirror images, a cell of twice the sides;
       'crop': the sub-rectangle, keeping at least (1 - taper) of each side, whose next
       period's first row (column: the scan's row just past it) differs least from its first
       (x chosen, then y, twice), so that it repeats as the scan continues;
       'none': the scan is periodic already.
    5. band and grid: the modes |q| <= k_cut q0 kept (q0 = 2 pi / length_x_m of the cell, as
       &surface k_cut), copied to the (nx, ny) solve grid (default: the cell's own points; one of
       nx, ny given: the other from the cell's aspect ratio), so nothing above k_cut is kept and
       nothing is aliased. k_cut must lie below the solve grid's Nyquist,
       min(nx/2, ny/2 lx/ly); default: half of it (4 cells per shortest wavelength kept).
       When the band removes more than half of the cell's slope variance, a VeslideWarning
       'band-slope-removed' (value: the fraction removed, threshold 0.5) names the smallest k_cut
       that keeps half, from the cell's spectrum, and the grid (nx, a fast FFT size) whose default
       k_cut reaches it -- or says that no band on the scan's points keeps half (its slopes lie at
       its Nyquist). Recorded in preparation['band']['half_slope'].

    `costs`: area_fraction_changed (of the cell: the taper band, or the 3/4 of mirror images),
    area_fraction_dropped (of the scan, by a crop), slope_variance_change (relative change of
    <|grad h|^2> from the detrended scan, differences inside it, to the periodic cell, its wrap
    included), edge_jump_x/y_before/after (rms over the rows/columns of the jump between the last
    and first point, in h_rms of the detrended scan, as the solver measures them) with the rms
    steps inside (edge_step_x/y), band_height_variance_removed and band_slope_variance_removed (the
    fractions of the cell's height and slope variance above k_cut).

    A line scan (a profile along x, `Scan.line_scan`) goes through the same steps on heights of
    shape (nx, 1) -- 'mirror' adds its mirror image in x only -- onto a solve grid of ny = 1 whose
    length_y_m is its point spacing, length_x_m / nx (square cells; recorded, with the reason, in
    preparation['line_scan']). The solver takes it as h(x), the same along y: parallel ridges.

    Refused (ValueError, one line naming the options): more than 2 % undefined points unless
    `fill` or `crop_valid` says what to do; a prepared rms slope above SLOPE_REFUSED (10): heights
    in another unit or a channel that is not heights. Warned (VeslideWarning, source
    'preparation', also listed in preparation['warnings']): 'filled-scan', 'band-slope-removed'."""
    if not isinstance(scan, Scan):
        scan = _in_metres(scan, {"path": None, "format": "SurfaceTopography object",
                                 "reader": type(scan).__name__})
    if detrend not in DETREND_MODES:
        raise ValueError("detrend must be one of %s, got %r" % (", ".join(DETREND_MODES), detrend))
    if periodic not in PERIODIC_METHODS:
        raise ValueError("periodic must be one of %s, got %r" % (", ".join(PERIODIC_METHODS), periodic))
    if fill not in FILL_CHOICES:
        raise ValueError("fill must be 'auto', 'harmonic' or None, got %r" % (fill,))
    topo = scan.topography
    src = scan.source
    name = src.get("path") or "the scan"
    lines = []
    notes = []                # the warnings (text, code, value, threshold), issued once nothing is refused
    prep = {"format": "veslide measured topography preparation, version 1",
            "layouts": LAYOUTS, "source": _jsonable(src)}
    # 1. units
    prep["units"] = {"from": src.get("unit"), "factor_to_m": src.get("factor_to_m"),
                     "by": "SurfaceTopography to_unit('m')"}
    line_scan = scan.line_scan
    if line_scan:
        lines.append("read:      %s (%s, reader '%s', channel %s): a line scan of %d points, %.6g %s"
                     % (src.get("path") or "(in memory)", src.get("format"), src.get("reader"),
                        (src.get("channel") or {}).get("name", "-"), scan.nx,
                        *src.get("physical_sizes", [np.nan]), src.get("unit")))
    else:
        lines.append("read:      %s (%s, reader '%s', channel %s): %d x %d points, %.6g x %.6g %s"
                     % (src.get("path") or "(in memory)", src.get("format"), src.get("reader"),
                        (src.get("channel") or {}).get("name", "-"), scan.nx, scan.ny,
                        *src.get("physical_sizes", [np.nan, np.nan]), src.get("unit")))
    lines.append("units:     %s -> m, factor %.6g" % (src.get("unit"), src.get("factor_to_m")))
    # 2. undefined points
    sx, sy = scan.nx, scan.ny
    lx, ly = scan.length_x_m, scan.length_y_m
    n_undefined = int(np.ma.count_masked(topo.heights())) if topo.has_undefined_data else 0
    frac_undefined = n_undefined / (sx * sy)
    rect = None
    if crop_valid or (n_undefined and (fill != "auto" or frac_undefined > FILL_MAX_AUTO)):
        mask = np.ma.getmaskarray(topo.heights())
        start, size = largest_measured_rectangle(~(mask[:, None] if mask.ndim == 1 else mask))
        rect = {"start": [int(v) for v in start], "points": [int(v) for v in size],
                "fraction_kept": size[0] * size[1] / (sx * sy), "scan_points": [sx, sy]}
        offer = ("crop_valid=True (--crop-valid) keeps the largest measured rectangle (%s points, %.3g %% of the "
                 "scan)" % (_points(*size), 100 * rect["fraction_kept"])) if size[0] >= 2 else \
                "crop_valid=True (--crop-valid) finds no measured rectangle of 2 points along x"
    filled = 0
    if crop_valid:
        if rect["points"][0] < 2:
            raise ValueError("%s: %.3g %% of its %s points are unmeasured and no measured rectangle of 2 points "
                             "along x is left to crop to" % (name, 100 * frac_undefined, _points(sx, sy)))
        if n_undefined:
            topo = _crop(topo, rect["start"], rect["points"], lx, ly)
            sx, sy = rect["points"]
            lx, ly = lx * sx / scan.nx, ly * sy / scan.ny
    elif n_undefined:
        if fill is None:
            raise ValueError("%s: %d undefined points (%.3g %% of its %s points): fill='harmonic' (--fill harmonic) "
                             "fills them, or %s" % (name, n_undefined, 100 * frac_undefined, _points(sx, sy), offer))
        if fill == "auto" and frac_undefined > FILL_MAX_AUTO:
            raise ValueError("%s: %.3g %% of its %s points are unmeasured: %s, or fill='harmonic' (--fill harmonic) "
                             "fills them (the filled heights are invented)"
                             % (name, 100 * frac_undefined, _points(sx, sy), offer))
        topo = topo.interpolate_undefined_data("harmonic")
        filled = n_undefined
        if frac_undefined > FILL_MAX_AUTO:
            notes.append(("%s: %.3g %% of its %s points were unmeasured and are filled by harmonic interpolation "
                          "(the filled heights are invented; %s)"
                          % (name, 100 * frac_undefined, _points(scan.nx, scan.ny), offer),
                          "filled-scan", frac_undefined, FILL_MAX_AUTO))
    prep["undefined_points"] = {"count": n_undefined, "fraction": frac_undefined,
                                "filled_by": "SurfaceTopography interpolate_undefined_data('harmonic')"
                                if filled else None,
                                "fill": fill, "fill_max_auto": FILL_MAX_AUTO,
                                "filled_fraction": filled / (scan.nx * scan.ny),
                                "crop_valid": bool(crop_valid), "measured_rectangle": rect if crop_valid else None}
    line = "undefined: %d points (%.3g of the area)" % (n_undefined, frac_undefined)
    if filled:
        line += ", filled by interpolate_undefined_data('harmonic')"
    elif crop_valid and n_undefined:
        line += ": cropped to the largest measured rectangle, %s points from [%d, %d] (%.3g of the scan), " \
                "%.6g x %.6g m" % (_points(sx, sy), rect["start"][0], rect["start"][1], rect["fraction_kept"], lx, ly)
    lines.append(line)
    # 3. detrend
    raw = np.asarray(topo.heights(), dtype=np.float64).reshape(sx, sy)
    d = topo.detrend(detrend_mode=DETREND_MODES[detrend])
    h0 = np.ascontiguousarray(np.asarray(d.heights(), dtype=np.float64).reshape(sx, sy))
    h0 = h0 - h0.mean()
    removed = raw - raw.mean() - h0
    hrms = float(np.sqrt(np.mean(h0 ** 2)))
    if not hrms > 0:
        raise ValueError("%s: the detrended scan is flat (h_rms = 0)" % (src.get("path") or "the scan"))
    prep["detrend"] = {"mode": detrend, "surfacetopography_mode": DETREND_MODES[detrend],
                       "coefficients": _jsonable(d.coeffs),
                       "coefficients_note": "SurfaceTopography polyfit order, in its units (m) and normalised "
                                            "coordinates x = ix/nx, y = iy/ny",
                       "rms_removed_m": float(np.sqrt(np.mean(removed ** 2))), "h_rms_after_m": hrms}
    lines.append("detrend:   %s (SurfaceTopography '%s'): removed %.4g m rms, h_rms %.4g m"
                 % (detrend, DETREND_MODES[detrend], prep["detrend"]["rms_removed_m"], hrms))
    # 4. periodic
    h1, lx1, ly1, rec, costs = _periodise(h0, lx, ly, periodic, taper, d)
    before, after = _edge_stats(h0, hrms), _edge_stats(h1, hrms)
    for k, v in before.items():
        costs[k + "_before"] = v
    for k, v in after.items():
        costs[k + "_after"] = v
    m2_scan, m2_cell = _slope_variance(h0, lx, ly, False), _slope_variance(h1, lx1, ly1, True)
    costs["slope_variance_change"] = m2_cell / m2_scan - 1 if m2_scan > 0 else 0.0
    rec.update(points=[int(n) for n in h1.shape], length_m=[lx1, ly1])
    prep["periodic"] = rec
    what = {"tukey": "Tukey taper %.3g" % taper,
            "mirror": "mirror image in x (cell twice the scan)" if line_scan else
                      "mirror stitching (cell 2 x 2 the scan)",
            "crop": "crop to %d x %d points (at least %.3g of each side)" % (h1.shape + (1 - taper,)),
            "none": "none (taken as periodic)"}[periodic]
    lines.append("periodic:  %s: area changed %.4f, dropped %.4f, slope variance %+.4f; edge jump x %.3g -> %.3g, "
                 "y %.3g -> %.3g h_rms (steps inside %.3g, %.3g)"
                 % (what, costs["area_fraction_changed"], costs["area_fraction_dropped"],
                    costs["slope_variance_change"], costs["edge_jump_x_before"], costs["edge_jump_x_after"],
                    costs["edge_jump_y_before"], costs["edge_jump_y_after"], costs["edge_step_x_after"],
                    costs["edge_step_y_after"]))
    # 5. band and grid
    nx_, ny_ = _grid(nx, ny, h1.shape[0], h1.shape[1], lx1, ly1, line_scan)
    nyq = _nyquist_k(nx_, ny_, lx1, ly1)
    if k_cut is None:
        k_cut = nyq / 2
        k_note = "default: half the grid's Nyquist"
    else:
        k_note = "given"
    k_cut = float(k_cut)
    if not (1 <= k_cut < nyq):
        raise ValueError("k_cut must be >= 1 and below the solve grid's Nyquist %.6g (in q0 = 2 pi/length_x_m "
                         "of the cell, %d x %d points over %.6g x %.6g m), got %.6g" % (nyq, nx_, ny_, lx1, ly1, k_cut))
    g, band, bcosts = _band_resample(h1, lx1, ly1, nx_, ny_, k_cut)
    band["k_cut_source"] = k_note
    costs.update(bcosts)
    prep["band"] = band
    if k_cut > band["scan_nyquist_k"]:
        band["note"] = "k_cut above the cell's own Nyquist %.6g: the scan has no modes there" % band["scan_nyquist_k"]
    lines.append("band:      k_cut %.6g q0 (%s; wavelength %.4g m, grid Nyquist %.6g): removed %.4f of the height "
                 "variance, %.4f of the slope variance%s"
                 % (k_cut, k_note, band["wavelength_cut_m"], band["grid_nyquist_k"],
                    costs["band_height_variance_removed"], costs["band_slope_variance_removed"],
                    "; " + band["note"] if "note" in band else ""))
    if line_scan:             # y: one point of the solve grid's spacing, square cells
        ly_out = lx1 / nx_
        prep["line_scan"] = {
            "length_y_m": ly_out,
            "why": "a line scan has no y side: the solve grid has ny = 1 (heights h(x), the same along y: parallel "
                   "ridges, plane strain) and length_y_m is its point spacing length_x_m / nx, so that its cells "
                   "are square; the y side enters no result per area (no wavevector has qy != 0)"}
        lines.append("resample:  %d -> %d points (Fourier), cell %.6g m; a line scan: ny = 1, length_y_m %.6g m "
                     "(the grid's spacing: square cells)" % (h1.shape[0], nx_, lx1, ly_out))
    else:
        ly_out = ly1
        prep["line_scan"] = None
        lines.append("resample:  %d x %d -> %d x %d points (Fourier), cell %.6g x %.6g m"
                     % (h1.shape[0], h1.shape[1], nx_, ny_, lx1, ly1))
    removed = costs["band_slope_variance_removed"]
    band["half_slope"] = None
    if removed > BAND_SLOPE_REMOVED_MAX:
        text, band["half_slope"] = _band_note(name, removed, k_cut, nx_, ny_, lx1, ly1, h1, line_scan)
        notes.append((text, "band-slope-removed", removed, BAND_SLOPE_REMOVED_MAX))
    hr = float(np.sqrt(np.mean(g ** 2)))
    gx = np.fft.fftfreq(nx_, lx1 / nx_) * 2 * np.pi
    gy = np.fft.fftfreq(ny_, ly1 / ny_) * 2 * np.pi
    GQ = np.abs(np.fft.fft2(g) / g.size) ** 2
    slope = float(np.sqrt((GQ * (gx[:, None] ** 2 + gy[None, :] ** 2)).sum()))
    if not slope <= SLOPE_REFUSED:
        unit_fix = ("height_scale_factor= (--height-scale) rescales them, the file giving its unit %s"
                    % src.get("unit") if src.get("unit_from") == "file" else
                    "unit= (--unit), or height_scale_factor= (--height-scale) for the heights alone")
        what = ("a channel that is not heights (channel= (--channel); channels: %s)" % ", ".join(src["channels"])
                if src.get("channels") else "an array that is not heights")
        raise ValueError("%s: the rms slope of the heights is %s (a contact of small slopes needs well below 1): "
                         "heights in another unit (%s), or %s"
                         % (name, ("%.2g" % slope).replace("e+0", "e").replace("e+", "e"), unit_fix, what))
    prep["result"] = {"nx": nx_, "ny": ny_, "length_x_m": lx1, "length_y_m": ly_out, "h_rms_m": hr,
                      "rms_slope": slope, "layout": LAYOUTS["numpy (this package, SurfaceTopography)"]}
    prep["costs"] = costs
    prep["costs_note"] = ("area_fraction_changed: of the cell (taper band; mirror images); area_fraction_dropped: "
                          "of the scan (crop); slope_variance_change: relative change of <|grad h|^2> by the "
                          "periodisation (forward differences inside the scan, then over the periodic cell); "
                          "edge_jump_*: rms over the lines of last minus first point, in h_rms of the detrended "
                          "scan; band_*: fractions of the cell's variance above k_cut")
    try:
        from . import __version__ as version
    except ImportError:       # pragma: no cover
        version = None
    prep["veslide_python"] = version
    lines.append("surface:   h_rms %.4g m, rms slope %.4g" % (hr, slope))
    prep["warnings"] = [{"code": c, "value": v, "threshold": t, "text": x} for x, c, v, t in notes]
    for text, code, value, threshold in notes:
        warn(text, code, value, threshold, source="preparation", stacklevel=2)
    return PreparedSurface(g, lx1, ly_out, _jsonable(prep), costs, lines, h0, h1)
