"""What a new user hits (issue 25): refused inputs that name the user's file, runs that leave
nothing behind, a notebook cell run twice, refresh in place, the git revision of the program."""
import subprocess
import tempfile

import pytest

import veslide
from conftest import params
from test_run import fake_exe

SMALL = params(grid={"nx": 32, "ny": 16}, surface={"k_cut": 6, "eccentricity": 0.6, "alpha_deg": 30.0},
               material={"model": "one_term"}, motion={"speed_m_s": 0.13})


def test_input_error_names_the_users_file_or_the_dict_and_its_variable(tmp_path, monkeypatch, exe):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.nml").write_text("&grid nx = 32, ny = abc /\n")
    with pytest.raises(veslide.InputError) as info:
        veslide.run("bad.nml", output="bad.h5", exe=exe, progress=None)
    err = info.value
    assert err.message.startswith("veslide: bad.nml: &grid ny = abc cannot be read")
    assert err.file == tmp_path / "bad.nml" and err.group == "grid" and err.variable == "ny"
    # a dict of groups: the message says so, and names no temporary file
    with pytest.raises(veslide.InputError) as info:
        veslide.run(params(grid={"nx": 0}), output="bad.h5", exe=exe, progress=None)
    err = info.value
    assert err.message == "veslide: params dict: &grid nx = 0 is out of range (allowed: 1 to 65536)"
    assert err.file is None and (err.group, err.variable) == ("grid", "nx") and "nx = 0" in err.namelist
    assert tempfile.gettempdir() not in err.message
    with pytest.raises(veslide.InputError) as info:
        veslide.run(params(gird={"nx": 32}), output="bad.h5", exe=exe, progress=None)
    assert (info.value.group, info.value.variable) == ("gird", None)
    with pytest.raises(veslide.InputError) as info:
        veslide.run(params(sweep={"n_speeds": 3000, "speed_min_m_s": 1e-3, "speed_max_m_s": 1.0}),
                    output="bad.h5", exe=exe, progress=None)
    assert info.value.group == "sweep" and info.value.variables == ("n_speeds", "speed_min_m_s", "speed_max_m_s")
    assert not list(tmp_path.glob("bad.h5*"))


@pytest.mark.parametrize("printed", [
    "veslide: X: &grid ny = abc cannot be read:\\n an integer is expected",
    "veslide: X: &grid\\n ny = abc cannot be read: an integer is expected",
])
def test_input_error_on_two_lines_keeps_the_variable(tmp_path, printed):
    """The program's message may come as a line and its continuation (starting with a space)."""
    (tmp_path / "in.nml").write_text("&grid ny = abc /\n")
    two = fake_exe(tmp_path / "two-lines", 'echo "veslide: warning first" >&2; '
                   'printf "%%b\\n" "%s" | sed "s|X|$1|" >&2; exit 1' % printed)
    with pytest.raises(veslide.InputError) as info:
        veslide.run(tmp_path / "in.nml", output=tmp_path / "x.h5", exe=two, progress=None)
    err = info.value
    assert "\n" not in err.message and err.message.endswith("an integer is expected")
    assert err.message.startswith("veslide: %s: &grid" % (tmp_path / "in.nml"))
    assert (err.group, err.variable) == ("grid", "ny")


def test_runs_without_an_output_leave_nothing_behind(tmp_path, monkeypatch, exe):
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    r = veslide.run(SMALL, exe=exe, progress=None)
    assert list(scratch.iterdir()) == []
    assert r.path is None and r.converged and r.fields.pressure_pa.shape == (32, 16)
    assert r.input["grid"]["nx"] == 32 and r.provenance["veslide_version"] and r.anisotropy is None
    assert r.refresh() is r and "in memory" in repr(r)
    # a study in memory: the summary, the ensemble, its cases and their fields
    s = veslide.run(params(grid={"nx": 32, "ny": 32}, surface={"k_cut": 8}, output={"fields": True},
                           sweep={"speeds_m_s": [0.0, 0.1], "n_seeds": 2}), exe=exe, progress=None)
    assert list(scratch.iterdir()) == []
    assert len(s.summary) == 4 and len(s.ensemble) == 2 and sorted(s.cases) == [1, 2, 3, 4]
    assert s.cases[3].scalars["contact_area_fraction"] == s.summary["contact_area_fraction"][2]
    assert s.cases[3].fields.gap_m.shape == (32, 32) and s.cases[3].provenance is s.provenance
    # kept on request
    s.save(tmp_path / "kept.h5")
    assert veslide.read(tmp_path / "kept.h5").summary.equals(s.summary)
    # refused inputs: neither the temporary namelist nor its directory stay
    for output in (None, tmp_path / "bad.h5"):
        with pytest.raises(veslide.InputError):
            veslide.run(params(grid={"nx": 0}), output=output, exe=exe, progress=None)
        assert list(scratch.iterdir()) == []


def test_a_cell_run_twice_reads_its_own_output(tmp_path, monkeypatch, exe):
    monkeypatch.chdir(tmp_path)
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    first = veslide.run(SMALL, output="a.h5", exe=exe, progress=None)
    version = subprocess.run([str(exe), "--version"], capture_output=True, text=True).stdout.strip()
    fails = fake_exe(tmp_path / "fails", 'if [ "$1" = --version ]; then echo "%s"; exit 0; fi; exit 3' % version)
    lines = []
    again = veslide.run(SMALL, output="a.h5", exe=fails, progress=lines.append)     # not run
    assert again.scalars == first.scalars and again.path == tmp_path / "a.h5" and again.reused
    assert list(scratch.iterdir()) == []                # not even the namelist's directory
    assert lines == ["veslide: a.h5 exists from the same input and program version: read, not run again "
                     "(overwrite=True runs it again)"]
    # another input's file is refused, naming overwrite=True; nothing replaced
    other = params(**{**SMALL, "motion": {"speed_m_s": 0.2}})
    with pytest.raises(veslide.InputError, match="another input.*overwrite=True") as info:
        veslide.run(other, output="a.h5", exe=exe, progress=None)
    assert isinstance(info.value, FileExistsError)
    newer = fake_exe(tmp_path / "newer", 'if [ "$1" = --version ]; then echo "veslide 99.0.0"; exit 0; fi; exit 3')
    with pytest.raises(FileExistsError, match="written by veslide .* the program is 99.0.0.*overwrite=True"):
        veslide.run(SMALL, output="a.h5", exe=newer, progress=None)
    with pytest.raises(FileExistsError, match="reuse=True"):
        veslide.run(SMALL, output="a.h5", exe=exe, reuse=False, progress=None)
    assert veslide.read("a.h5").scalars == first.scalars
    replaced = veslide.run(other, output="a.h5", exe=exe, overwrite=True, progress=None)
    assert replaced.scalars["speed_m_s"] == 0.2 and not replaced.reused
    # a namelist that asks for its output to be replaced is run again, as it asks
    asks = params(**{**SMALL, "output": {"overwrite": True}})
    assert veslide.run(asks, output="a.h5", exe=exe, progress=None).scalars["speed_m_s"] == 0.13


def test_git_revision_of_a_program_in_a_veslide_checkout(tmp_path, monkeypatch, exe):
    repo = tmp_path / "checkout"
    (repo / "build" / "app").mkdir(parents=True)
    (repo / "fpm.toml").write_text('name = "veslide"\n')
    (repo / ".gitignore").write_text("build/\n")
    git = ["git", "-C", str(repo), "-c", "user.name=t", "-c", "user.email=t@t"]
    subprocess.run(git + ["init", "-q"], check=True)
    subprocess.run(git + ["add", "fpm.toml", ".gitignore"], check=True)
    subprocess.run(git + ["commit", "-q", "-m", "x"], check=True)
    head = subprocess.run(git + ["rev-parse", "--short=12", "HEAD"], capture_output=True, text=True).stdout.strip()
    copy = repo / "build" / "app" / "veslide"
    copy.write_bytes(exe.read_bytes())
    copy.chmod(0o755)
    monkeypatch.delenv("VESLIDE_GIT_REVISION", raising=False)
    p = params(grid={"nx": 16, "ny": 16}, surface={"k_cut": 4}, output={"fields": False})
    assert veslide.run(p, exe=copy, progress=None).provenance["git_revision"] == head
    (repo / "fpm.toml").write_text('name = "veslide"\nversion = "9"\n')
    assert veslide.run(p, exe=copy, progress=None).provenance["git_revision"] == head + "-dirty"
    monkeypatch.setenv("VESLIDE_GIT_REVISION", "given")                 # a value set is kept
    assert veslide.run(p, exe=copy, progress=None).provenance["git_revision"] == "given"
    monkeypatch.delenv("VESLIDE_GIT_REVISION")
    (repo / "fpm.toml").write_text('name = "other"\n')                  # not a veslide checkout
    assert veslide.run(p, exe=copy, progress=None).provenance["git_revision"] == "unknown"
