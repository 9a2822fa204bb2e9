"""Running the veslide executable from Python."""
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import warnings
from collections.abc import Mapping
from pathlib import Path

import f90nml
import numpy as np

from .results import read

# python/veslide/runner.py -> the checkout holding fpm.toml
REPO = Path(__file__).resolve().parents[2]


class VeslideError(RuntimeError):
    """The executable failed in a way the program does not report as bad input (a crash, a
    signal, a missing result file)."""

    def __init__(self, message, returncode=None, stderr="", command=None, namelist=None):
        super().__init__(message)
        self.message = message
        self.returncode = returncode
        self.stderr = stderr
        self.command = command
        self.namelist = namelist


class InputError(VeslideError, ValueError):
    """The program refused the input (exit status 1: bad input or I/O error; nothing written).
    `message` is the program's one line naming the group, the variable and the allowed range
    (for a dict of groups it names the temporary namelist file; `namelist` is that file's text)."""


class ConvergenceWarning(UserWarning):
    """A solve (or some cases of a study) did not reach the tolerance (exit status 2)."""


def _plain(value):
    """numpy values as the Python values f90nml writes."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def namelist(params):
    """An f90nml Namelist from a dict of groups: {"grid": {"nx": 64}, "motion": {...}}."""
    if not isinstance(params, Mapping):
        raise TypeError("params must be a dict of namelist groups or a path, got %r" % type(params).__name__)
    groups = {}
    for group, variables in params.items():
        if not isinstance(variables, Mapping):
            raise TypeError("namelist group %r must be a dict of variables, got %r"
                            % (group, type(variables).__name__))
        groups[str(group).lower()] = {str(k).lower(): _plain(v) for k, v in variables.items()}
    return f90nml.Namelist(groups)


def load_params(params):
    """(Namelist, path) of a namelist file's path, or (Namelist, None) of a dict of groups or a
    Namelist."""
    if isinstance(params, (str, os.PathLike)):
        path = Path(params)
        if not path.is_file():
            raise FileNotFoundError("%s: no such namelist file" % path)
        return f90nml.read(str(path)), path
    return (params if isinstance(params, f90nml.Namelist) else namelist(params)), None


def write_namelist(params, path):
    """Write a dict of namelist groups (or a Namelist) as a namelist file; returns the path."""
    nml = params if isinstance(params, f90nml.Namelist) else namelist(params)
    nml.write(str(path), force=True)
    return Path(path)


def _fpm_build_executable():
    """This checkout's release build, as fpm names it (building it if it is out of date)."""
    if not (REPO / "fpm.toml").is_file():
        return None
    fpm = shutil.which("fpm") or (str(REPO / ".venv/bin/fpm") if (REPO / ".venv/bin/fpm").exists() else None)
    if fpm:
        try:
            out = subprocess.run([fpm, "run", "--profile", "release", "veslide", "--runner", "echo"],
                                 cwd=REPO, capture_output=True, text=True, timeout=1800)
            lines = out.stdout.strip().splitlines()
            if out.returncode == 0 and lines and (REPO / lines[-1].strip()).is_file():
                return REPO / lines[-1].strip()
        except (OSError, subprocess.SubprocessError):
            pass
    builds = sorted((REPO / "build").glob("*/app/veslide"), key=lambda p: p.stat().st_mtime)
    return builds[-1] if builds else None


def find_executable(exe=None):
    """The veslide executable: `exe` (a path or a command name), else $VESLIDE_EXE, else `veslide`
    on the PATH (e.g. after `fpm install --prefix ~/.local`), else this checkout's fpm release
    build."""
    for candidate, origin in ((exe, "exe"), (os.environ.get("VESLIDE_EXE"), "VESLIDE_EXE")):
        if candidate:
            found = shutil.which(os.fspath(candidate))
            if not found:
                raise FileNotFoundError("%s=%r: not an executable file" % (origin, os.fspath(candidate)))
            return Path(found)
    on_path = shutil.which("veslide")
    if on_path:
        return Path(on_path)
    built = _fpm_build_executable()
    if built:
        return built
    raise FileNotFoundError("no veslide executable: pass exe=..., set VESLIDE_EXE, put veslide on the PATH "
                            "(fpm install --profile release --prefix ~/.local) or build this checkout "
                            "(./dev.sh run)")


def _output_of(nml):
    out = nml.get("output", {}) if nml is not None else {}
    return out.get("file") if hasattr(out, "get") else None


DEVICES = ("auto", "cpu", "gpu")


def run(params, output=None, threads=None, exe=None, *, overwrite=False, quiet=False, progress=print, device=None):
    """Run one case or study and return its `Result`.

    params    a dict of namelist groups ({"grid": {"nx": 64, "ny": 64}, "material": {...}}) or the
              path of a namelist file.
    output    the result file; relative paths are taken from the current directory. Default: the
              namelist's &output file, else veslide.h5 in a new temporary directory.
    threads   OMP_NUM_THREADS for the run (default: inherited).
    exe       the executable (see `find_executable`).
    overwrite replace an existing result file (--overwrite).
    quiet     pass --quiet (no summary, no progress lines).
    progress  called with each line the program prints (default: print); None to keep silent.
    device    where the solve runs: 'auto' (a GPU when the program was built with GPU support and
              one is visible), 'cpu' or 'gpu' (--device; default: the namelist's &solver device).
              Which one a case used: `result.scalars.attrs['device']`; the GPU itself is in
              `result.provenance` (device_name, device_memory_bytes, cuda_*_version).

    Exit status 1 raises `InputError` with the program's one-line message; exit status 2 (not
    converged) returns the result with `result.converged` False, `result.residual`, and issues a
    `ConvergenceWarning`. An interrupt (KeyboardInterrupt) stops the program; a study leaves its
    part file OUT.part with the finished cases (`veslide.read_running(OUT)`)."""
    if device is not None and device not in DEVICES:
        raise ValueError(f"device must be one of {', '.join(DEVICES)}, got {device!r}")
    program = find_executable(exe)
    scratch = None
    nml, nml_path = load_params(params)
    if output is None:
        output = _output_of(nml)
    if output is None:
        scratch = Path(tempfile.mkdtemp(prefix="veslide-"))
        output = scratch / "veslide.h5"
    output = Path(output).expanduser()
    if not output.is_absolute():
        output = Path.cwd() / output
    with tempfile.TemporaryDirectory(prefix="veslide-nml-") as tmp:
        if nml_path is None:
            nml_path = write_namelist(nml, (scratch or Path(tmp)) / "input.nml")
        cmd = [str(program), str(nml_path), "--output", str(output)]
        if overwrite:
            cmd.append("--overwrite")
        if quiet:
            cmd.append("--quiet")
        if device is not None:
            cmd += ["--device", device]
        env = dict(os.environ)
        if threads is not None:
            env["OMP_NUM_THREADS"] = str(int(threads))
        returncode, log, stderr = _execute(cmd, env, progress)
        sent = Path(nml_path).read_text() if returncode == 1 else None
    message = next((line for line in reversed(stderr.splitlines()) if line.strip()), "")
    if returncode == 1:
        raise InputError(message or "veslide refused the input (exit status 1)", 1, stderr, cmd, sent)
    if returncode not in (0, 2):
        raise VeslideError("veslide failed with exit status %s: %s" % (returncode, stderr.strip()[-2000:]),
                           returncode, stderr, cmd)
    if not output.exists():
        raise VeslideError("veslide exited with status %d but wrote no %s" % (returncode, output),
                           returncode, stderr, cmd)
    result = read(output)
    result.returncode, result.log, result.stderr = returncode, log, stderr
    if returncode == 2:
        warnings.warn(message or "veslide: NOT CONVERGED", ConvergenceWarning, stacklevel=2)
    return result


def _execute(cmd, env, progress):
    """Run cmd, passing each stdout line to progress as it comes; returns (status, lines, stderr)."""
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, bufsize=1,
                            env=env)
    err = []
    reader = threading.Thread(target=lambda: err.extend(proc.stderr), daemon=True)
    reader.start()
    log = []
    try:
        for line in proc.stdout:
            line = line.rstrip("\n")
            log.append(line)
            if progress is not None:
                progress(line)
        returncode = proc.wait()
    except BaseException:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        raise
    finally:
        reader.join(timeout=10)
        proc.stdout.close()
        proc.stderr.close()
    stderr = "".join(err)
    if stderr and progress is not None and returncode not in (0, 1):
        sys.stderr.write(stderr)
    return returncode, log, stderr
