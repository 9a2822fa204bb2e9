"""Small readers of veslide results for the postproc scripts (study_tables.py, make_figures.py), with
h5py and numpy only: a study's table as a dict of arrays, values of the stored namelist, the
dimensionless speed and seed statistics. Fields, polar curves and the seed ensemble are read with
the package (veslide.read: .fields, .anisotropy, .ensemble) and drawn with veslide.plot."""
import re

import h5py
import numpy as np


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


# angles defined modulo pi (axes): the range their mean is reported in, as /ensemble does
AXIAL = {"theta_s_rad": "0..pi", "theta_d_rad": "0..pi", "patch_theta_rad": "0..pi", "phi_rad": "-pi/2..pi/2"}


def seed_stats(x, name=""):
    """mean, standard error of the mean, min and max over seeds. Axes (AXIAL names) are averaged
    as axial data like /ensemble: circular mean of the doubled angle, deviations wrapped into
    (-pi/2, pi/2]; min and max are of the samples unwrapped about that mean."""
    x = np.asarray(x, float)
    n = len(x)
    if name in AXIAL:
        m = 0.5 * np.arctan2(np.sin(2 * x).sum(), np.cos(2 * x).sum())
        if AXIAL[name] == "0..pi":
            m = m % np.pi
        d = x - m
        d = d - np.pi * np.round(d / np.pi)
    else:
        m = x.mean()
        d = x - m
    se = np.sqrt((d ** 2).sum() / max(1, n - 1) / n)
    return m, se, (m + d).min(), (m + d).max()
