"""Shared fixtures: small (32 x 16 and 32 x 32) cases and studies, run once per session."""
import os

import matplotlib
import pytest

matplotlib.use("Agg")

import veslide  # noqa: E402

# the smallest meaningful problems: fast on a shared 2-core machine
FAST = {"solver": {"fft_planner": "estimate", "tolerance": 1e-8}}


def params(**groups):
    """FAST merged with the given groups: params(grid={"nx": 32}, motion={...})."""
    out = {k: dict(v) for k, v in FAST.items()}
    for g, v in groups.items():
        out.setdefault(g, {}).update(v)
    return out


@pytest.fixture(scope="session")
def exe():
    """The executable under test: $VESLIDE_EXE (./dev.sh test sets it to this checkout's build),
    else the package's own search."""
    return veslide.find_executable()


@pytest.fixture(scope="session")
def case(exe, tmp_path_factory):
    """A sliding case on a rectangular 32 x 16 grid (so x and y cannot be confused), with every
    optional analysis."""
    out = tmp_path_factory.mktemp("case") / "case.h5"
    p = params(grid={"nx": 32, "ny": 16}, surface={"k_cut": 6, "eccentricity": 0.6, "alpha_deg": 30.0},
               material={"model": "one_term"}, motion={"speed_m_s": 0.13},
               analysis={"anisotropy": True, "zeta2": 6, "patches": True, "persson": True})
    return veslide.run(p, output=out, exe=exe, progress=None)


@pytest.fixture(scope="session")
def study(exe, tmp_path_factory):
    """A study of 8 cases: 2 seeds x 2 angles x 2 speeds, without fields."""
    out = tmp_path_factory.mktemp("study") / "study.h5"
    p = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8, "eccentricity": 0.5},
               material={"model": "one_term"}, output={"fields": False},
               sweep={"speeds_m_s": [0.01, 0.1], "alphas_deg": [0.0, 90.0], "n_seeds": 2})
    return veslide.run(p, output=out, exe=exe, progress=None)
