"""Reading a study while the executable writes it (its part file OUT.part; the writer holds OUT.lock)."""
import subprocess

import numpy as np
import pytest

import veslide
from conftest import params


def start_study(tmp_path, exe, n_speeds):
    out = tmp_path / "running.h5"
    p = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, material={"model": "one_term"},
               output={"fields": False},
               sweep={"speed_min_m_s": 1e-3, "speed_max_m_s": 10.0, "n_speeds": n_speeds, "n_seeds": 2})
    nml = veslide.write_namelist(p, tmp_path / "running.nml")
    proc = subprocess.Popen([str(exe), str(nml), "--output", str(out)], stdout=subprocess.PIPE, text=True,
                            env={"OMP_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"})
    return proc, out


def test_read_a_study_while_it_runs_then_once_published(tmp_path, exe):
    proc, out = start_study(tmp_path, exe, n_speeds=60)
    try:
        first = proc.stdout.readline()
        assert first.startswith("case 1/120:")
        r = veslide.read_running(out)
        assert proc.poll() is None, "the study finished before it could be read: make it longer"
        assert r.partial and r.running
        assert r.path.name == "running.h5.part"
        n1 = len(r.summary)
        assert n1 >= 1 and r.summary["case"].dtype == np.int64 and r.summary["converged"].dtype == np.int64
        assert list(r.summary["case"]) == list(range(1, n1 + 1))
        assert len(r.cases) == n1 and r.cases[1].scalars["converged"] == 1
        assert list(r.provenance["seeds"]) == [1, 2] and r.input["sweep"]["n_speeds"] == 60
        assert r.ensemble is None                               # written when the study ends
        for _ in range(10):
            proc.stdout.readline()
        r2 = r.refresh()
        assert r2.partial and len(r2.summary) >= max(n1, 11)
        rest = proc.stdout.read()
        assert proc.wait(timeout=120) == 0 and "study written" in rest
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert not r.path.exists() and out.exists()                 # published, part file gone
    done = veslide.read_running(out)
    assert not done.partial and done.path == out and len(done.summary) == 120 and len(done.ensemble) == 60
    # a result read while running still reads cases it had not read: its part file is gone, the
    # published file is the same file
    k = max(r2.cases)
    assert k not in r2.cases._cache and not r2.path.exists()
    assert r2.cases[k].scalars == done.cases[k].scalars
    final = r.refresh()
    assert final.path == out and not final.partial and len(final.summary) == 120


def test_an_interrupted_study_leaves_a_readable_part_file(tmp_path, exe):
    proc, out = start_study(tmp_path, exe, n_speeds=200)
    try:
        for _ in range(3):
            proc.stdout.readline()
        proc.terminate()
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert not out.exists()
    r = veslide.read_running(out)
    assert r.partial and not r.running and len(r.summary) >= 3
    assert r.converged in (True, False) and r.cases[3].parameters["case"] == 3
    same = veslide.read(r.path)                                 # the part file by its own name
    assert len(same.summary) == len(r.summary)


def test_read_running_on_a_finished_study_reads_it(study):
    r = veslide.read_running(study.path)
    assert not r.partial and len(r.summary) == 8
    with pytest.raises(FileNotFoundError):
        veslide.read_running(study.path.with_name("nothing.h5"))


def test_refresh_updates_the_result_in_place(tmp_path, exe):
    """refresh() re-reads into the same object (a notebook's variable is never left stale)."""
    proc, out = start_study(tmp_path, exe, n_speeds=60)
    try:
        proc.stdout.readline()
        r = veslide.read_running(out)
        n1 = len(r.summary)
        case1 = r.cases[1]
        assert "study written" in proc.stdout.read() and proc.wait(timeout=120) == 0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert n1 >= 1
    assert r.refresh() is r
    assert r.path == out and not r.partial and not r.running
    assert len(r.summary) == 120 and len(r.cases) == 120 and len(r.ensemble) == 60
    assert case1.refresh() is case1 and case1.scalars == r.cases[1].scalars and case1.path == out
