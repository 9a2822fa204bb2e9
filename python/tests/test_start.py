"""veslide.start: a run in the background with a handle (done, wait, cancel, progress, output)."""
import tempfile
import time

import pytest

import veslide
from conftest import params
from test_run import fake_exe


def long_study(n_speeds=1000, n_seeds=4):
    return params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, material={"model": "one_term"},
                  output={"fields": False},
                  sweep={"speed_min_m_s": 1e-3, "speed_max_m_s": 10.0, "n_speeds": n_speeds, "n_seeds": n_seeds})


def wait_for(h, cases, limit=60.0):
    t0 = time.monotonic()
    while h.progress.cases_done < cases and not h.done:
        assert time.monotonic() - t0 < limit, "no progress"
        time.sleep(0.02)


def test_a_study_in_the_background_reports_its_progress(tmp_path, monkeypatch, exe):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    h = veslide.start(long_study(n_speeds=4, n_seeds=2), exe=exe)
    assert h.progress.cases_done == 0 and h.progress.fraction == 0.0
    r = h.wait(timeout=120)
    assert h.done and h.returncode == 0 and h.wait() is r
    p = h.progress
    assert (p.cases_done, p.cases_total, p.fraction) == (8, 8, 1.0) and p.left_s == 0.0
    assert [line.split(":")[0] for line in h.output[:8]] == ["case %d/8" % k for k in range(1, 9)]
    assert h.output == r.log and len(r.summary) == 8 and r.path is None
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("in_memory", [False, True])
def test_cancel_midway_leaves_nothing_behind(tmp_path, monkeypatch, exe, in_memory):
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    out = tmp_path / "study.h5"
    h = veslide.start(long_study(), output=None if in_memory else out, exe=exe)
    wait_for(h, 3)
    with pytest.raises(TimeoutError):
        h.wait(timeout=0.01)
    assert not h.done
    p = h.progress
    assert p.cases_total == 4000 and 3 <= p.cases_done < 4000 and 0 < p.fraction < 1 and p.left_s > 0
    if not in_memory:
        assert (tmp_path / "study.h5.part").exists()
    assert h.cancel(keep_part=False) is True
    assert h.done and h.cancel() is False
    with pytest.raises(veslide.Cancelled):
        h.wait()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["tmp"] and list(scratch.iterdir()) == []


def test_cancel_keeps_the_finished_cases_of_a_study(exe, tmp_path):
    """By default a cancelled study keeps its part file with the cases it finished, which
    read_running reads and the same call resumes; the lock goes."""
    out = tmp_path / "study.h5"
    h = veslide.start(long_study(), output=out, exe=exe)
    wait_for(h, 3)
    assert h.cancel() is True
    with pytest.raises(veslide.Cancelled):
        h.wait()
    assert sorted(p.name for p in tmp_path.iterdir() if not p.name.endswith(".resume")) == ["study.h5.part"]
    partial = veslide.read_running(out)
    assert partial.partial and not partial.running and len(partial.summary) >= 3


def test_progress_of_a_single_solve(tmp_path):
    """The solver's line every five seconds, as the program prints it, read while it runs."""
    lines = ("solver pdr: iteration 212, residual  3.10E-06 (target  1.0E-08), 180 FFT pairs, 15.0 s",
             "solver pdr: iteration 300, residual  1.00E-07 (target  1.0E-08), 260 FFT pairs, 20.5 s")
    slow = fake_exe(tmp_path / "slow", 'printf "%%s\\n" "%s" "%s"; exec sleep 30' % lines)
    seen = []
    h = veslide.start({"grid": {"nx": 8}}, output=tmp_path / "x.h5", exe=slow, progress=seen.append)
    t0 = time.monotonic()
    while len(h.output) < 2:
        assert time.monotonic() - t0 < 10
        time.sleep(0.01)
    p = h.progress
    assert (p.method, p.iteration, p.residual, p.target, p.fft_pairs, p.solve_s) == ("pdr", 300, 1e-7, 1e-8, 260, 20.5)
    assert p.cases_total is None and p.fraction == pytest.approx(7 / 8)      # 7 of 8 decades
    first = veslide.Progress()
    first.update(lines[0])
    assert (first.iteration, first.residual, first.fft_pairs) == (212, 3.1e-6, 180)
    assert first.fraction == pytest.approx(0.689, abs=1e-3)
    assert seen == list(lines) and not h.done and h.cancel() and h.done
    with pytest.raises(veslide.Cancelled):
        h.wait()
    assert list(tmp_path.iterdir()) == [slow]


def test_run_is_start_then_wait(tmp_path, exe):
    """The same implementation: run's result carries the log the handle collected."""
    lines = []
    r = veslide.run(long_study(n_speeds=2, n_seeds=1), output=tmp_path / "s.h5", exe=exe, progress=lines.append)
    assert lines == r.log and lines[-1].startswith("veslide: study written to") and len(r.summary) == 2


def test_python_exiting_stops_its_runs(tmp_path, exe):
    """A run still going when Python exits is stopped, its temporary directory removed; a study
    with an output keeps its part file (the same call resumes it)."""
    import os
    import subprocess
    import sys
    script = """
import time, veslide
from test_start import long_study
a = veslide.start(long_study(), output="kept.h5", exe=%r)
b = veslide.start(long_study(), exe=%r)
while a.progress.cases_done < 2 or b.progress.cases_done < 2:
    time.sleep(0.02)
""" % (str(exe), str(exe))
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    env = dict(os.environ, TMPDIR=str(scratch), PYTHONPATH=os.pathsep.join(sys.path))
    done = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env, timeout=120, capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    assert list(scratch.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kept.h5.part", "kept.h5.part.resume", "tmp"]
    r = veslide.read_running(tmp_path / "kept.h5")
    assert r.partial and not r.running and len(r.summary) >= 2
