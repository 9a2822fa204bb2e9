"""The executable's promises under faults, run as a user would (a subprocess): a failed write is an
ordinary error, memory is checked first, outputs are never silently replaced or left half-written,
a second writer is refused, and a killed study resumes to the result of an uninterrupted one."""
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np
import pytest

import veslide

SMALL = """&grid nx = 256, ny = 256 / &surface k_cut = 32 / &solver fft_planner = 'estimate' /
&output file = '{out}' /
"""
STUDY = """&grid nx = 32, ny = 32 / &surface k_cut = 8, eccentricity = 0.5 / &material model = 'one_term' /
&solver fft_planner = 'estimate', tolerance = 1e-10 / &sweep speed_min_m_s = 1e-3, speed_max_m_s = 1e2,
n_speeds = {n}, n_seeds = 2 / &output file = '{out}', fields = .false. /
"""
SKIP = ("seconds", "iterations", "operator_applications", "residual", "penetration", "complementarity",
        "negative_pressure", "load_error", "memory_peak")


def run(exe, nml, *args, env=None, shell_prefix=""):
    cmd = "%s%s %s %s" % (shell_prefix, exe, nml, " ".join(args))
    return subprocess.run(["bash", "-c", cmd], capture_output=True, text=True, env=env, timeout=600)


def write(path, text):
    path.write_text(text)
    return path


def one_line(stderr):
    lines = [l for l in stderr.splitlines() if l.strip()]
    assert len(lines) == 1, stderr
    return lines[0]


def leftovers(directory):
    return sorted(p.name for p in directory.iterdir() if p.suffix in (".part", ".lock", ".resume")
                  or ".part" in p.name)


def test_file_size_limit_is_an_ordinary_error(tmp_path, exe):
    out = tmp_path / "out.h5"
    nml = write(tmp_path / "in.nml", SMALL.format(out=out))
    r = run(exe, nml, "--quiet", shell_prefix="ulimit -f 200; ")
    assert r.returncode == 3, r.stderr     # an I/O error (exit status 3)
    line = one_line(r.stderr)
    assert "could not be written" in line and str(out) in line
    assert not out.exists() and leftovers(tmp_path) == []


def test_full_disk_is_an_ordinary_error(tmp_path, exe):
    disk = tmp_path / "disk"
    disk.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", "size=600k", "tmpfs", str(disk)],
                                           capture_output=True).returncode != 0:
        pytest.skip("a small tmpfs needs root (mount)")
    try:
        out = disk / "out.h5"
        nml = write(tmp_path / "in.nml", SMALL.format(out=out))
        r = run(exe, nml, "--quiet")
        assert r.returncode == 3, r.stderr
        assert "could not be written" in one_line(r.stderr)
        assert list(disk.iterdir()) == []
    finally:
        subprocess.run(["umount", str(disk)])


def test_memory_is_checked_before_allocating(tmp_path, exe):
    out = tmp_path / "out.h5"
    nml = write(tmp_path / "big.nml", "&grid nx = 65536, ny = 65536 / &output file = '%s' /\n" % out)
    r = run(exe, nml)
    assert r.returncode == 1
    line = one_line(r.stderr)
    assert "&grid nx, ny = 65536 x 65536" in line and "GiB" in line
    # a limit on the data segment is seen too: a sliding 1024^2 case needs ~230 MiB, refused under 150 MiB
    nml = write(tmp_path / "mid.nml", SMALL.replace("256", "1024").format(out=out) +
                "&material model = 'one_term' / &motion speed_m_s = 0.13 /\n")
    r = run(exe, nml, shell_prefix="ulimit -d 150000; ")
    assert r.returncode == 1 and "&grid nx, ny = 1024 x 1024" in one_line(r.stderr)
    assert not out.exists() and leftovers(tmp_path) == []


def test_estimate_is_honest(tmp_path, exe):
    out = tmp_path / "out.h5"
    nml = write(tmp_path / "in.nml", (SMALL.replace("256", "512") + "&material model = 'one_term' /\n"
                                      "&motion speed_m_s = 0.13 /\n").format(out=out))
    r = run(exe, nml, "--quiet")
    assert r.returncode == 0, r.stderr
    s = veslide.read(out).scalars
    assert 0.85 < s["memory_peak_bytes"] / s["memory_estimate_bytes"] < 1.15


@pytest.mark.parametrize("kind", ["fifo", "directory"])
def test_non_regular_output_refused_before_work(tmp_path, exe, kind):
    out = tmp_path / "out.h5"
    if kind == "fifo":
        os.mkfifo(out)
    else:
        out.mkdir()
    nml = write(tmp_path / "in.nml", SMALL.format(out=out))
    t0 = time.time()
    r = run(exe, nml, "--overwrite", "--quiet")
    assert r.returncode == 1 and time.time() - t0 < 5
    line = one_line(r.stderr)
    assert ("not a regular file" if kind == "fifo" else "is a directory") in line
    assert (out.is_fifo() if kind == "fifo" else out.is_dir())


def start(exe, nml):
    return subprocess.Popen([str(exe), str(nml)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def test_second_writer_refused_while_the_first_lives(tmp_path, exe):
    out = tmp_path / "study.h5"
    nml = write(tmp_path / "in.nml", STUDY.format(n=60, out=out))
    first = start(exe, nml)
    try:
        first.stdout.readline()                                  # the first case is done: it holds the lock
        r = run(exe, nml, "--quiet")
        assert r.returncode == 1
        assert "another veslide run is writing" in one_line(r.stderr)
    finally:
        first.kill()
        first.wait()


def summary(path):
    with h5py.File(path, "r") as f:
        return f["/summary"][()], f["/ensemble"][()]


def test_killed_study_resumes_to_the_uninterrupted_result(tmp_path, exe):
    whole = tmp_path / "whole.h5"
    r = run(exe, write(tmp_path / "whole.nml", STUDY.format(n=8, out=whole)), "--quiet")
    assert r.returncode == 0, r.stderr
    out = tmp_path / "study.h5"
    nml = write(tmp_path / "in.nml", STUDY.format(n=8, out=out))
    proc = start(exe, nml)
    for _ in range(5):                                           # 5 of 16 cases, mid-chain
        proc.stdout.readline()
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert not out.exists() and (tmp_path / "study.h5.part").exists()
    r = run(exe, nml, "--quiet")                                 # the same command again
    assert r.returncode == 0, r.stderr
    assert out.exists() and leftovers(tmp_path) == []
    (a, ea), (b, eb) = summary(whole), summary(out)
    assert a.dtype == b.dtype and len(a) == len(b) == 16
    for x, y in ((a, b), (ea, eb)):
        for name in x.dtype.names:
            if any(s in name for s in SKIP):
                continue
            assert np.allclose(x[name], y[name], rtol=1e-9, atol=0), name
    assert abs(b["iterations"].sum() - a["iterations"].sum()) <= 0.02 * a["iterations"].sum()


def test_part_file_of_another_input_is_refused(tmp_path, exe):
    out = tmp_path / "study.h5"
    nml = write(tmp_path / "in.nml", STUDY.format(n=8, out=out))
    proc = start(exe, nml)
    proc.stdout.readline()
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    other = write(tmp_path / "other.nml", STUDY.format(n=9, out=out))
    r = run(exe, other, "--quiet")
    assert r.returncode == 1
    line = one_line(r.stderr)
    assert "study.h5.part" in line and "another input" in line
    assert (tmp_path / "study.h5.part").exists()                # not replaced


def test_summary_names_long_paths_whole(tmp_path, exe):
    """The summary's first line names the input and the output whole, however long (it was cut
    at 120 characters); the program prints it (app/veslide_summary.f90)."""
    deep = tmp_path / ("o" * 120) / ("p" * 120)
    deep.mkdir(parents=True)
    out = deep / ("q" * 200 + ".h5")
    nml = write(tmp_path / ("n" * 200 + ".nml"), "&grid nx = 16, ny = 16 / &surface k_cut = 4 /\n"
                "&solver fft_planner = 'estimate' / &output file = '%s' /\n" % out)
    r = run(exe, nml)
    assert r.returncode == 0, r.stderr
    first = r.stdout.splitlines()[0]
    assert str(nml) in first and str(out) in first, first


def test_write_error_in_python(tmp_path, exe):
    """Exit status 3 (a write that failed) is `veslide.WriteError` in Python, an OSError with the
    program's one line; nothing is published."""
    out = tmp_path / "out.h5"
    code = ("import resource, sys, veslide\n"
            "resource.setrlimit(resource.RLIMIT_FSIZE, (200 * 1024, resource.RLIM_INFINITY))\n"
            "try:\n"
            "    veslide.run(sys.argv[1], exe=sys.argv[2], output=sys.argv[3], quiet=True)\n"
            "except veslide.WriteError as e:\n"
            "    print(e.returncode, isinstance(e, OSError), 'could not be written' in e.message)\n")
    nml = write(tmp_path / "in.nml", SMALL.format(out=out))
    r = subprocess.run([sys.executable, "-c", code, str(nml), str(exe), str(out)], capture_output=True, text=True,
                       timeout=600)
    assert r.stdout.split() == ["3", "True", "True"], r.stdout + r.stderr
    assert not out.exists()


def test_memory_of_a_study_on_a_gpu_counts_its_speeds(tmp_path, exe):
    """--memory of a study at rest in &motion but swept over speeds sizes the device for the
    solver it runs at speed, as a single case at one of those speeds is sized."""
    base = ("&grid nx = 1024, ny = 1024 / &surface k_cut = 8 / &material model = 'one_term', ratio = 30 /\n"
            "&output file = '%s' /\n" % (tmp_path / "x.h5"))
    study = write(tmp_path / "study.nml", base + "&sweep speeds_m_s = 0.01, 0.1 /\n")
    single = write(tmp_path / "single.nml", base + "&motion speed_m_s = 0.1 /\n")
    at_rest = write(tmp_path / "rest.nml", base)

    def gpu_line(nml):
        r = run(exe, "--memory", str(nml), "--device", "cpu")
        assert r.returncode == 0, r.stderr
        return [l for l in r.stdout.splitlines() if "solved on a GPU" in l][0].split("about ")[1]

    assert gpu_line(study) == gpu_line(single) != gpu_line(at_rest)
