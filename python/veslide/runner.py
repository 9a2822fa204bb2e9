"""Running the veslide executable from Python."""
import atexit
import dataclasses
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import warnings
import weakref
from collections.abc import Mapping
from pathlib import Path

import f90nml
import numpy as np

from ._h5 import writer_alive
from ._warning import VeslideWarning
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
    """The program refused the input (exit status 1: bad input; nothing written).

    `message` is the program's one line (a message the program printed on several lines is
    joined): `veslide: FILE: &group variable = value ...`, naming the user's namelist file, or
    `params dict` when the input was a dict of groups. `file` is the namelist file (None for a
    dict; `namelist` is the text the program was given), `group` and `variable` the namelist
    group and variable the line names (None when it names none; `variables` all of them when a
    check involves several: `&sweep n_speeds, speed_min_m_s = ...`)."""

    def __init__(self, message, returncode=None, stderr="", command=None, namelist=None, file=None):
        super().__init__(message, returncode, stderr, command, namelist)
        self.file = file
        self.group, self.variables = _named_in(message)
        self.variable = self.variables[0] if self.variables else None


class OutputExistsError(InputError, FileExistsError):
    """The output file exists and was not made from this input by this program version (or
    `reuse=False`): pass `overwrite=True` to replace it. Both an `InputError` (what the program
    says of an existing output) and a `FileExistsError`."""


class Cancelled(VeslideError):
    """`Run.wait()` of a run stopped by `Run.cancel()`."""


class WriteError(VeslideError, OSError):
    """A file could not be written or read (exit status 3: disk full, file-size limit, an I/O
    error; nothing published, no earlier result lost). `message` is the program's one line; the
    same input may succeed when retried where there is room."""


class NumericalError(VeslideError, ArithmeticError):
    """The numbers broke down (exit status 4: a discrete kernel that is not positive definite, an
    overflow); `message` is the program's one line, naming what to change."""


# &group, then the variables a check names: 'nx = 0', 'foo: no such', 'file 'x.h5' exists',
# 'n_speeds, speed_min_m_s = ...' (a word followed by text, as '&grid has no closing', is none)
_NAMED_RE = re.compile(r"&(?P<group>\w+)(?P<names>(?:\s+\w+,)*\s+\w+(?=\s*(?:=|:|'|\(|$)))?")


def _named_in(message):
    """(group, (variable, ...)) the program's message names first, else (None, ())."""
    m = _NAMED_RE.search(message)
    if m is None:
        return None, ()
    names = tuple(w.strip() for w in (m.group("names") or "").split(",") if w.strip())
    return m.group("group").lower(), tuple(n.lower() for n in names)


def _messages(stderr):
    """The program's messages in stderr: a line starting with white space continues the one
    before (joined with one space)."""
    out = []
    for line in stderr.splitlines():
        if not line.strip():
            continue
        if line[:1].isspace() and out:
            out[-1] = out[-1].rstrip() + " " + line.strip()
        else:
            out.append(line.rstrip())
    return out


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
    on the PATH (e.g. after `fpm install --prefix ~/.local`, or `.venv/bin` activated), else the
    build `./dev.sh` linked into this checkout's `.venv/bin`, else this checkout's fpm release
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
    # the link ./dev.sh makes to this checkout's release build (built with the set-up's library
    # settings, which a bare `fpm run` here may not have)
    link = REPO / ".venv" / "bin" / "veslide"
    if link.exists() and os.access(link, os.X_OK):
        return link.resolve()
    built = _fpm_build_executable()
    if built:
        return built
    raise FileNotFoundError("no veslide executable: pass exe=..., set VESLIDE_EXE, put veslide on the PATH "
                            "(fpm install --profile release --prefix ~/.local) or build this checkout "
                            "(./dev.sh run)")


def _output_of(nml):
    out = nml.get("output", {}) if nml is not None else {}
    return out.get("file") if hasattr(out, "get") else None


def git_revision(path):
    """The revision of the veslide checkout `path` lies in, as dev.sh gives it to the program
    (VESLIDE_GIT_REVISION): `git rev-parse --short=12 HEAD`, with '-dirty' when a tracked file
    differs from it; None when `path` lies in no git checkout of veslide (its top has no
    fpm.toml with name = "veslide") or git is missing."""
    def git(*args):
        out = subprocess.run(["git", "-C", str(where)] + list(args), capture_output=True, text=True, timeout=60)
        return out.stdout.strip() if out.returncode == 0 else None
    where = Path(path).resolve()
    if not where.is_dir():
        where = where.parent
    try:
        top = git("rev-parse", "--show-toplevel")
        if not top or not _is_veslide(Path(top) / "fpm.toml"):
            return None
        where = Path(top)
        rev = git("rev-parse", "--short=12", "HEAD")
        if not rev:
            return None
        status = git("status", "--porcelain", "--untracked-files=no")
        return rev + "-dirty" if status else rev
    except (OSError, subprocess.SubprocessError):
        return None


def _is_veslide(fpm_toml):
    try:
        text = fpm_toml.read_text()
    except OSError:
        return False
    return re.search(r'^\s*name\s*=\s*"veslide"\s*$', text, re.M) is not None


def program_version(exe):
    """The version the executable reports (`veslide --version`: 'veslide X.Y.Z'), or None."""
    out = subprocess.run([str(find_executable(exe)), "--version"], capture_output=True, text=True, timeout=60)
    words = out.stdout.split()
    return words[1] if out.returncode == 0 and len(words) >= 2 else None


def reuse_existing(out, nml, exe, reuse=True, version=None):
    """The Result in the existing file `out` when it was made from the input `nml` (compared as
    parsed namelists: layout and comments do not matter) by the program's version (`version`, or
    asked of `exe`); otherwise `OutputExistsError`, naming overwrite=True. A program rebuilt
    without a new version is not detected. `veslide.run` and `veslide.refine` share it."""
    if not reuse:
        raise OutputExistsError("%s exists: pass reuse=True to read it or overwrite=True to run again" % out)
    try:
        r = read(out)
    except Exception as e:              # not HDF5, or not veslide's
        raise OutputExistsError("%s exists and is not a veslide result (%s): pass overwrite=True to replace it"
                                % (out, e)) from None
    if r.input is None or str(r.input) != str(nml):
        raise OutputExistsError("%s holds the result of another input: pass overwrite=True to replace it, or "
                                "another output" % out)
    version = version or program_version(exe)
    if r.provenance.get("veslide_version") != version:
        raise OutputExistsError("%s was written by veslide %s, the program is %s: pass overwrite=True to replace it"
                                % (out, r.provenance.get("veslide_version"), version))
    r.reused = True
    return r


def _asks_overwrite(nml):
    """The namelist's &output overwrite (the program replaces its output: nothing to reuse)."""
    out = nml.get("output", {}) if nml is not None else {}
    return bool(out.get("overwrite", False)) if hasattr(out, "get") else False


DEVICES = ("auto", "cpu", "gpu")


def run(params, output=None, threads=None, exe=None, *, overwrite=False, reuse=True, quiet=False, progress=print,
        device=None):
    """Run one case or study, wait for it and return its `Result`: `start(...).wait()`.

    params    a dict of namelist groups ({"grid": {"nx": 64, "ny": 64}, "material": {...}}) or the
              path of a namelist file.
    output    the result file; relative paths are taken from the current directory. Default: the
              namelist's &output file, else none: the result is read into memory
              (`result.in_memory`, `result.path` None; `result.save(path)` keeps it) and the
              temporary directory it was written in is removed.
    threads   OMP_NUM_THREADS for the run (default: inherited).
    exe       the executable (see `find_executable`).
    overwrite replace an existing result file (--overwrite).
    reuse     when `output` exists, made from the same input (the parsed namelist) by the same
              program version (`veslide --version`), read it instead of running (one line to
              `progress` says so; `result.reused`); another input's or version's file raises
              `OutputExistsError` (pass overwrite=True). reuse=False refuses any existing file.
              A namelist with &output overwrite = .true. is run again, as it asks.
    quiet     pass --quiet (no summary, no progress lines).
    progress  called with each line the program prints (default: print); None to keep silent.
    device    where the solve runs: 'auto' (a GPU when the program was built with GPU support and
              one is visible), 'cpu' or 'gpu' (--device; default: the namelist's &solver device).
              Which one a case used: `result.scalars.attrs['device']`; the GPU itself is in
              `result.provenance` (device_name, device_memory_bytes, cuda_*_version).

    Exit status 1 raises `InputError` with the program's one-line message, 3 `WriteError` (a file
    could not be written), 4 `NumericalError`; exit status 2 (not converged) returns the result
    with `result.converged` False, `result.residual`, and issues a `ConvergenceWarning`. An interrupt (KeyboardInterrupt) stops the program; a study with an
    output leaves its part file OUT.part with the finished cases (`veslide.read_running(OUT)`;
    the same call resumes it)."""
    handle = start(params, output, threads, exe, overwrite=overwrite, reuse=reuse, quiet=quiet, progress=progress,
                   device=device)
    try:
        return handle.wait(_stacklevel=3)
    except BaseException:
        handle.cancel(keep_part=True)
        raise


def start(params, output=None, threads=None, exe=None, *, overwrite=False, reuse=True, quiet=False, progress=None,
          device=None):
    """Start one case or study in the background and return its `Run` handle at once:
    `.done`, `.wait(timeout=None)` (the `Result`), `.cancel()`, `.progress`, `.output`.

    The arguments are `run`'s; `progress` (a callable given each line the program prints, from
    a background thread) defaults to None here: `.output` collects the lines. The environment
    gets VESLIDE_GIT_REVISION (the provenance's `git_revision`) from `git_revision(program)` when
    it is unset and the program lies in a veslide checkout, as dev.sh does."""
    if device is not None and device not in DEVICES:
        raise ValueError(f"device must be one of {', '.join(DEVICES)}, got {device!r}")
    program = find_executable(exe)
    nml, nml_path = load_params(params)
    if output is None:
        output = _output_of(nml)
    memory = output is None
    if not memory:
        shown = str(output)
        output = Path(output).expanduser()
        if not output.is_absolute():
            output = Path.cwd() / output
        if not overwrite and not _asks_overwrite(nml) and output.exists():
            result = reuse_existing(output, nml, program, reuse)
            result.log = ["veslide: %s exists from the same input and program version: read, not run again "
                          "(overwrite=True runs it again)" % shown]
            return Run._finished_with(result, progress)
    scratch = Path(tempfile.mkdtemp(prefix="veslide-")) if memory or nml_path is None else None
    try:
        if memory:
            output = scratch / "veslide.h5"
        source = None if nml_path is None else Path(nml_path).resolve()
        if nml_path is None:
            nml_path = write_namelist(nml, scratch / "input.nml")
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
        if not env.get("VESLIDE_GIT_REVISION"):
            rev = git_revision(program)
            if rev:
                env["VESLIDE_GIT_REVISION"] = rev
        return Run(cmd, env, output, scratch=scratch, memory=memory, source=source, progress=progress)
    except BaseException:
        if scratch is not None:
            shutil.rmtree(scratch, ignore_errors=True)
        raise


@dataclasses.dataclass
class Progress:
    """How far a run has come, from the lines the program prints (none with quiet=True).

    A study: `cases_done` of `cases_total` (the cases this run solves: a resumed study counts
    those left), `elapsed_s` and `left_s` (the program's estimate). A solve (a single case, or a
    study's current case when it takes more than five seconds): the solver's `method`,
    `iteration`, `residual`, its `target`, `fft_pairs`, `solve_s`, from its line every five
    seconds. `fraction` is for a progress bar (0 to 1)."""
    cases_done: int = 0
    cases_total: int = None
    elapsed_s: float = None
    left_s: float = None
    method: str = None
    iteration: int = None
    residual: float = None
    target: float = None
    fft_pairs: int = None
    solve_s: float = None
    finished: bool = False

    @property
    def fraction(self):
        """A study: cases done / total. A solve: the decades the residual has come down from 1
        over those to its target (log10 residual / log10 target; the pace is not even). 1.0 once
        the run has finished."""
        if self.finished:
            return 1.0
        if self.cases_total:
            return self.cases_done / self.cases_total
        if self.residual is not None and self.target is not None and 0 < self.target < 1:
            return min(max(math.log10(max(self.residual, 1e-300)) / math.log10(self.target), 0.0), 1.0)
        return 0.0

    def update(self, line):
        """Take one line of the program's output into account."""
        m = _CASE_LINE.match(line)
        if m:
            self.cases_done, self.cases_total = int(m.group(1)), int(m.group(2))
            if m.group(3) is not None:
                self.elapsed_s, self.left_s = float(m.group(3)), float(m.group(4))
            self.method = self.iteration = self.residual = self.target = self.fft_pairs = self.solve_s = None
            return
        m = _SOLVER_LINE.match(line)
        if m:
            self.method, self.iteration = m.group(1), int(m.group(2))
            self.residual, self.target = float(m.group(3)), float(m.group(4))
            self.fft_pairs, self.solve_s = int(m.group(5)), float(m.group(6))


def _raised_warnings(result):
    """The VeslideWarnings `run` raises for a result: each of a case's; for a study, each of its
    input's, and one per warning code of its cases (naming how many cases and which)."""
    found = result.warnings
    if not result.is_study:
        return found
    out = [w for w in found if w.case is None]
    by_code = {}
    for w in found:
        if w.case is not None:
            by_code.setdefault(w.code, []).append(w)
    total = len(result.summary) if result.summary is not None else 0
    for code, ws in by_code.items():
        first = ws[0]
        if len(ws) == 1:
            out.append(first)
            continue
        cases = sorted({w.case for w in ws})
        shown = ", ".join(str(c) for c in cases[:10]) + (", ..." if len(cases) > 10 else "")
        out.append(VeslideWarning("in %d of %d cases (%s; Result.warnings lists each): case %d: %s"
                                  % (len(cases), total, shown, first.case, first.text), code, first.value,
                                  first.threshold, case=tuple(cases), source=first.source))
    return out


# the runs started and not ended: stopped when Python exits (a study with an output keeps its part file)
_RUNNING = weakref.WeakSet()


@atexit.register
def _stop_running():
    for handle in list(_RUNNING):
        handle.cancel(keep_part=True)


# 'case 3/8: seed 1, ... ; elapsed      0.4 s, left ~     0.6 s'
_CASE_LINE = re.compile(r"^case (\d+)/(\d+):.*?(?:elapsed\s+([0-9.]+) s, left ~\s*([0-9.]+) s)?\s*$")
# 'solver pdr: iteration 212, residual  3.10E-06 (target  1.0E-08), 180 FFT pairs, 15.0 s'
_SOLVER_LINE = re.compile(r"^solver (\S+): iteration (\d+), residual\s+(\S+) \(target\s+(\S+)\), (\d+) FFT pairs, "
                          r"([0-9.]+) s")


class Run:
    """A veslide run started by `veslide.start` (and waited for by `veslide.run`).

    done       the program has ended and its result (or error) is ready
    wait(timeout=None)  the `Result` (raises what `run` raises; `TimeoutError` when the run is
               still going after `timeout` seconds; `Cancelled` after `cancel()`)
    cancel(keep_part=True)  terminate the program and remove its lock and temporary directory;
               a study written to a file keeps its part file OUT.part with the cases finished
               (the same call resumes it; `veslide.read_running(OUT)` reads it) unless
               keep_part=False, which removes it too (never one it resumed from); True if it
               stopped a running program (since 0.4.0; before, keep_part defaulted to False)
    progress   a `Progress` (a copy: numbers for a progress bar)
    output     the lines the program printed so far (stdout)
    stderr     what it printed on stderr so far
    returncode the exit status once ended (None before; negative: a signal)
    command    the command line
    """

    def __init__(self, cmd, env, output, *, scratch, memory, source, progress):
        self.command = cmd
        self._output_file = Path(output)
        self._scratch = scratch
        self._memory = memory
        self._source = source
        self._callback = progress
        self._lines, self._err = [], []
        self._progress = Progress()
        self._mutex = threading.Lock()
        self._finished = threading.Event()
        self._cancelled = False
        self._keep_part = True
        self._result = self._error = self._warning = None
        self._warned = False
        part = Path(str(output) + ".part")
        self._leftovers = [f for f in (part, Path(str(part) + ".resume"), Path(str(output) + ".lock"))
                           if not f.exists()]       # what this run may create (a part file it resumes stays)
        self._sent = Path(cmd[1]).read_text() if source is None else None
        self._proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, bufsize=1,
                                      env=env)
        self._stderr_reader = threading.Thread(target=self._read_stderr, daemon=True)
        self._stderr_reader.start()
        self._monitor = threading.Thread(target=self._follow, daemon=True)
        self._monitor.start()
        _RUNNING.add(self)

    @classmethod
    def _finished_with(cls, result, progress):
        """A handle for a result read instead of run (`reuse`)."""
        self = cls.__new__(cls)
        self.command, self._proc = None, None
        self._lines, self._err = list(result.log), []
        self._progress = Progress(finished=True)
        self._mutex = threading.Lock()
        self._finished = threading.Event()
        self._finished.set()
        self._cancelled = False
        self._result, self._error = result, None
        self._warned = False
        self._warning = ("veslide: %s: NOT CONVERGED (read, not run again)" % result.path
                         if result.converged is False else None)
        if progress is not None:
            for line in self._lines:
                progress(line)
        return self

    # -- the background threads -----------------------------------------------------------------
    def _read_stderr(self):
        for line in self._proc.stderr:
            with self._mutex:
                self._err.append(line)

    def _follow(self):
        try:
            for line in self._proc.stdout:
                line = line.rstrip("\n")
                if self._source is None:            # the header names the namelist: a temporary file
                    line = line.replace(self.command[1], "params dict")
                with self._mutex:
                    self._lines.append(line)
                    self._progress.update(line)
                if self._callback is not None and not self._cancelled:
                    try:
                        self._callback(line)
                    except BaseException as e:      # the caller's progress failed: stop, keep the part file
                        self._error = e
                        self._cancelled = True
                        self._proc.terminate()
            self._proc.wait()
            self._stderr_reader.join(timeout=10)
        finally:
            try:
                self._finish()
            finally:
                self._proc.stdout.close()
                self._proc.stderr.close()
                self._finished.set()
                _RUNNING.discard(self)

    def _finish(self):
        rc = self._proc.returncode
        stderr = self.stderr
        try:
            if self._cancelled and rc not in (0, 2):
                if self._error is None:
                    self._error = Cancelled("veslide run cancelled (%s)" % " ".join(self.command), rc, stderr,
                                            self.command)
                self._remove_leftovers()
                return
            messages = _messages(stderr)
            message = messages[-1] if messages else ""
            if rc == 1:
                if self._source is None:
                    message = message.replace(self.command[1], "params dict")
                self._error = InputError(message or "veslide refused the input (exit status 1)", 1, stderr,
                                         self.command, self._sent, file=self._source)
            elif rc in (3, 4):
                self._error = (WriteError if rc == 3 else NumericalError)(
                    message or "veslide failed with exit status %d" % rc, rc, stderr, self.command, self._sent)
            elif rc not in (0, 2):
                if stderr and self._callback is not None:
                    sys.stderr.write(stderr)
                self._error = VeslideError("veslide failed with exit status %s: %s" % (rc, stderr.strip()[-2000:]),
                                           rc, stderr, self.command)
            elif not self._output_file.exists():
                self._error = VeslideError("veslide exited with status %d but wrote no %s" % (rc, self._output_file),
                                           rc, stderr, self.command)
            else:
                result = read(self._output_file, memory=self._memory)
                if self._memory:
                    result.path = None
                result.returncode, result.log, result.stderr = rc, list(self._lines), stderr
                self._result = result
                if rc == 2:
                    self._warning = message or "veslide: NOT CONVERGED"
                with self._mutex:
                    self._progress.finished = True
        except BaseException as e:
            self._error = e
        finally:
            if self._scratch is not None:
                shutil.rmtree(self._scratch, ignore_errors=True)

    def _remove_leftovers(self):
        part, resume, lock = (Path(str(self._output_file) + ext) for ext in (".part", ".part.resume", ".lock"))
        for f in ([] if self._keep_part else [part, resume]) + [lock]:
            if f in self._leftovers and not (f == lock and writer_alive(self._output_file)):
                try:
                    f.unlink()
                except FileNotFoundError:
                    pass

    # -- the handle -----------------------------------------------------------------------------
    @property
    def done(self):
        return self._finished.is_set()

    @property
    def returncode(self):
        return None if self._proc is None else self._proc.returncode

    @property
    def output(self):
        with self._mutex:
            return list(self._lines)

    @property
    def stderr(self):
        with self._mutex:
            return "".join(self._err)

    @property
    def progress(self):
        with self._mutex:
            return dataclasses.replace(self._progress)

    def wait(self, timeout=None, *, _stacklevel=2):
        if not self._finished.wait(timeout):
            raise TimeoutError("veslide is still running after %g s" % timeout)
        if self._error is not None:
            raise self._error
        if self._warning is not None:
            warnings.warn(self._warning, ConvergenceWarning, stacklevel=_stacklevel)
            self._warning = None
        if not self._warned and self._result is not None:
            self._warned = True
            for w in _raised_warnings(self._result):
                warnings.warn(w, stacklevel=_stacklevel)
        return self._result

    def cancel(self, keep_part=True):
        if self._finished.is_set():
            return False
        self._keep_part = keep_part
        self._cancelled = True
        self._proc.terminate()
        try:
            self._proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._proc.kill()
        self._finished.wait(60)
        return True

    def __repr__(self):
        p = self.progress
        state = ("done" if self.done else "running") if self._proc is not None else "read, not run again"
        what = ("%d/%d cases" % (p.cases_done, p.cases_total) if p.cases_total else
                "iteration %d, residual %.3g" % (p.iteration, p.residual) if p.iteration is not None else "")
        return "<veslide.Run %s%s>" % (state, ", " + what if what else "")
