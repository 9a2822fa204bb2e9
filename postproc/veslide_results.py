"""Small readers of veslide results for the postproc scripts (study_tables.py, make_figures.py), with
h5py and numpy only: a study's table as a dict of arrays, values of the stored namelist, the
dimensionless speed and seed statistics. Fields, polar curves and the seed ensemble are read with
the package (veslide.read: .fields, .anisotropy, .ensemble) and drawn with veslide.plot."""
import re

import h5py
import numpy as np

from veslide.results import seed_statistics


def table(path, name="/summary"):
    """A study's /summary (or /ensemble) as a dict of column name -> numpy array."""
    with h5py.File(path, "r") as f:
        data = f[name][()]
    return {k: np.asarray(data[k]) for k in data.dtype.names}


def namelist_value(path, name, default=None):
    """A numeric value from the input namelist stored in the file (/input/namelist)."""
    with h5py.File(path, "r") as f:
        text = f["/input/namelist"][()].decode()
    m = re.search(r"\b" + re.escape(name) + r"\s*=\s*([-+0-9.eEdD]+)", text)
    return float(m.group(1).replace("d", "e").replace("D", "e")) if m else default


def dimensionless_speed(path, speed_m_s):
    """v tau / L0 with tau the creep time of the one-term law (tau_s) and L0 = 2 pi/q_r the
    roll-off wavelength, lx_m / k_roll (the punch size of the paper; L0 = lx_m when k_roll = 1)."""
    tau = namelist_value(path, "tau_s", 0.01)
    lx = namelist_value(path, "lx_m", 0.01)
    k_roll = namelist_value(path, "k_roll", 1.0)
    return np.asarray(speed_m_s) * tau / (lx / k_roll)


def seed_stats(x, name=""):
    """mean, standard error of the mean, min and max over seeds, by /ensemble's rule (axes as
    axial data): the package's veslide.results.seed_statistics."""
    return seed_statistics(x, name)
