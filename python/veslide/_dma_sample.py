"""The DMA sample shipped with the package (`veslide.material.SAMPLE_DMA`, data/dma-sample.csv)
and how it was made: isothermal sweeps of a known solid in the layout of a real instrument
export, so that the route from an export to a study (`read_dma`, `master_curve`, `fit_prony`,
`python -m veslide material`) can be tried, and tested against the truth.

The known solid (`true_material`): a relaxation series of 30 terms, times 1e-13..1e3 s (about two
a decade), E0 = 2.5 MPa, Einf = 2.0025 GPa; its spectrum is a Gaussian over log rho (the glass
transition, centre 10^-9.5 s, 1.1 decades wide) and a power-law tail to long times (a filled
rubber's slow relaxation). Its time-temperature law is WLF at 20 C with C1 = 7.5, C2 = 130 K
(`TRUE_WLF`: a rubber whose glass transition lies near -60 C). Its tan delta peaks (1.22) at 1.1 MHz at 20 C,
at 10 Hz near -32 C.

The export (`write_export`): 21 sweeps from -50 to 100 C every 7.5 K, 10 frequencies from 0.1
to 100 Hz each (log-spaced); each point at its own temperature, which drifts by up to 0.3 K
about the set point; E' and E'' each with 2.5 % relative Gaussian noise (seed 2024). In a real
export's layout: the columns f, E', E'', tan d, T in that order, a units row (Hz, MPa, MPa, -,
degC), moduli in MPa to 5 significant digits, UTF-8 with a byte-order mark, comma separated,
CRLF lines. 7.6 kB.

    python -m veslide._dma_sample            # writes python/veslide/data/dma-sample.csv again
"""
from pathlib import Path

import numpy as np
import pandas as pd

#: the known shift law of the sample (its master curve's reference and WLF constants)
TRUE_WLF = {"reference_temperature_c": 20.0, "shift": "wlf", "wlf_c1": 7.5, "wlf_c2_k": 130.0}
#: the sample's set temperatures [C] and frequencies [Hz]
TEMPERATURES_C = np.round(np.arange(-50.0, 100.0 + 1e-9, 7.5), 1)
FREQUENCIES_HZ = np.logspace(-1, 2, 10)
NOISE = 0.025
SEED = 2024
#: where the sample lives
PATH = Path(__file__).resolve().parent / "data" / "dma-sample.csv"


def true_material(**law):
    """The known solid of the sample: 30 relaxation terms (see the module's text) with the
    shift law `law` (default `TRUE_WLF`)."""
    from .material import Material
    rho = np.logspace(-13, 3, 30)
    x = np.log10(rho)
    w = np.exp(-(x + 9.5) ** 2 / (2 * 1.1 ** 2)) + 0.05 * 10 ** (-0.3 * (x + 8)) / (1 + np.exp(-(x + 8.5) / 0.4))
    return Material.relaxation(2.5e6, 2.0e9 * w / w.sum(), rho, **(law or TRUE_WLF))


def sweeps(material=None, temperatures_c=TEMPERATURES_C, frequencies_hz=FREQUENCIES_HZ, noise=NOISE, seed=SEED,
           temperature_scatter_k=0.3):
    """Isothermal sweeps of `material` (default `true_material()`): a DataFrame with one row per
    point in measuring order (each temperature, its frequencies rising) and the columns
    frequency_hz, storage_pa, loss_pa, temperature_c (the sample's temperature at that point,
    its set point plus a uniform drift of up to `temperature_scatter_k`, at which the moduli
    are taken), set_temperature_c; E' and E'' each times (1 + noise N(0, 1))."""
    material = true_material() if material is None else material
    rng = np.random.default_rng(seed)
    rows = []
    for t in temperatures_c:
        measured = t + temperature_scatter_k * rng.uniform(-1, 1, len(frequencies_hz))
        e = np.array([material.at_temperature(float(tm)).modulus(f) for f, tm in zip(frequencies_hz, measured)])
        s = e.real * (1 + noise * rng.standard_normal(len(frequencies_hz)))
        ls = e.imag * (1 + noise * rng.standard_normal(len(frequencies_hz)))
        rows += [(f, a, b, tm, t) for f, a, b, tm in zip(frequencies_hz, s, ls, measured)]
    return pd.DataFrame(rows, columns=["frequency_hz", "storage_pa", "loss_pa", "temperature_c", "set_temperature_c"])


def export_text(table):
    """The sweeps of `table` (as `sweeps` gives) as an instrument's export: the header
    f,E',E'',tan d,T, the units row Hz,MPa,MPa,-,degC (the degree sign in UTF-8), one line per
    point (5 significant digits), lines ending in CRLF as Windows instruments write them. The
    byte-order mark is added by `write_export`."""
    lines = ["f,E',E'',tan d,T", "Hz,MPa,MPa,-,\u00b0C"]
    for r in table.itertuples(index=False):
        lines.append("%.5g,%.5g,%.5g,%.5g,%.2f" % (r.frequency_hz, r.storage_pa * 1e-6, r.loss_pa * 1e-6,
                                                   r.loss_pa / r.storage_pa, r.temperature_c))
    return "\r\n".join(lines) + "\r\n"


def write_export(table, path):
    """Write `export_text(table)` to `path` in UTF-8 with a byte-order mark; returns the path."""
    path = Path(path)
    path.write_bytes(b"\xef\xbb\xbf" + export_text(table).encode("utf-8"))
    return path


def main():
    print("written: %s" % write_export(sweeps(), PATH))


if __name__ == "__main__":
    main()
