"""veslide.run: the executable's search, the namelist it is given, progress, errors, non-convergence."""
import os
import subprocess

import f90nml
import h5py
import pytest

import veslide
from conftest import params


def fake_exe(path, body):
    path.write_text("#!/bin/sh\n" + body + "\n")
    path.chmod(0o755)
    return path


def test_executable_search_order(tmp_path, monkeypatch, exe):
    a = fake_exe(tmp_path / "a" , "exit 0")
    bindir = tmp_path / "bin"
    bindir.mkdir()
    on_path = fake_exe(bindir / "veslide", "exit 0")
    monkeypatch.setenv("PATH", str(bindir) + os.pathsep + os.environ["PATH"])
    monkeypatch.setenv("VESLIDE_EXE", str(a))
    assert veslide.find_executable(exe) == exe                     # exe= first
    assert veslide.find_executable() == a                          # then $VESLIDE_EXE
    monkeypatch.delenv("VESLIDE_EXE")
    assert veslide.find_executable() == on_path                    # then veslide on the PATH
    monkeypatch.setenv("PATH", "/usr/bin:/bin")
    built = veslide.find_executable()                              # then this checkout's fpm build
    assert built.name == "veslide" and "build" in built.parts and os.access(built, os.X_OK)
    monkeypatch.setenv("VESLIDE_EXE", str(tmp_path / "missing"))
    with pytest.raises(FileNotFoundError, match="VESLIDE_EXE"):
        veslide.find_executable()


def test_threads_set_omp_num_threads(tmp_path, monkeypatch):
    monkeypatch.setenv("OMP_NUM_THREADS", "7")
    echo = fake_exe(tmp_path / "echo-threads", 'echo "threads $OMP_NUM_THREADS" >&2; exit 1')
    with pytest.raises(veslide.InputError, match="^threads 3$"):
        veslide.run(params(), output=tmp_path / "x.h5", threads=3, exe=echo, progress=None)
    with pytest.raises(veslide.InputError, match="^threads 7$"):
        veslide.run(params(), output=tmp_path / "x.h5", exe=echo, progress=None)


def test_dict_is_written_as_a_namelist_and_progress_streamed(tmp_path, exe):
    lines = []
    p = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, output={"fields": False},
               sweep={"speeds_m_s": [0.0, 0.1], "pressures_pa": [2e4, 4e4]})
    r = veslide.run(p, output=tmp_path / "s.h5", exe=exe, progress=lines.append)
    assert [l.split(":")[0] for l in lines[:4]] == ["case 1/4", "case 2/4", "case 3/4", "case 4/4"]
    assert lines[-1].startswith("veslide: study written to") and r.log == lines
    assert r.converged and len(r.summary) == 4
    assert sorted(set(r.summary["pressure_pa"])) == [2e4, 4e4]
    written = r.input
    assert written["sweep"]["speeds_m_s"] == [0.0, 0.1] and written["output"]["fields"] is False


def test_namelist_file_and_relative_paths_against_the_cwd(tmp_path, monkeypatch, exe):
    monkeypatch.chdir(tmp_path)
    nml = f90nml.Namelist(params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8},
                                 output={"file": "from_nml.h5"}))
    nml.write("case.nml")
    r = veslide.run("case.nml", exe=exe, progress=None)
    assert r.path == tmp_path / "from_nml.h5" and r.path.exists() and r.converged
    r2 = veslide.run("case.nml", output="other.h5", exe=exe, quiet=True, progress=None)
    assert r2.path == tmp_path / "other.h5" and r2.log == []
    # an existing result of the same input is read again; another input's is refused (as the
    # program refuses an existing output), and replaced with overwrite=True
    assert veslide.run("case.nml", output="other.h5", exe=exe, progress=None).reused
    nml["surface"]["k_cut"] = 6
    nml.write("case.nml", force=True)
    with pytest.raises(veslide.InputError, match="other.h5"):
        veslide.run("case.nml", output="other.h5", exe=exe, progress=None)
    veslide.run("case.nml", output="other.h5", exe=exe, overwrite=True, progress=None)
    # no output named anywhere: a result in memory
    r3 = veslide.run(params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}), exe=exe, progress=None)
    assert r3.path is None and r3.in_memory and r3.converged


@pytest.mark.parametrize("groups, words", [
    ({"grid": {"nx": 0}}, ["&grid", "nx"]),
    ({"surface": {"hurst": 1.5}}, ["&surface", "hurst"]),
    ({"gird": {"nx": 32}}, ["gird"]),
])
def test_refused_input_raises_input_error_with_the_programs_line(tmp_path, exe, groups, words):
    out = tmp_path / "bad.h5"
    with pytest.raises(veslide.InputError) as info:
        veslide.run(params(**groups), output=out, exe=exe, progress=None)
    err = info.value
    veslide.write_namelist(params(**groups), tmp_path / "bad.nml")
    direct = subprocess.run([str(exe), str(tmp_path / "bad.nml"), "--output", str(out)],
                            capture_output=True, text=True)
    assert direct.returncode == 1 and err.returncode == 1
    # the program's one line, verbatim, naming the dict instead of the temporary namelist file
    assert err.message == str(err) == direct.stderr.strip().replace(str(tmp_path / "bad.nml"), "params dict")
    assert err.namelist == (tmp_path / "bad.nml").read_text()
    assert "\n" not in err.message
    for w in words:
        assert w in err.message
    assert not out.exists() and not list(tmp_path.glob("bad.h5*"))  # nothing written


def test_non_convergence_is_reported_not_hidden(tmp_path, exe):
    p = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, material={"model": "one_term"},
               motion={"speed_m_s": 0.13})
    p["solver"]["max_iterations"] = 3
    with pytest.warns(veslide.ConvergenceWarning, match="NOT CONVERGED"):
        r = veslide.run(p, output=tmp_path / "nc.h5", exe=exe, progress=None)
    assert r.returncode == 2 and r.converged is False
    assert r.residual > r.scalars["tolerance"] and r.scalars["iterations"] == 3
    assert "NOT CONVERGED" in repr(r) and "NOT CONVERGED" in r.stderr
    with h5py.File(r.path, "r") as f:
        assert f["/scalars/converged"][()] == 0


def test_device_choice(tmp_path, exe):
    """device= is passed as --device; the case records where it was solved and the file the
    build's device support; 'gpu' without a GPU is refused naming the choice; a bad name is a
    ValueError before anything runs."""
    p = params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, output={"fields": False})
    r = veslide.run(p, output=tmp_path / "cpu.h5", exe=exe, progress=None, device="cpu")
    assert r.scalars.attrs["device"] == "cpu"
    assert r.provenance["device_support"] in ("none", "cuda", "cuda-emulated")
    if r.provenance["device_support"] == "none" or "device_name" not in r.provenance:
        with pytest.raises(veslide.InputError, match="device = 'gpu'"):
            veslide.run(p, output=tmp_path / "gpu.h5", exe=exe, progress=None, device="gpu")
        assert not (tmp_path / "gpu.h5").exists()
    with pytest.raises(ValueError, match="device must be one of auto, cpu, gpu"):
        veslide.run(p, output=tmp_path / "x.h5", exe=exe, progress=None, device="cuda")
