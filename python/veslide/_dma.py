"""From a DMA instrument's export to a master curve: `read_dma` reads the isothermal sweeps of an
export (CSV, TSV or Excel), `master_curve` finds the horizontal (and optionally vertical) shift
factors from the overlap of neighbouring sweeps and returns a `MasterCurve`, whose shift factors
take WLF or Arrhenius fits (`ShiftFit`) and whose data take a Prony fit. Used through
`veslide.material` (read_dma, master_curve, MasterCurve, ShiftFit, SAMPLE_DMA, DmaError) and
`python -m veslide material`."""
import csv
import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from ._warning import warn

#: the DMA export shipped with the package: sweeps of a known solid (veslide/_dma_sample.py)
SAMPLE_DMA = str(Path(__file__).resolve().parent / "data" / "dma-sample.csv")

ROLES = ("frequency", "storage", "loss", "temperature")
_WHAT = {"frequency": "the frequency", "storage": "the storage modulus E'", "loss": "the loss modulus E''",
         "temperature": "the temperature", "sweep": "the sweep number"}
_UNIT_HINT = {"frequency": "'Hz' or 'rad/s'", "storage": "'Pa', 'kPa', 'MPa' or 'GPa'",
              "loss": "'Pa', 'kPa', 'MPa' or 'GPa'", "temperature": "'C' or 'K'"}
_EXAMPLE_UNIT = {"frequency": "Hz", "storage": "MPa", "loss": "MPa", "temperature": "C"}
# units: (role kind, factor to SI, offset) -- SI: Hz, Pa, degC
_MODULUS_UNITS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/mm2": 1e6, "n/mm^2": 1e6, "n/m2": 1.0,
                  "n/m^2": 1.0, "psi": 6894.757293168361, "ksi": 6894757.293168361}
_FREQUENCY_UNITS = {"hz": 1.0, "1/s(hz)": 1.0, "khz": 1e3, "mhz": 1e6, "rad/s": 1.0 / (2 * math.pi),
                    "rad s-1": 1.0 / (2 * math.pi), "rad/sec": 1.0 / (2 * math.pi)}
_TEMPERATURE_UNITS = {"c": ("c", 0.0), "degc": ("c", 0.0), "celsius": ("c", 0.0), "k": ("k", -273.15),
                      "kelvin": ("k", -273.15), "f": ("f", 0.0), "degf": ("f", 0.0)}
# words that are no unit (a units row may hold them under unitless columns)
_NO_UNIT = {"", "-", "--", "1", "%", "()", "[]", "n/a", "na"}


class DmaError(ValueError):
    """A DMA table the package refuses to read or shift, with one line saying why and what to pass."""


# ---------------------------------------------------------------- reading an export


def read_dma(path, *, columns=None, units=None, sheet=0, drop_bad=False, sweep_tolerance_k=1.0, encoding=None,
             delimiter=None, decimal=None):
    """Read an instrument's export of isothermal frequency sweeps: a pandas DataFrame with one
    row per point and the columns `frequency_hz`, `storage_pa`, `loss_pa` (the moduli as given:
    Young's, or shear when the columns are G', G''; `attrs['shear']` says which),
    `temperature_c`, `sweep` (0, 1, ... in the file's order) and `line` (the point's line in the
    file, 1-based, or its row in the sheet).

    The file: CSV, TSV or semicolon-separated text (decimal commas too), or Excel (.xlsx,
    .xlsm; the sheet `sheet`, by index or name), in UTF-8 with or without a byte-order mark
    (UTF-16 with one, else Windows-1252 as a last resort). Lines of metadata above the table are
    skipped: the table is the header row above the first row of numbers, with an optional row
    of units between them. Columns in any order are found by their names (frequency: f, freq,
    frequency, Frequenz, omega/w in rad/s; E' or G': storage, E', E1, Storage modulus; E'':
    loss, E'', E", E2, Loss modulus; temperature: T, Temp, Temperature; an optional sweep or
    segment number), or given as `columns={'frequency': name or 0-based index, 'storage': ...,
    'loss': ..., 'temperature': ..., 'sweep': ...}`.

    Units come from the units row, else from the name ('E' [MPa]', 'f (Hz)', 'T/degC',
    'E' in MPa'), else from `units={'storage': 'MPa', ...}` (which wins over both): moduli in
    Pa, kPa, MPa, GPa (N/mm2, psi, ksi), frequency in Hz, kHz or rad/s, temperature in C, K or F.
    A column without a unit, or with one that is not of its kind, is refused with one line that
    says what to pass; so are a missing column and two columns that fit one role.

    Bad points (a frequency or a modulus that is zero, negative or not a number, a temperature
    that is not a number) are named by their line, frequency and temperature: refused by
    default (a DmaError listing them), dropped with `drop_bad=True`, which warns
    (`dma-dropped-points`, a VeslideWarning) naming each; `attrs['dropped']` holds them.

    Sweeps: the `sweep` column when the file has one, else a new sweep wherever the temperature
    moves more than `sweep_tolerance_k` (default 1 K) from the current sweep's mean or a
    frequency repeats within it. `attrs` also holds `path`, `columns` (role -> header),
    `units` (role -> unit as read) and `lines` (one line per step, for printing)."""
    path = str(path)
    if not Path(path).is_file():
        raise FileNotFoundError("read_dma: no such file: %r" % path)
    rows, where = _read_rows(path, sheet, encoding, delimiter)
    header_at, units_at, first = _find_table(rows, path)
    header = [_clean(c) for c in rows[header_at]]
    unit_row = [_clean(c) for c in rows[units_at]] if units_at is not None else None
    width = max(len(r) for r in rows[first:])
    header += [""] * (width - len(header))
    if unit_row is not None:
        unit_row += [""] * (width - len(unit_row))
    chosen, shear = _choose_columns(header, unit_row, columns, path)
    unit_of = {}
    for role in ROLES + (("sweep",) if "sweep" in chosen else ()):
        unit_of[role] = _unit_of(role, chosen[role], header, unit_row, units, path)
    data = rows[first:]
    dec = decimal if decimal is not None else _guess_decimal(data, [chosen[r] for r in ROLES])
    n = len(data)
    values = {}
    for role in ROLES:
        col = chosen[role]
        values[role] = np.array([_number(r[col] if col < len(r) else "", dec) for r in data])
    line = np.array([where[first + k] for k in range(n)])
    keep_row = np.array([any(str(c).strip() for c in r) for r in data])       # blank lines are no points
    f = _to_si("frequency", values["frequency"], unit_of["frequency"])
    e1 = _to_si("storage", values["storage"], unit_of["storage"])
    e2 = _to_si("loss", values["loss"], unit_of["loss"])
    t = _to_si("temperature", values["temperature"], unit_of["temperature"])
    table = pd.DataFrame({"frequency_hz": f, "storage_pa": e1, "loss_pa": e2, "temperature_c": t, "line": line})
    table = table[keep_row].reset_index(drop=True)
    if "sweep" in chosen:
        col = chosen["sweep"]
        sw = np.array([_number(r[col] if col < len(r) else "", dec) for r in data])[keep_row]
        table["sweep"] = sw
    bad = ~(np.isfinite(table["frequency_hz"]) & (table["frequency_hz"] > 0) & np.isfinite(table["storage_pa"])
            & (table["storage_pa"] > 0) & np.isfinite(table["loss_pa"]) & (table["loss_pa"] > 0)
            & np.isfinite(table["temperature_c"]) & (table["temperature_c"] > -273.15))
    if "sweep" in table:
        bad |= ~np.isfinite(table["sweep"])
    names = {r: header[chosen[r]] or "column %d" % (chosen[r] + 1) for r in chosen}
    described = [_describe_bad(table.loc[k], names, unit_of, where_word="line" if where != "row" else "row")
                 for k in np.flatnonzero(bad)]
    dropped = table[bad].copy()
    if bad.any() and not drop_bad:
        shown = "; ".join(described[:4]) + ("; and %d more" % (len(described) - 4) if len(described) > 4 else "")
        raise DmaError("read_dma: %d bad point%s in %s (a frequency or modulus not positive, or not a number): %s; "
                       "pass drop_bad=True (--drop-bad) to drop %s, each named in a warning"
                       % (len(described), "" if len(described) == 1 else "s", path, shown,
                          "it" if len(described) == 1 else "them"))
    table = table[~bad].reset_index(drop=True)
    if len(table) < 3:
        raise DmaError("read_dma: %s holds %d usable points: a DMA table needs sweeps of several frequencies"
                       % (path, len(table)))
    if "sweep" in table:
        table["sweep"] = pd.factorize(table["sweep"])[0]
    else:
        table["sweep"] = _sweeps_of(table["temperature_c"].to_numpy(), table["frequency_hz"].to_numpy(),
                                    sweep_tolerance_k)
    table = table[["frequency_hz", "storage_pa", "loss_pa", "temperature_c", "sweep", "line"]]
    by = table.groupby("sweep")["temperature_c"].mean()
    lines = ["read:     %d points in %d sweeps (%.1f to %.1f C) from %s; columns %s"
             % (len(table), by.size, by.min(), by.max(), path,
                ", ".join("%s = '%s' [%s]" % (r, names[r], unit_of[r]) for r in ROLES))]
    if shear:
        lines.append("moduli:   shear moduli G', G'' (attrs['shear']); E = 2 (1 + poisson) G when fitted")
    if bad.any():
        lines.append("dropped:  %d bad point%s: %s" % (len(described), "" if len(described) == 1 else "s",
                                                       "; ".join(described)))
        warn("read_dma dropped %d bad point%s of %s: %s" % (len(described), "" if len(described) == 1 else "s", path,
                                                            "; ".join(described)),
             "dma-dropped-points", float(len(described)), 0.0, source="dma", stacklevel=2)
    table.attrs.update(path=path, columns=names, units=unit_of, shear=shear, dropped=dropped, lines=lines)
    return table


def _read_rows(path, sheet, encoding, delimiter):
    """The file's cells as rows of strings, and where each row is (its 1-based line or row)."""
    suffix = Path(path).suffix.lower()
    if suffix in (".xlsx", ".xlsm", ".xls", ".ods"):
        try:
            raw = pd.read_excel(path, sheet_name=sheet, header=None, dtype=object)
        except ImportError as e:
            raise DmaError("read_dma: reading %s needs %s (pip install openpyxl), or export the sheet as CSV"
                           % (path, e.name or "an Excel reader")) from None
        rows = [["" if (isinstance(c, float) and math.isnan(c)) or c is None else str(c) for c in r]
                for r in raw.itertuples(index=False)]
        return rows, list(range(1, len(rows) + 1))
    data = Path(path).read_bytes()
    if encoding is not None:
        text = data.decode(encoding)
    elif data.startswith(b"\xef\xbb\xbf"):
        text = data[3:].decode("utf-8")
    elif data.startswith((b"\xff\xfe", b"\xfe\xff")):
        text = data.decode("utf-16")
    else:
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            text = data.decode("cp1252")
    lines = text.splitlines()
    if delimiter is None:
        sample = [ln for ln in lines[:60] if ln.strip()]
        counts = {d: sum(ln.count(d) for ln in sample) for d in ("\t", ";", ",")}
        delimiter = "\t" if counts["\t"] else (";" if counts[";"] else ",")
        if delimiter == "\t" and counts["\t"] < len(sample) // 2:
            delimiter = ";" if counts[";"] else ","
    rows = list(csv.reader(io.StringIO("\n".join(lines)), delimiter=delimiter))
    return rows, list(range(1, len(rows) + 1))


def _clean(cell):
    return str(cell).replace("\ufeff", "").strip()


def _is_number(cell):
    s = _clean(cell)
    return bool(re.fullmatch(r"[+-]?(\d+[.,]?\d*|[.,]\d+)([eE][+-]?\d+)?", s))


def _find_table(rows, path):
    """(header row, units row or None, first data row): the first run of rows with 3 or more
    numbers below a header of 3 or more names."""
    for k, r in enumerate(rows):
        if sum(_is_number(c) for c in r) >= 3 and k + 1 < len(rows) and sum(_is_number(c) for c in rows[k + 1]) >= 3:
            above = [j for j in range(k) if sum(bool(_clean(c)) for c in rows[j]) >= 3]
            if not above:
                raise DmaError("read_dma: %s has numbers from line %d but no header row naming its columns above them: "
                               "add one (f, E', E'', T) or pass columns= and units=" % (path, k + 1))
            h = above[-1]
            if h == k - 1 and len(above) >= 2 and above[-2] == k - 2 and _looks_like_units(rows[h]):
                return above[-2], h, k
            return h, None, k
    raise DmaError("read_dma: %s holds no table of numbers (rows of 3 or more numbers under a header)" % path)


def _looks_like_units(row):
    cells = [_clean(c) for c in row]
    known = 0
    for c in cells:
        u = _norm_unit(c)
        if u in _NO_UNIT or u in _MODULUS_UNITS or u in _FREQUENCY_UNITS or u in _TEMPERATURE_UNITS or u == "s" \
                or u in ("min", "%", "mm", "um", "n", "1/s"):
            known += 1
    return known == len(cells) and any(_norm_unit(c) not in _NO_UNIT for c in cells)


def _norm_unit(u):
    u = str(u).strip().strip("[]()").strip()
    u = u.replace("\u00b0", "deg").replace("\u00ba", "deg").replace("\u00b2", "2").replace("\u2218", "deg")
    u = u.replace("\u00c2", "")                            # a degree sign read as Windows-1252
    u = re.sub(r"\s+", " ", u).lower()
    if u in ("degc", "deg c", "deg. c", "deg.c", "grad c"):
        return "degc"
    if u in ("degf", "deg f"):
        return "degf"
    if u in ("deg k", "degk"):
        return "k"
    return u.replace(" ", "") if u not in ("rad s-1",) else u


def _split_name(name):
    """('E''', 'MPa') from "E'' [MPa]", "E'' (MPa)", "E''/MPa", "E'' in MPa"; (name, None) without."""
    m = re.fullmatch(r"(.*?)\s*[\[(]\s*([^\])]*)\s*[\])]\s*", name)
    if m and m.group(1):
        return m.group(1).strip(), m.group(2).strip()
    m = re.fullmatch(r"(.*?)\s+in\s+(\S+)\s*", name, flags=re.I)
    if m:
        return m.group(1).strip(), m.group(2).strip()
    m = re.fullmatch(r"(.*[^/\s])\s*/\s*([A-Za-z\u00b0][^/]*)", name)
    if m and _norm_unit(m.group(2)) not in ("s",) and not re.fullmatch(r"[a-z]", m.group(2).strip()):
        return m.group(1).strip(), m.group(2).strip()
    return name.strip(), None


def _role_of(name):
    """('storage', shear?) ... for a header name without its unit; (None, False) for others."""
    n = name.lower().replace("\u2032", "'").replace("\u2033", "''").replace("\u2019", "'").replace("\u00b4", "'")
    n = n.replace("`", "'").replace('"', "''").strip()
    compact = re.sub(r"[\s_.\-]", "", n)
    if re.fullmatch(r"(tan|tg)(d|delta|\u03b4)?|lossfactor|dampingfactor|verlustfaktor|tand\w*", compact):
        return None, False
    if re.fullmatch(r"\|?[eg]\*\|?|[eg]\*|complexmodulus", compact):
        return None, False
    m = re.fullmatch(r"([eg])(''|2)|([eg])?lossmodulus|loss|([eg])loss|verlustmodul(e|g)?", compact)
    if m:
        return "loss", compact.startswith("g")
    m = re.fullmatch(r"([eg])('|1)|([eg])?storagemodulus|storage|([eg])stor(age)?|speichermodul(e|g)?", compact)
    if m:
        return "storage", compact.startswith("g")
    if re.fullmatch(r"f|freq|frequency|frequenz|fr[eé]quence|\u03bd|nu", compact):
        return "frequency", False
    if re.fullmatch(r"omega|\u03c9|angularfrequency|w|angfreq", compact):
        return "angular", False
    if re.fullmatch(r"t|temp|temperature|temperatur|temp[eé]rature|\u03b8|theta|tsample|sampletemperature", compact):
        return "temperature", False
    if re.fullmatch(r"sweep|segment|seg|set|isotherm|sweepno|segmentno|sweepnumber|segmentnumber|step", compact):
        return "sweep", False
    return None, False


def _choose_columns(header, unit_row, columns, path):
    chosen, shear, found = {}, False, {}
    for k, h in enumerate(header):
        base, _ = _split_name(h)
        role, g = _role_of(base)
        if role == "temperature" and base.strip() == "t" and unit_row is not None \
                and _norm_unit(unit_row[k]) in ("s", "min", "h"):
            role = None                                           # t [s]: time
        if role == "angular":
            role = "frequency"
        if role:
            found.setdefault(role, []).append((k, g))
    if columns:
        for role, c in columns.items():
            if role not in ROLES + ("sweep",):
                raise DmaError("read_dma: columns= takes the roles %s, got %r" % (", ".join(ROLES + ("sweep",)), role))
            if isinstance(c, (int, np.integer)):
                if not 0 <= c < len(header):
                    raise DmaError("read_dma: columns['%s'] = %d: %s has columns 0 to %d" % (role, c, path,
                                                                                           len(header) - 1))
                found[role] = [(int(c), False)]
            else:
                hits = [k for k, h in enumerate(header) if h == c] or \
                       [k for k, h in enumerate(header) if _split_name(h)[0].lower() == str(c).lower()]
                if not hits:
                    raise DmaError("read_dma: columns['%s'] = %r is no column of %s (its columns: %s)"
                                   % (role, c, path, ", ".join(repr(h) for h in header if h)))
                found[role] = [(hits[0], False)]
    for role in ROLES + ("sweep",):
        hits = found.get(role, [])
        if role in ("storage", "loss") and len(hits) > 1 and any(g for _, g in hits) and not all(g for _, g in hits):
            hits = [(k, g) for k, g in hits if not g]             # E' and G' both: Young's
        if len(hits) > 1:
            raise DmaError("read_dma: %d columns of %s look like %s (%s): pass columns={'%s': name or index}"
                           % (len(hits), path, _WHAT[role], ", ".join("'%s' (column %d)" % (header[k], k)
                                                                     for k, _ in hits), role))
        if not hits:
            if role == "sweep":
                continue
            raise DmaError("read_dma: no column of %s is %s (its columns: %s): pass columns={'%s': name or index}"
                           % (path, _WHAT[role], ", ".join("'%s'" % h for h in header if h), role))
        chosen[role] = hits[0][0]
        if role == "storage":
            shear = hits[0][1]
    return chosen, shear


def _unit_of(role, col, header, unit_row, units, path):
    if role == "sweep":
        return "-"
    given = (units or {}).get(role)
    source = "units['%s']" % role
    if given is None and unit_row is not None and _norm_unit(unit_row[col]) not in _NO_UNIT:
        given, source = unit_row[col], "the units row"
    if given is None:
        given, source = _split_name(header[col])[1], "its name"
    name = header[col] or "column %d" % (col + 1)
    if given is None or _norm_unit(given) in _NO_UNIT:
        if role == "frequency" and _role_of(_split_name(header[col])[0])[0] == "angular":
            return "rad/s"
        raise DmaError("read_dma: column '%s' (%s) of %s has no unit (no units row, no [unit] in its name): pass "
                       "units={'%s': '%s'} (%s)" % (name, _WHAT[role], path, role, _EXAMPLE_UNIT[role], _UNIT_HINT[role]))
    u = _norm_unit(given)
    table = {"frequency": _FREQUENCY_UNITS, "storage": _MODULUS_UNITS, "loss": _MODULUS_UNITS,
             "temperature": _TEMPERATURE_UNITS}[role]
    if u not in table:
        hint = " ('1/s' is Hz or rad/s)" if u == "1/s" else ""
        raise DmaError("read_dma: the unit '%s' of column '%s' (%s, from %s) of %s is not %s%s: pass units={'%s': ...}"
                       % (given, name, _WHAT[role], source, path, _UNIT_HINT[role], hint, role))
    return str(given).strip().strip("[]()")


def _to_si(role, v, unit):
    u = _norm_unit(unit)
    if role in ("storage", "loss"):
        return v * _MODULUS_UNITS[u]
    if role == "frequency":
        return v * _FREQUENCY_UNITS[u]
    kind, offset = _TEMPERATURE_UNITS[u]
    if kind == "f":
        return (v - 32.0) * 5.0 / 9.0
    return v + offset


def _guess_decimal(data, cols):
    comma = point = 0
    for r in data[:50]:
        for c in cols:
            s = _clean(r[c]) if c < len(r) else ""
            if re.fullmatch(r"[+-]?\d+,\d+([eE][+-]?\d+)?", s):
                comma += 1
            elif re.fullmatch(r"[+-]?\d*\.\d+([eE][+-]?\d+)?", s):
                point += 1
    return "," if comma > point else "."


def _number(cell, decimal):
    s = _clean(cell)
    if decimal == ",":
        s = s.replace(".", "").replace(",", ".") if re.fullmatch(r"[+-]?[\d.]*,\d*([eE][+-]?\d+)?", s) else s
    try:
        return float(s)
    except ValueError:
        return math.nan


def _describe_bad(row, names, unit_of, where_word="line"):
    what = []
    for role, key in (("frequency", "frequency_hz"), ("storage", "storage_pa"), ("loss", "loss_pa"),
                      ("temperature", "temperature_c")):
        v = row[key]
        ok = math.isfinite(v) and (v > 0 if role != "temperature" else v > -273.15)
        if not ok:
            what.append("%s = %s" % (names[role], "not a number" if not math.isfinite(v) else "%.4g %s"
                                     % (_from_si(role, v, unit_of[role]), unit_of[role])))
    f = "%.4g Hz" % row["frequency_hz"] if math.isfinite(row["frequency_hz"]) else "f ?"
    t = "%.1f C" % row["temperature_c"] if math.isfinite(row["temperature_c"]) else "T ?"
    return "%s %d (%s, %s): %s" % (where_word, int(row["line"]), f, t, ", ".join(what) or "sweep not a number")


def _from_si(role, v, unit):
    u = _norm_unit(unit)
    if role in ("storage", "loss"):
        return v / _MODULUS_UNITS[u]
    if role == "frequency":
        return v / _FREQUENCY_UNITS[u]
    kind, offset = _TEMPERATURE_UNITS[u]
    return v * 9.0 / 5.0 + 32.0 if kind == "f" else v - offset


def _sweeps_of(t, f, tolerance_k):
    """A sweep number per point: a new sweep where the temperature leaves the current sweep's
    mean by more than `tolerance_k`, or a frequency repeats within it."""
    out = np.zeros(t.size, dtype=int)
    k, start = 0, 0
    for i in range(1, t.size):
        mean = t[start:i].mean()
        if abs(t[i] - mean) > tolerance_k or np.any(np.isclose(f[start:i], f[i], rtol=1e-9, atol=0)):
            k, start = k + 1, i
        out[i] = k
    return out


# ---------------------------------------------------------------- shift factors


@dataclass
class ShiftFit:
    """A law fitted to measured shift factors: `law` ('wlf' or 'arrhenius') at
    `reference_temperature_c`, its constants (`wlf_c1`, `wlf_c2_k` or `activation_energy_j_mol`)
    with their standard errors (`*_error`, from the fit's Jacobian and residual variance), and
    how it meets the measured log10 a_T: `rms` and `max` of the residuals [decades], `residuals`
    by temperature (a pandas Series)."""
    law: str
    reference_temperature_c: float
    residuals: pd.Series
    rms: float
    max: float
    wlf_c1: float = math.nan
    wlf_c2_k: float = math.nan
    wlf_c1_error: float = math.nan
    wlf_c2_k_error: float = math.nan
    activation_energy_j_mol: float = math.nan
    activation_energy_error: float = math.nan

    def shift_kwargs(self):
        """The keywords of `fit_prony` and `Material` for this law."""
        if self.law == "wlf":
            return {"shift": "wlf", "wlf_c1": self.wlf_c1, "wlf_c2_k": self.wlf_c2_k}
        return {"shift": "arrhenius", "activation_energy_j_mol": self.activation_energy_j_mol}

    def log10_at(self, temperature_c):
        """log10 a_T of the fitted law at `temperature_c` against its reference."""
        from .material import shift_factor
        return np.log10(shift_factor(temperature_c, self.reference_temperature_c, **{
            "shift": self.law, "c1": self.wlf_c1, "c2_k": self.wlf_c2_k,
            "activation_energy_j_mol": self.activation_energy_j_mol if self.law == "arrhenius" else None}))

    def __str__(self):
        if self.law == "wlf":
            head = "WLF at %g C: C1 = %.4g +- %.2g, C2 = %.4g +- %.2g K" % (
                self.reference_temperature_c, self.wlf_c1, self.wlf_c1_error, self.wlf_c2_k, self.wlf_c2_k_error)
        else:
            head = "Arrhenius at %g C: Ea = %.4g +- %.2g kJ/mol" % (
                self.reference_temperature_c, 1e-3 * self.activation_energy_j_mol, 1e-3 * self.activation_energy_error)
        return "%s; misses the measured log10 a_T by %.3f rms, %.3f at most" % (head, self.rms, self.max)


@dataclass(eq=False)
class MasterCurve:
    """Isothermal sweeps shifted onto one frequency axis at `reference_temperature_c`
    (`master_curve` makes it). `log_shift`: log10 a_T of each sweep (a pandas Series indexed by
    the sweep's mean temperature [C]), `log_shift_error` its standard error (the pairs' errors
    added along the chain from the reference); `log_vertical`: log10 b_T (the moduli at T were
    divided by b_T; None without a vertical shift). The shifted points, sorted by reduced
    frequency: `frequency_hz` (f a_T), `storage_pa`, `loss_pa` (divided by b_T),
    `temperature_c`, `sweep`. `pairs`: a DataFrame with a row per neighbouring pair of sweeps
    (their temperatures, the shift between them and its standard error, the rms log10
    residual of their overlap, the points in it). `shear`: the moduli are shear moduli.
    `table` is the table it was made from, `lines` what `python -m veslide material` prints."""
    reference_temperature_c: float
    log_shift: pd.Series
    log_shift_error: pd.Series
    log_vertical: object
    frequency_hz: np.ndarray
    storage_pa: np.ndarray
    loss_pa: np.ndarray
    temperature_c: np.ndarray
    sweep: np.ndarray
    pairs: pd.DataFrame
    table: pd.DataFrame = field(repr=False)
    shear: bool = False
    method: str = ""
    lines: list = field(default_factory=list, repr=False)

    # ---- laws fitted to the shift factors
    def fit_wlf(self, reference_temperature_c=None):
        """WLF fitted to the measured log10 a_T (least squares on log10 a_T, scipy's
        least_squares started from the linearised WLF, (T - Tref)/log10 a_T = -C2/C1 - (T -
        Tref)/C1, so that no default constants are needed), at `reference_temperature_c`
        (default: the master curve's; the measured shifts are moved there first). C2 is kept
        above Tref minus the coldest sweep's temperature (WLF diverges there). Returns a ShiftFit."""
        from scipy.optimize import least_squares
        tref, t, y = self._shifts_at(reference_temperature_c)
        dt = t - tref
        use = np.abs(y) > 0.05
        c1, c2 = 10.0, 100.0
        if use.sum() >= 2:
            slope, icpt = np.polyfit(dt[use], dt[use] / y[use], 1)
            if slope < 0 and icpt * slope > 0:
                c1, c2 = -1.0 / slope, icpt / slope
        c2_min = max(1e-6, -dt.min() + 1e-6)
        c2 = max(c2, c2_min * 1.05 + 1.0)
        c1 = max(c1, 1e-3)

        def resid(p):
            return -p[0] * dt / (p[1] + dt) - y
        r = least_squares(resid, [c1, c2], bounds=([1e-6, c2_min], [1e3, 1e4]), x_scale="jac")
        err = _errors(r, y.size)
        res = pd.Series(r.fun, index=pd.Index(t, name="temperature_c"), name="log10_a_t_residual")
        return ShiftFit("wlf", tref, res, float(np.sqrt(np.mean(r.fun ** 2))), float(np.abs(r.fun).max()),
                        wlf_c1=float(r.x[0]), wlf_c2_k=float(r.x[1]), wlf_c1_error=err[0], wlf_c2_k_error=err[1])

    def fit_arrhenius(self, reference_temperature_c=None):
        """Arrhenius fitted to the measured log10 a_T: log10 a_T = Ea/(R ln 10) (1/T - 1/Tref),
        linear least squares through the origin (T in kelvin). Returns a ShiftFit."""
        from .material import GAS_CONSTANT_J_MOL_K, ZERO_CELSIUS_K
        tref, t, y = self._shifts_at(reference_temperature_c)
        x = 1.0 / (t + ZERO_CELSIUS_K) - 1.0 / (tref + ZERO_CELSIUS_K)
        k = float(np.dot(x, y) / np.dot(x, x))
        r = k * x - y
        dof = max(y.size - 1, 1)
        k_err = math.sqrt(float(np.dot(r, r)) / dof / float(np.dot(x, x)))
        scale = GAS_CONSTANT_J_MOL_K * math.log(10.0)
        res = pd.Series(r, index=pd.Index(t, name="temperature_c"), name="log10_a_t_residual")
        return ShiftFit("arrhenius", tref, res, float(np.sqrt(np.mean(r ** 2))), float(np.abs(r).max()),
                        activation_energy_j_mol=k * scale, activation_energy_error=k_err * scale)

    def _shifts_at(self, reference_temperature_c):
        t = self.log_shift.index.to_numpy(dtype=float)
        y = self.log_shift.to_numpy(dtype=float)
        tref = self.reference_temperature_c if reference_temperature_c is None else float(reference_temperature_c)
        if tref != self.reference_temperature_c:
            if not t.min() <= tref <= t.max():
                raise DmaError("MasterCurve: reference_temperature_c = %g is outside the sweeps (%.1f to %.1f C)"
                               % (tref, t.min(), t.max()))
            y = y - float(np.interp(tref, t, y))
        return tref, t, y

    # ---- the series
    def fit_prony(self, shift="table", *, law=None, **kwargs):
        """A Prony series fitted to the master curve (`veslide.material.fit_prony` on the
        shifted points, at the reference temperature), with the temperature law `shift`:
        'table' (default: the measured shift factors, `log_shift`, as `&material shift =
        'table'`), 'wlf' or 'arrhenius' (fitted here, or `law`, a ShiftFit), or 'none'. Other
        keywords go to fit_prony (form, terms_per_decade, smoothing, poisson, ...); shear moduli
        are turned into Young's moduli (shear=True) unless told otherwise. With a vertical shift
        the series is the master curve's at the reference; the program moves it to other
        temperatures by a_T only (without b_T)."""
        from .material import fit_prony
        kw = dict(kwargs)
        kw.setdefault("shear", self.shear)
        shift = str(shift).lower()
        if shift == "table":
            t = self.log_shift.index.to_numpy(dtype=float)
            y = self.log_shift.to_numpy(dtype=float)
            bad = np.flatnonzero(np.diff(y) >= 0)
            if bad.size:
                k = int(bad[0])
                raise DmaError("MasterCurve.fit_prony: the measured log10 a_T rises from %.1f C (%.3f) to %.1f C (%.3f), "
                               "which no shift table may (a_T falls as the temperature rises): where the moduli "
                               "barely change with frequency the shifts are noise; use shift='wlf' or 'arrhenius'"
                               % (t[k], y[k], t[k + 1], y[k + 1]))
            kw.update(shift="table", shift_temperatures_c=t, shift_log10_at=y)
        elif shift in ("wlf", "arrhenius"):
            law = law if law is not None else (self.fit_wlf() if shift == "wlf" else self.fit_arrhenius())
            kw.update(law.shift_kwargs())
        elif shift != "none":
            raise DmaError("MasterCurve.fit_prony: shift must be 'table', 'wlf', 'arrhenius' or 'none', got %r" % shift)
        else:
            kw["shift"] = "none"
        m = fit_prony(self.frequency_hz, self.storage_pa, self.loss_pa,
                      reference_temperature_c=self.reference_temperature_c, **kw)
        if m.fit is not None:
            order = np.argsort(self.frequency_hz, kind="stable")
            m.fit.temperature_c = self.temperature_c[order]
        return m

    # ---- a look at it
    def plot(self, fig=None, *, unit="MPa", laws=True):
        """E' and E'' (one axis), tan delta (another) against reduced frequency f a_T, coloured
        by temperature, and log10 a_T against T with its error bars and (`laws`) the WLF and
        Arrhenius fits. Returns the figure (its axes: moduli, tan delta, shift factors)."""
        import matplotlib.pyplot as plt
        from matplotlib import cm, colors
        if fig is None:
            fig = plt.figure(figsize=(12, 4))
        axes = fig.subplots(1, 3)
        scale = {"Pa": 1.0, "kPa": 1e-3, "MPa": 1e-6, "GPa": 1e-9}[unit]
        norm = colors.Normalize(self.temperature_c.min(), self.temperature_c.max())
        cmap = plt.get_cmap("coolwarm")
        for s in np.unique(self.sweep):
            k = self.sweep == s
            c = cmap(norm(self.temperature_c[k].mean()))
            f = self.frequency_hz[k]
            axes[0].plot(f, scale * self.storage_pa[k], "o-", color=c, ms=3, lw=0.8)
            axes[0].plot(f, scale * self.loss_pa[k], "s--", color=c, ms=3, lw=0.8, mfc="none")
            axes[1].plot(f, self.loss_pa[k] / self.storage_pa[k], "^-", color=c, ms=3, lw=0.8)
        for ax in axes[:2]:
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("reduced frequency $f a_T$ [Hz] at %g $^\\circ$C" % self.reference_temperature_c)
        axes[0].set_ylabel("$E'$ (o), $E''$ (s) [%s]" % unit)
        axes[1].set_ylabel(r"$\tan\delta$")
        fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), ax=axes[1], label="T [$^\\circ$C]")
        t = self.log_shift.index.to_numpy(dtype=float)
        axes[2].errorbar(t, self.log_shift.to_numpy(), yerr=self.log_shift_error.to_numpy(), fmt="o", ms=4,
                         color="k", label="measured")
        if laws:
            tt = np.linspace(t.min(), t.max(), 200)
            for fit, style in ((self._safe(self.fit_wlf), "-"), (self._safe(self.fit_arrhenius), "--")):
                if fit is not None:
                    axes[2].plot(tt, fit.log10_at(tt), style, label="%s (rms %.3f)" % (fit.law.upper()
                                 if fit.law == "wlf" else "Arrhenius", fit.rms))
        axes[2].axvline(self.reference_temperature_c, color="0.6", lw=0.8)
        axes[2].set_xlabel("T [$^\\circ$C]")
        axes[2].set_ylabel("$\\log_{10} a_T$")
        axes[2].legend(fontsize="small")
        fig.tight_layout()
        return fig

    @staticmethod
    def _safe(fit):
        try:
            return fit()
        except Exception:                    # a law that cannot be fitted is not drawn
            return None

    def to_frame(self):
        """The shifted points as a DataFrame (frequency_hz = f a_T, storage_pa, loss_pa,
        temperature_c, sweep)."""
        return pd.DataFrame({"frequency_hz": self.frequency_hz, "storage_pa": self.storage_pa,
                             "loss_pa": self.loss_pa, "temperature_c": self.temperature_c, "sweep": self.sweep})

    def __str__(self):
        return "\n".join(self.lines)


def _errors(result, n):
    """Standard errors of a least_squares result from its Jacobian and residual variance."""
    jac = result.jac
    dof = max(n - jac.shape[1], 1)
    s2 = float(np.sum(result.fun ** 2)) / dof
    try:
        cov = np.linalg.inv(jac.T @ jac) * s2
        return [float(math.sqrt(max(v, 0.0))) for v in np.diag(cov)]
    except np.linalg.LinAlgError:
        return [math.nan] * jac.shape[1]


#: a pair whose overlap's rms log10 residual exceeds this (10 % in the moduli; DMA noise is
#: 1-5 %, which leaves 0.005-0.02) does not superpose: `master_curve` warns (`poor-superposition`)
POOR_OVERLAP_LOG10 = 0.04
#: a shift factor whose standard error exceeds this [decades] is barely determined: warned
#: (`uncertain-shift`); 0.1 decade is 26 % in every time of the series
UNCERTAIN_SHIFT_LOG10 = 0.1


def master_curve(table, reference_temperature_c, *, vertical=False, degree=2, min_overlap=4):
    """The master curve at `reference_temperature_c` [C] of a table of isothermal sweeps
    (`read_dma`'s, or any DataFrame with frequency_hz, storage_pa, loss_pa, temperature_c and
    optionally sweep), by time-temperature superposition with shift factors found from the data.

    Method: least-squares superposition of the sweeps on their overlaps (shift factors estimated
    by least squares between shifted data and smooth curves, as Honerkamp & Weese, Rheol. Acta
    32 (1993) 57; see also Dealy & Plazek, Rheol. Bull. 78(2) (2009) 16). Each sweep's
    log10 E' and log10 E'' are smoothed by a polynomial P in log10 f (`degree`, default 2).
    Two sweeps i (colder) and j (warmer) shifted by d = log10 a_Tj - log10 a_Ti are compared on
    their overlap: the points of each that fall within the other's log10 f range once shifted,
    with the residuals y_qj - v - P_qi(x_j + d) and y_qi + v - P_qj(x_i - d) for q = E', E''
    (y = log10 of the modulus, x = log10 f; v = 0, or with `vertical=True` the step in log10 b_T,
    the moduli at T being divided by b_T). First each neighbouring pair alone: d minimises the
    mean square of its residuals, found by a scan (0.02 decade steps, at least `min_overlap`
    points overlapping) refined by scipy's least_squares on that overlap; these add up along the
    chain. Then every sweep's shift at once: the sum of squares of the residuals of every pair
    of sweeps that overlap (not only neighbours: where shifts are small a sweep overlaps several,
    and the chain's errors no longer add up from one end), by least_squares, the overlaps found
    again until they settle. log10 a_T is then measured from the reference (the monotone cubic
    through the sweeps' temperatures and shifts, taken at the reference, which must lie within
    them). What is minimised, in one line: sum over overlapping pairs, points and q of the
    squared log10 residuals above.

    Standard errors come from the Jacobian and the residual variance of the last fit (they
    leave out a temperature drift within a sweep); `pairs` gives each neighbouring pair's own
    shift, its error and the rms residual of its overlap, which says how well it superposes. Warned (VeslideWarning):
    `poor-superposition` (a pair's rms log10 residual above 0.04, 10 %), `uncertain-shift` (a
    log10 a_T whose standard error exceeds 0.1), `shift-not-monotone` (log10 a_T rising with
    temperature somewhere: the table shift refuses it). Refused (DmaError, one line): fewer than
    2 sweeps, a sweep of fewer than degree + 2 points, the reference outside the sweeps, a pair
    with no overlap of `min_overlap` points at any shift."""
    from scipy.interpolate import PchipInterpolator
    t_all = pd.DataFrame(table)
    need = ["frequency_hz", "storage_pa", "loss_pa", "temperature_c"]
    missing = [c for c in need if c not in t_all]
    if missing:
        raise DmaError("master_curve: the table lacks the column%s %s (read_dma makes them)"
                       % ("" if len(missing) == 1 else "s", ", ".join(missing)))
    if "sweep" not in t_all:
        t_all = t_all.assign(sweep=_sweeps_of(t_all["temperature_c"].to_numpy(float),
                                              t_all["frequency_hz"].to_numpy(float), 1.0))
    for c in need:
        v = t_all[c].to_numpy(float)
        bad = np.flatnonzero(~(np.isfinite(v) & ((v > 0) if c != "temperature_c" else (v > -273.15))))
        if bad.size:
            raise DmaError("master_curve: %s at row %d is %r (%d bad points): drop them first (read_dma(..., "
                           "drop_bad=True))" % (c, int(bad[0]), float(v[bad[0]]), bad.size))
    tref = float(reference_temperature_c)
    groups = [g for _, g in t_all.groupby("sweep", sort=False)]
    groups.sort(key=lambda g: g["temperature_c"].mean())
    if len(groups) < 2:
        raise DmaError("master_curve: %d sweep: shifting needs sweeps at 2 or more temperatures" % len(groups))
    temps = np.array([g["temperature_c"].mean() for g in groups])
    if not temps.min() <= tref <= temps.max():
        raise DmaError("master_curve: reference_temperature_c = %g is outside the sweeps' %.1f to %.1f C: shift "
                       "factors are measured only between them" % (tref, temps.min(), temps.max()))
    sw = []
    for g, t in zip(groups, temps):
        g = g.sort_values("frequency_hz")
        x = np.log10(g["frequency_hz"].to_numpy(float))
        y = np.vstack([np.log10(g["storage_pa"].to_numpy(float)), np.log10(g["loss_pa"].to_numpy(float))])
        if x.size < degree + 2:
            raise DmaError("master_curve: the sweep at %.1f C has %d points, fewer than degree + 2 = %d"
                           % (t, x.size, degree + 2))
        polys = [np.polynomial.Polynomial.fit(x, yq, degree) for yq in y]
        sw.append(dict(x=x, y=y, p=polys, t=t, g=g))
    d_pair, e_pair, v_pair, rows = [], [], [], []
    for i in range(len(sw) - 1):
        d, err, v, rms, n_ov = _pair_shift(sw[i], sw[i + 1], vertical, min_overlap)
        d_pair.append(d)
        e_pair.append(err)
        v_pair.append(v)
        rows.append((sw[i]["t"], sw[i + 1]["t"], d, err, v, rms, n_ov))
    s = np.concatenate([[0.0], np.cumsum(d_pair)])
    b = np.concatenate([[0.0], np.cumsum(v_pair)])
    s, b, cov, n_pairs = _all_pairs(sw, s, b, vertical, min_overlap)
    if np.all(np.diff(temps) > 0):
        at_ref = float(PchipInterpolator(temps, s)(tref))
        b_ref = float(PchipInterpolator(temps, b)(tref))
    else:
        at_ref, b_ref = float(np.interp(tref, temps, s)), float(np.interp(tref, temps, b))
    log_at = s - at_ref
    k_ref = int(np.argmin(np.abs(temps - tref)))
    err = np.sqrt(np.abs(np.diag(cov) + cov[k_ref, k_ref] - 2 * cov[:, k_ref]))
    log_b = b - b_ref
    idx = pd.Index(np.round(temps, 6), name="temperature_c")
    log_shift = pd.Series(log_at, index=idx, name="log10_a_t")
    log_shift_error = pd.Series(err, index=idx, name="log10_a_t_error")
    log_vertical = pd.Series(log_b, index=idx, name="log10_b_t") if vertical else None
    f, e1, e2, tt, ss = [], [], [], [], []
    for k, w in enumerate(sw):
        g = w["g"]
        f.append(g["frequency_hz"].to_numpy(float) * 10.0 ** log_at[k])
        e1.append(g["storage_pa"].to_numpy(float) / 10.0 ** log_b[k])
        e2.append(g["loss_pa"].to_numpy(float) / 10.0 ** log_b[k])
        tt.append(g["temperature_c"].to_numpy(float))
        ss.append(np.full(len(g), k))
    f, e1, e2, tt, ss = (np.concatenate(a) for a in (f, e1, e2, tt, ss))
    order = np.argsort(f, kind="stable")
    pairs = pd.DataFrame(rows, columns=["temperature_c", "next_temperature_c", "log10_shift", "log10_shift_error",
                                        "log10_vertical", "rms_log10_residual", "overlap_points"])
    if not vertical:
        pairs = pairs.drop(columns="log10_vertical")
    shear = bool(getattr(table, "attrs", {}).get("shear", False))
    mc = MasterCurve(tref, log_shift, log_shift_error, log_vertical, f[order], e1[order], e2[order], tt[order],
                     ss[order], pairs, t_all, shear=shear,
                     method="pairwise least squares on log10 E', log10 E'' (degree %d)%s"
                     % (degree, ", vertical shift" if vertical else ""))
    decades = math.log10(mc.frequency_hz.max() / mc.frequency_hz.min())
    mc.lines = ["shifts:   %d sweeps to %g C by pairwise least squares on log E', log E''%s: log10 a_T from %.2f "
                "(%.1f C) to %.2f (%.1f C); the master curve spans %.1f decades (%.3g to %.3g Hz)"
                % (len(sw), tref, " with a vertical shift" if vertical else "", log_at[0], temps[0], log_at[-1],
                   temps[-1], decades, mc.frequency_hz.min(), mc.frequency_hz.max()),
                "overlaps: rms log10 residual %.3f median, %.3f worst (%.1f C to %.1f C); standard error of log10 a_T "
                "%.3f at most" % (float(np.median(pairs["rms_log10_residual"])), pairs["rms_log10_residual"].max(),
                                  *pairs.loc[pairs["rms_log10_residual"].idxmax(), ["temperature_c",
                                                                                   "next_temperature_c"]],
                                  float(err.max()))]
    if vertical:
        mc.lines.append("vertical: log10 b_T from %.3f to %.3f (the program shifts times only: runs at other "
                        "temperatures lack b_T)" % (log_b.min(), log_b.max()))
    poor = pairs[pairs["rms_log10_residual"] > POOR_OVERLAP_LOG10]
    for r in poor.itertuples(index=False):
        warn("the sweeps at %.1f C and %.1f C superpose to %.3f rms in log10 E', E'' (%.0f %%; above %.2f): "
             "time-temperature superposition does not hold there, or the data are noisy; the master curve and "
             "its shift factors are uncertain there" % (r.temperature_c, r.next_temperature_c,
                                                         r.rms_log10_residual, 100 * (10 ** r.rms_log10_residual - 1),
                                                         POOR_OVERLAP_LOG10),
             "poor-superposition", float(r.rms_log10_residual), POOR_OVERLAP_LOG10, source="dma", stacklevel=2)
    if err.max() > UNCERTAIN_SHIFT_LOG10:
        k = int(np.argmax(err))
        warn("log10 a_T at %.1f C is uncertain by %.2f (standard error; above %.2f): the sweeps barely change with "
             "frequency there, so the overlap fixes their shift poorly" % (temps[k], err[k], UNCERTAIN_SHIFT_LOG10),
             "uncertain-shift", float(err[k]), UNCERTAIN_SHIFT_LOG10, source="dma", stacklevel=2)
    rise = np.flatnonzero(np.diff(log_at) >= 0)
    if rise.size:
        k = int(rise[0])
        warn("log10 a_T rises from %.1f C (%.3f) to %.1f C (%.3f), where every relaxation should be faster: "
             "the shift table refuses it (fit_prony(shift='wlf') or 'arrhenius' smooths it)"
             % (temps[k], log_at[k], temps[k + 1], log_at[k + 1]), "shift-not-monotone",
             float(log_at[k + 1] - log_at[k]), 0.0, source="dma", stacklevel=2)
    return mc


def _overlap(a, b, d):
    """Which points of b fall within a's log10 f range shifted by d, and which of a within b's."""
    ua = b["x"] + d
    ub = a["x"] - d
    return ((ua >= a["x"].min()) & (ua <= a["x"].max()), (ub >= b["x"].min()) & (ub <= b["x"].max()))


def _all_pairs(sw, s, b, vertical, min_overlap):
    """The shifts of every sweep at once (s_0 = 0): least squares over every pair of sweeps
    that overlap by `min_overlap` points (not only neighbours: where shifts are small a sweep
    overlaps several), each pair's residuals as in `_pair_shift`, the overlaps fixed at the
    current shifts and found again until they settle (at most 5 times). Returns s, b, the
    covariance of s and the number of pairs used."""
    from scipy.optimize import least_squares
    n = len(sw)
    for _ in range(5):
        pairs = []
        for i in range(n):
            for j in range(i + 1, n):
                ina, inb = _overlap(sw[i], sw[j], s[j] - s[i])
                if ina.sum() + inb.sum() >= min_overlap:
                    pairs.append((i, j, ina, inb))

        def fun(p):
            ss = np.concatenate([[0.0], p[:n - 1]])
            bb = np.concatenate([[0.0], p[n - 1:]]) if vertical else np.zeros(n)
            out = []
            for i, j, ina, inb in pairs:
                a, c = sw[i], sw[j]
                d, v = ss[j] - ss[i], bb[j] - bb[i]
                for q in range(2):
                    out.append(c["y"][q][ina] - v - a["p"][q](c["x"][ina] + d))
                    out.append(a["y"][q][inb] + v - c["p"][q](a["x"][inb] - d))
            return np.concatenate(out)
        p0 = np.concatenate([s[1:], b[1:]]) if vertical else s[1:].copy()
        r = least_squares(fun, p0, method="lm" if fun(p0).size > p0.size else "trf")
        s_new = np.concatenate([[0.0], r.x[:n - 1]])
        if vertical:
            b = np.concatenate([[0.0], r.x[n - 1:]])
        moved = np.abs(s_new - s).max()
        s = s_new
        if moved < 1e-9:
            break
    jac = r.jac
    dof = max(r.fun.size - jac.shape[1], 1)
    try:
        full = np.linalg.inv(jac.T @ jac) * float(np.sum(r.fun ** 2)) / dof
    except np.linalg.LinAlgError:
        full = np.full((jac.shape[1], jac.shape[1]), np.nan)
    cov = np.zeros((n, n))
    cov[1:, 1:] = full[:n - 1, :n - 1]
    return s, b, cov, len(pairs)


def _pair_shift(a, b, vertical, min_overlap):
    """(d, its standard error, v, rms residual, overlap points) of sweep b (warmer) against a."""
    from scipy.optimize import least_squares
    span = (a["x"].max() - a["x"].min()) + (b["x"].max() - b["x"].min())

    def parts(d):
        return _overlap(a, b, d)

    def residuals(d, ina, inb, v=None):
        r1 = np.concatenate([b["y"][q][ina] - a["p"][q](b["x"][ina] + d) for q in range(2)])
        r2 = np.concatenate([a["y"][q][inb] - b["p"][q](a["x"][inb] - d) for q in range(2)])
        if vertical:
            if v is None:
                v = (r1.sum() - r2.sum()) / max(r1.size + r2.size, 1)
            return np.concatenate([r1 - v, r2 + v]), v
        return np.concatenate([r1, r2]), 0.0

    best = None
    for d in np.arange(-span, 0.5 + 1e-9, 0.02):
        ina, inb = parts(d)
        n = int(ina.sum() + inb.sum())
        if n < min_overlap:
            continue
        r, _ = residuals(d, ina, inb)
        j = float(np.mean(r ** 2))
        if best is None or j < best[0]:
            best = (j, d)
    if best is None:
        raise DmaError("master_curve: the sweeps at %.1f C and %.1f C cannot overlap by %d points at any shift "
                       "(too few frequencies?): lower min_overlap" % (a["t"], b["t"], min_overlap))
    d = best[1]
    result = None
    for _ in range(6):
        ina, inb = parts(d)
        if ina.sum() + inb.sum() < min_overlap:
            break
        if vertical:
            def fun(p):
                return residuals(p[0], ina, inb, p[1])[0]
            p0 = [d, residuals(d, ina, inb)[1]]
        else:
            def fun(p):
                return residuals(p[0], ina, inb)[0]
            p0 = [d]
        result = least_squares(fun, p0, method="lm" if len(fun(p0)) > len(p0) else "trf")
        moved = abs(result.x[0] - d)
        d = float(result.x[0])
        new_a, new_b = parts(d)
        if moved < 1e-9 or (np.array_equal(new_a, ina) and np.array_equal(new_b, inb)):
            break
    if result is None:
        ina, inb = parts(d)
        r, v = residuals(d, ina, inb)
        return d, math.nan, v, float(np.sqrt(np.mean(r ** 2))), int(ina.sum() + inb.sum())
    err = _errors(result, result.fun.size)[0]
    v = float(result.x[1]) if vertical else 0.0
    ina, inb = parts(d)
    return d, err, v, float(np.sqrt(np.mean(result.fun ** 2))), int(ina.sum() + inb.sum())
