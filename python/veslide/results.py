"""Reading veslide results: a single case, a study, or a study still being written."""
import io
import shutil
from collections.abc import Mapping
from pathlib import Path

import f90nml
import h5py
import numpy as np
import pandas as pd
import xarray as xr

from ._h5 import open_file, published_name, python_value, retry, text, writer_alive
from ._warning import VeslideWarning

#: The parameter columns that lead a study's /summary, for files written before the program named
#: them (veslide < 0.2.0); newer files name them in the attribute `parameters` of /summary and
#: /ensemble (read by `parameter_columns`)
LEGACY_PARAMETERS = ("case", "seed", "eccentricity", "alpha_deg", "pressure_pa", "speed_m_s", "temperature_c")
_LONG_NAMES = {"height_m": "height h", "pressure_pa": "pressure p", "displacement_m": "displacement w",
               "gap_m": "gap g"}


class Scalars(dict):
    """The scalars of a case: name -> value (int or float), with `.units` (name -> unit string) and
    `.attrs` (the attributes of the group, e.g. solver_method, kernel_variant)."""

    def __init__(self, values=(), units=None, attrs=None):
        super().__init__(values)
        self.units = dict(units or {})
        self.attrs = dict(attrs or {})


class Arrays(dict):
    """The datasets of a group (/anisotropy, /patches, /persson): name -> numpy array, with
    `.units` and `.attrs` (name -> that dataset's other attributes, e.g. layout)."""

    def __init__(self, values=(), units=None, attrs=None):
        super().__init__(values)
        self.units = dict(units or {})
        self.attrs = dict(attrs or {})


def _group_values(g, cls):
    values, units, attrs = {}, {}, {}
    for name, ds in g.items():
        if not hasattr(ds, "dtype"):
            continue
        values[name] = python_value(ds[()])
        a = {k: python_value(v) for k, v in ds.attrs.items()}
        units[name] = a.pop("units", "")
        if a:
            attrs[name] = a
    out = cls(values, units)
    out.attrs = attrs if cls is Arrays else {k: python_value(v) for k, v in g.attrs.items()}
    return out


def _table(ds):
    """A compound table (/summary, /ensemble) as a DataFrame; int64 columns stay int64, the
    `units` attribute goes to df.attrs['units'] (column -> unit)."""
    data = ds[()]
    names = data.dtype.names
    df = pd.DataFrame({n: np.asarray(data[n]) for n in names}, columns=list(names))
    units = [text(u) for u in np.atleast_1d(ds.attrs.get("units", []))]
    df.attrs["units"] = dict(zip(names, units)) if len(units) == len(names) else {}
    # the columns that identify a case (the study's parameters), as the program names them
    if "parameters" in ds.attrs:
        df.attrs["parameters"] = [text(p) for p in np.atleast_1d(ds.attrs["parameters"])]
    # /paths: 'load' or 'approach' (the control of the study's load paths)
    if "control" in ds.attrs:
        df.attrs["control"] = text(ds.attrs["control"])
    return df


#: Quantities that are axes (angles modulo pi) and the range of their mean over seeds, as the
#: program's /ensemble averages them (veslide_quantities' axial_of)
AXIAL = {"theta_s_rad": "0..pi", "theta_d_rad": "0..pi", "patch_theta_rad": "0..pi", "phi_rad": "-pi/2..pi/2"}


def seed_statistics(x, name=""):
    """Mean, standard error of the mean, min and max of the values `x` of quantity `name` over
    seeds, by the rule of the program's /ensemble: axes (AXIAL names) by the circular mean of the
    doubled angle, deviations wrapped into (-pi/2, pi/2] (an axis scattering about 0 = pi averages
    to 0, not pi/2); min and max are of the samples unwrapped about that mean. One seed: sem 0."""
    x = np.asarray(x, float)
    n = len(x)
    if name in AXIAL:
        m = 0.5 * np.arctan2(np.sin(2 * x).sum(), np.cos(2 * x).sum())
        if AXIAL[name] == "0..pi":
            m = m % np.pi
        d = x - m
        d = d - np.pi * np.round(d / np.pi)
    else:
        m = x.sum() / n
        d = x - m
    se = np.sqrt((d ** 2).sum() / max(1, n - 1)) / np.sqrt(n)
    return m, se, (m + d).min(), (m + d).max()


def parameter_columns(table):
    """The columns of a study's table (/summary or /ensemble DataFrame) that identify a case, as
    the program names them (its `parameters` attribute); for older files, those of
    LEGACY_PARAMETERS that the table has."""
    named = table.attrs.get("parameters")
    if named:
        return list(named)
    return [p for p in LEGACY_PARAMETERS if p in table.columns]


def _warnings_of(g, case=None):
    """The warnings a group's /warnings holds (veslide_case_file's write_warnings), as
    VeslideWarning objects in the order written; [] for files before version 0.4.0."""
    if "warnings" not in g:
        return []
    w = g["warnings"]
    columns = {k: np.atleast_1d(w[k][()]) for k in ("code", "source", "text", "value", "threshold") if k in w}
    n = len(columns.get("code", []))
    out = []
    for i in range(n):
        value, threshold = float(columns["value"][i]), float(columns["threshold"][i])
        source = text(columns["source"][i])
        out.append(VeslideWarning(text(columns["text"][i]), text(columns["code"][i]),
                                  value if (value or threshold) else None, threshold if (value or threshold) else None,
                                  case=case, source=source))
    return out


def _fields(g, scalars):
    """/fields as an xarray Dataset with dims (x, y): values[ix, iy], coordinates in metres."""
    names = list(g)          # what the program's field catalogue wrote (veslide_quantities)
    first = g[names[0]]
    ny, nx = first.shape
    lx = scalars.get("length_x_m", 1.0)
    ly = scalars.get("length_y_m", lx * ny / nx)
    coords = {"x": ("x", np.arange(nx) * (lx / nx), {"units": "m", "long_name": "x"}),
              "y": ("y", np.arange(ny) * (ly / ny), {"units": "m", "long_name": "y"})}
    data = {}
    for n in names:
        ds = g[n]
        attrs = {"units": text(ds.attrs.get("units", "")), "long_name": _LONG_NAMES.get(n, n)}
        data[n] = (("x", "y"), np.ascontiguousarray(ds[()].T), attrs)   # file [iy, ix] -> [ix, iy]
    return xr.Dataset(data, coords=coords, attrs={"length_x_m": lx, "length_y_m": ly, "nx": nx, "ny": ny})


class Cases(Mapping):
    """A study's cases, read when first asked for: case number -> Result of /cases/NNNNNN."""

    def __init__(self, parent, numbers):
        self._parent = parent
        self._numbers = list(numbers)
        self._cache = {}

    def __getitem__(self, k):
        k = int(k)
        if k not in self._numbers:
            raise KeyError(k)
        if k not in self._cache:
            self._cache[k] = Result(self._parent.path, group="/cases/%06d" % k, parent=self._parent,
                                    image=self._parent._image)
        return self._cache[k]

    def __iter__(self):
        return iter(self._numbers)

    def __len__(self):
        return len(self._numbers)

    def __repr__(self):
        if not self._numbers:
            return "Cases()"
        return "Cases(%d: %d..%d)" % (len(self._numbers), self._numbers[0], self._numbers[-1])


class Result:
    """A veslide result file (or one case group of a study), read with `veslide.read`.

    Attributes read at once: `scalars`, `summary`, `ensemble`, `paths` (a load path study's
    /paths: each path's jumps, pull-off and patches made, lost and bistable, docs/adhesion.md; None
    otherwise), `input`, `input_text`,
    `provenance`, `anisotropy`, `patches`, `persson`, `parameters`, `validity` (the validity
    measures of a case, /validity: values, `.units`, `.attrs` with each threshold and when it
    warns; `validity_table` as a DataFrame); read when first used: `fields`, `cases`,
    `warnings` (a list of `veslide.VeslideWarning`). `partial` is True for a part file OUT.part (a study being written or
    interrupted), `running` when its writer was alive at reading time. `returncode`, `log` and
    `stderr` are set by `veslide.run`, `reused` when it read an earlier run's file instead.

    `in_memory`: the whole file was read into memory (`veslide.read(path, memory=True)`, or a
    `veslide.run` that asked for no file: its `path` is then None); `save(path)` writes it."""

    def __init__(self, path, group="/", parent=None, *, image=None):
        self.group = group
        self.parent = parent
        self._image = image
        self.returncode = None
        self.log = None
        self.stderr = None
        self.reused = False
        self._attach(path)

    def _attach(self, path):
        """(Re)read everything from `path` (or from the image in memory)."""
        self.path = Path(path) if path is not None else None
        final = published_name(self.path) if self._image is None else None
        self.partial = final is not None
        self.running = self.partial and writer_alive(final)
        self._fields = None
        self._cases = None
        retry(self._load, self.partial)

    @property
    def in_memory(self):
        """The file's bytes are held in memory (no file is read again)."""
        return self._image is not None

    # -- reading -----------------------------------------------------------------------------
    def _open(self):
        """The file, or, for a part file published meanwhile, the published one (the same data:
        publication links the part file under its final name)."""
        if self._image is not None:
            return h5py.File(io.BytesIO(self._image), "r")
        if not self.path.exists() and self.partial:
            final = published_name(self.path)
            if final is not None and final.exists():
                return open_file(final)
        return open_file(self.path)

    def _load(self):
        with self._open() as f:
            if self.group not in f:
                raise KeyError("%s: no group %s" % (self.path, self.group))
            g = f[self.group]
            self.scalars = _group_values(g["scalars"], Scalars) if "scalars" in g else None
            self.anisotropy = _group_values(g["anisotropy"], Arrays) if "anisotropy" in g else None
            self.patches = _group_values(g["patches"], Arrays) if "patches" in g else None
            self.persson = _group_values(g["persson"], Arrays) if "persson" in g else None
            self.validity = _group_values(g["validity"], Arrays) if "validity" in g else None
            self._own_warnings = _warnings_of(g, self._case_number())
            self._warnings = None
            self.has_fields = "fields" in g and len(g["fields"]) > 0
            self.parameters = None
            if "parameters" in g:
                p = g["parameters"]
                cols = [c.strip() for c in text(p.attrs.get("columns", "")).split(",")]
                vals = p[()]
                self.parameters = {c: (int(v) if c in ("case", "seed") else float(v)) for c, v in zip(cols, vals)}
            self.summary = _table(g["summary"]) if "summary" in g else None
            self.ensemble = _table(g["ensemble"]) if "ensemble" in g else None
            self.paths = _table(g["paths"]) if "paths" in g else None
            numbers = sorted(int(k) for k in g["cases"]) if "cases" in g else []
            if self.partial and self.summary is not None:
                done = set(int(c) for c in self.summary["case"])   # a row is written after its case
                numbers = [k for k in numbers if k in done]
            elif self.partial:
                numbers = []
            self._case_numbers = numbers
            self.is_study = "summary" in g or "cases" in g or (self.group == "/" and "seeds" in f.attrs)
            if self.parent is None:
                self.provenance = {k: python_value(v) for k, v in f.attrs.items()}
                self.input_text = text(f["input/namelist"][()]) if "input/namelist" in f else None
            else:
                self.provenance = self.parent.provenance
                self.input_text = self.parent.input_text
        self.input = f90nml.reads(self.input_text) if self.input_text is not None else None

    @property
    def fields(self):
        """The 2-D fields as an xarray Dataset (dims x, y; coordinates in metres; `units`
        attributes), or None when the run wrote no fields. Values are indexed [ix, iy]:
        `fields.pressure_pa.sel(x=..., y=...)`, `fields.height_m.values[ix, iy]`."""
        if not self.has_fields:
            return None
        if self._fields is None:
            def load():
                with self._open() as f:
                    return _fields(f[self.group]["fields"], self.scalars or {})
            self._fields = retry(load, self.partial)
        return self._fields

    def _case_number(self):
        return int(self.group.rsplit("/", 1)[-1]) if self.group.startswith("/cases/") else None

    @property
    def warnings(self):
        """What the program found questionable, as `veslide.VeslideWarning` objects (attributes
        code, value, threshold, text, case, source; docs/validity.md lists the codes). A case: its
        input's warnings and its own. A study: its input's warnings, then every case's own (each
        with `case`), read when first asked for. [] for files before version 0.4.0."""
        if self._warnings is None:
            out = list(self._own_warnings)
            if self.is_study and self.summary is not None and "warnings" in self.summary:
                n_input = len(out)
                flagged = [int(c) for c, n in zip(self.summary["case"], self.summary["warnings"]) if n > n_input]

                def load():
                    found = []
                    with self._open() as f:
                        for k in flagged:
                            g = f[self.group.rstrip("/") + "/cases/%06d" % k]
                            found += [w for w in _warnings_of(g, k) if w.source != "input"]
                    return found
                out += retry(load, self.partial)
            self._warnings = out
        return list(self._warnings)

    @property
    def validity_table(self):
        """The validity measures as a DataFrame indexed by name: value, units, threshold, warns
        ('above', 'below' or 'never') and past (the value is past its threshold). A case only
        (a study's measures are columns of its `summary`); None for files before 0.4.0."""
        if self.validity is None:
            return None
        rows = []
        for name, value in self.validity.items():
            a = self.validity.attrs.get(name, {})
            warns, thr = a.get("warns", "never"), a.get("threshold")
            past = (warns == "above" and value > thr) or (warns == "below" and value < thr)
            rows.append({"name": name, "value": value, "units": self.validity.units.get(name, ""),
                         "threshold": thr, "warns": warns, "past": bool(past)})
        return pd.DataFrame(rows).set_index("name")

    @property
    def cases(self):
        """A study's cases: a mapping case number (1-based, as /summary's `case`) -> Result,
        each read when first accessed. Empty for a single case."""
        if self._cases is None:
            self._cases = Cases(self, self._case_numbers)
        return self._cases

    # -- convenience -------------------------------------------------------------------------
    @property
    def converged(self):
        """A case: /scalars/converged == 1. A study: every /summary row converged (None before
        the first row of a running study)."""
        if self.scalars is not None and "converged" in self.scalars:
            return bool(self.scalars["converged"])
        if self.summary is not None and len(self.summary):
            return bool((self.summary["converged"] == 1).all())
        return None

    @property
    def residual(self):
        """A case: its final residual. A study: the largest over its cases."""
        if self.scalars is not None and "residual" in self.scalars:
            return self.scalars["residual"]
        if self.summary is not None and len(self.summary):
            return float(self.summary["residual"].max())
        return None

    def refresh(self):
        """Read the file again, into this object, and return it (for a running study: the rows
        and cases written since; once it is published, the published file). A case of a study
        refreshes its study too. A result in memory has nothing to re-read."""
        if self._image is not None:
            return self
        if self.parent is not None:
            self.parent.refresh()
            self._attach(self.parent.path)
            return self
        path = self.path
        if self.partial and not path.exists():
            final = published_name(path)
            if final is not None and final.exists():
                path = final
        self._attach(path)
        return self

    def save(self, path):
        """Write the whole file (a study's, for one of its cases) to `path`, e.g. a result that
        `veslide.run` kept in memory; returns the path. An existing file is not replaced."""
        root = self.parent if self.parent is not None else self
        path = Path(path)
        with open(path, "xb") as out:
            if root._image is not None:
                out.write(root._image)
            else:
                with open(root.path, "rb") as src:
                    shutil.copyfileobj(src, out)
        return path

    def __repr__(self):
        what = "study" if self.is_study else "case"
        where = "in memory" if self.path is None else self.path
        bits = ["%s %s%s" % (what, where, "" if self.group == "/" else ":" + self.group)]
        if self.partial:
            bits.append("partial (writer %s)" % ("running" if self.running else "gone"))
        if self.summary is not None:
            bits.append("%d rows" % len(self.summary))
        if self.scalars is not None:
            for k in ("contact_area_fraction", "friction_coefficient"):
                if k in self.scalars:
                    bits.append("%s=%.6g" % (k, self.scalars[k]))
        if self.converged is False:
            bits.append("NOT CONVERGED (residual %.3g)" % self.residual)
        return "<veslide.Result %s>" % ", ".join(bits)


def read(path, memory=False):
    """Read a veslide HDF5 result (a case, a study, or a part file OUT.part of a study that
    is running or was interrupted) into a `Result`. `memory=True` reads the whole file into
    memory first: the Result needs the file no more (it may be removed or replaced)."""
    path = Path(path)
    if memory and path.exists():
        return Result(path, image=path.read_bytes())
    if not path.exists():
        parts = _part_files(path)
        hint = (" (a running study writes %s: use veslide.read_running(%r))" % (parts[-1].name, str(path))
                if parts else "")
        raise FileNotFoundError("%s: no such file%s" % (path, hint))
    return Result(path)


def _part_files(path):
    part = Path(str(path) + ".part")
    return [part] if part.exists() else []


def read_running(path):
    """Read a study that may still be running: `path` is its final name OUT (as in &output file
    or --output). Reads OUT.part while the study runs (or after it was interrupted: the same
    command resumes it), and OUT once it has been published. The Result has `partial` (read from
    the part file) and `running` (a veslide run holds OUT.lock); `refresh()` re-reads."""
    path = Path(path)
    if published_name(path) is not None:
        return read(path)
    for p in _part_files(path):
        try:
            return Result(p)
        except FileNotFoundError:    # published (or removed) between the listing and the read
            pass
    if path.exists():
        return Result(path)
    raise FileNotFoundError("%s: no such file and no %s.part" % (path, path.name))
