"""Results repeat bit for bit: the same input on the same machine gives the same file (timings and
provenance aside), whatever OMP_NUM_THREADS, with FFTW's measured plans kept in the wisdom file."""
import os
import subprocess

import h5py
import numpy as np
import pytest

CASE = """&grid nx = 192, ny = 160 / &surface k_cut = 24, eccentricity = 0.7, alpha_deg = 20 /
&material model = '{model}' / &motion speed_m_s = 0.05, direction_deg = 30 /
&solver fft_planner = 'measure', tolerance = 1e-10, method = '{method}' /
&analysis anisotropy = .true., patches = .true. / &output file = '{out}' /
{extra}"""
# every solver: the splitting, the metric splitting with its inner CG, the CG of the elastic case,
# and the adhesive laws' conjugate gradients inside their splitting (passes on all the threads)
SOLVERS = [("one_term", "dr"), ("one_term", "pdr"), ("elastic", "bccg"), ("one_term", "gcg")]
ADHESION = "&adhesion law = 'exponential', energy_j_m2 = 0.05, range_m = 2.0e-5 /\n"
TIMING = ("seconds", "memory_peak")


def solve(exe, tmp_path, name, threads, wisdom, model, method):
    """The same input file and output name every time (both are recorded in the file)"""
    out = tmp_path / "out.h5"
    nml = tmp_path / "case.nml"
    nml.write_text(CASE.format(out=out, model=model, method=method, extra=ADHESION if method == "gcg" else ""))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), VESLIDE_FFTW_WISDOM=str(wisdom))
    r = subprocess.run([exe, str(nml), "--quiet"], capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr
    return out.rename(tmp_path / (name + ".h5"))


def contents(path):
    """Every dataset and attribute but timings and provenance, as bytes"""
    items = {}
    with h5py.File(path) as f:
        def visit(name, obj):
            if name.startswith("provenance") or any(t in name for t in TIMING):
                return
            if isinstance(obj, h5py.Dataset):
                value = np.asarray(obj[()])
                # (strings come back as Python objects, whose bytes are addresses: their values)
                items[name] = repr(value.tolist()).encode() if value.dtype.kind == "O" else value.tobytes()
            for key, value in obj.attrs.items():
                items[name + "@" + key] = np.asarray(value).tobytes()
        f.visititems(visit)
    return items


@pytest.mark.parametrize("model, method", SOLVERS)
def test_same_bits_on_one_and_two_threads_and_on_a_rerun(tmp_path, exe, model, method):
    wisdom = tmp_path / "wisdom"
    first = contents(solve(exe, tmp_path, "a", 1, wisdom, model, method))   # plans measured, kept in the file
    assert wisdom.exists()
    again = contents(solve(exe, tmp_path, "b", 2, wisdom, model, method))
    third = contents(solve(exe, tmp_path, "c", 1, wisdom, model, method))
    assert first.keys() == again.keys() == third.keys()
    assert "fields/pressure_pa" in first and "scalars/friction_coefficient" in first
    differ = [k for k in first if first[k] != again[k] or first[k] != third[k]]
    assert differ == [], differ
