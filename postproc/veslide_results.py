"""Reading veslide HDF5 results (single runs and studies) with numpy/h5py/pandas-free helpers."""
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
    """v tau / L0 with tau the creep time of the one-term law (tau_s) and L0 = lx_m."""
    tau = namelist_value(path, "tau_s", 0.01)
    lx = namelist_value(path, "lx_m", 0.01)
    return np.asarray(speed_m_s) * tau / lx


def case_group(path, k):
    """Name of case k (1-based) of a study."""
    return "/cases/%06d" % k


def field(path, name, prefix=""):
    """A 2-D field as a numpy array indexed [iy, ix], with its units."""
    with h5py.File(path, "r") as f:
        d = f[prefix + "/fields/" + name]
        return d[()], d.attrs["units"].decode() if isinstance(d.attrs["units"], bytes) else d.attrs["units"]


def polar(path, prefix=""):
    """theta, m2 of the rigid surface and mu2 of the deformed solid."""
    with h5py.File(path, "r") as f:
        g = f[prefix + "/anisotropy"]
        return g["theta_rad"][()], g["m2_surface"][()], g["mu2_deformed"][()]
