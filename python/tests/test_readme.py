"""The README's and the reference pages' examples, run and checked, so that they cannot go stale.

Every ```python block of the README, of docs/python.md and of docs/output.md (the small h5py
example) must be in doctest form (`>>> ` lines followed by their output). They are run in one
namespace, in a temporary directory, with the program under test: first the README's quick start
1 (its shell block writes case.nml and runs it), then its Python blocks, then docs/python.md's
(the session writes aniso.h5), then docs/output.md's (which reads it). Output is compared with
ELLIPSIS, NORMALIZE_WHITESPACE and NUMBER: a number written with a decimal point or an exponent
matches the printed one to the digits written (pytest's doctest NUMBER option, re-implemented
here because the blocks are not collected by pytest's doctest plugin). Any `veslide.VeslideWarning`
the program raises fails them: the examples are sound scenes.

The README's quick start 3 (a study) runs as written but for the MPI line (mpi/check.sh runs the
MPI study), and warns of nothing either.

Skipped, and said here: the `veslide.refine` example of inputs/default.nml on five grids up to
2048^2 (66 s on two threads of an idle machine, too long for the suite); its figures are those of
docs/figures/refinement-*.csv. docs/python.md says it is not run.
"""
import doctest
import re
import subprocess
import tempfile
import warnings
from pathlib import Path

import matplotlib.pyplot as plt

import veslide

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
DOCS = ROOT / "docs"
#: the pages whose python blocks run, in this order
PAGES = (README, DOCS / "python.md", DOCS / "output.md")

#: blocks not run, with the reason (a block is matched by a string it contains)
SKIPPED = {"veslide.refine(": "the refinement on five grids up to 2048^2 takes a minute or more"}

_FENCE = re.compile(r"^(?P<indent>[ ]*)```(?P<lang>python|sh)\n(?P<body>.*?)^(?P=indent)```$", re.M | re.S)

# a number with a decimal point or an exponent (as pytest's doctest NUMBER option)
_NUMBER = re.compile(r"""
    (?<![\w.])(?P<number>
      (?P<mantissa>[+-]?\d*\.(?P<fraction>\d+)|[+-]?\d+\.)(?:[eE](?P<exponent1>[+-]?\d+))?
      |[+-]?\d+[eE](?P<exponent2>[+-]?\d+)
    )(?![\w.])""", re.X)


def _section(text, title):
    start = text.index("\n" + title + "\n")
    end = text.find("\n## ", start + len(title) + 2)
    return text[start:end if end >= 0 else len(text)]


def blocks_of(text, lang="python"):
    out = []
    for m in _FENCE.finditer(text):
        if m.group("lang") == lang:
            out.append("\n".join(line[len(m.group("indent")):] for line in m.group("body").splitlines()))
    return out


def readme_blocks():
    """[(page, block text)]: the python blocks of each page of PAGES, in order."""
    return [(page, body) for page in PAGES for body in blocks_of(page.read_text())]


def quick_start(n):
    """The shell block of the README's quick start n."""
    text = README.read_text()
    start = text.index("\n## Quick start %d" % n)
    sh, = blocks_of(text[start:text.index("\n## ", start + 5)], "sh")
    return sh


def run_shell(block, exe, cwd):
    """A README shell block with `veslide` the program under test (MPI lines left out)"""
    script = "\n".join(line for line in block.splitlines() if "mpi/run.sh" not in line)
    script = re.sub(r"(?m)^veslide ", str(exe) + " ", script)
    return subprocess.run(["bash", "-e", "-c", script], cwd=cwd, capture_output=True, text=True,
                          env=dict(__import__("os").environ, OMP_NUM_THREADS="1"), timeout=600)


class NumberChecker(doctest.OutputChecker):
    """OutputChecker that, failing the plain check, lets each number written in `want` stand for
    the number printed at the same place in `got` when they agree to the digits written."""

    def check_output(self, want, got, optionflags):
        if super().check_output(want, got, optionflags):
            return True
        offset = 0
        for w, g in zip(_NUMBER.finditer(want), _NUMBER.finditer(got)):
            fraction = w.group("fraction") or ""
            exponent = w.group("exponent1") or w.group("exponent2") or "0"
            precision = len(fraction) - int(exponent)
            if abs(float(w.group("number")) - float(g.group("number"))) <= 10.0 ** -precision:
                got = got[:g.start() + offset] + w.group("number") + got[g.end() + offset:]
                offset += len(w.group("number")) - (g.end() - g.start())
        return super().check_output(want, got, optionflags)


def test_every_python_block_is_a_doctest():
    blocks = readme_blocks()
    assert len(blocks) >= 5
    for page, body in blocks:
        assert body.lstrip().startswith(">>> "), "a python block of %s is not in doctest form:\n%s" % (page, body)


def test_readme_examples(tmp_path, monkeypatch, exe):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("VESLIDE_EXE", str(exe))
    monkeypatch.setenv("OMP_NUM_THREADS", "1")
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    r = run_shell(quick_start(1), exe, tmp_path)          # writes case.nml and case.h5
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert "validity              no warnings" in r.stdout
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    runner = doctest.DocTestRunner(checker=NumberChecker(), optionflags=flags)
    parser = doctest.DocTestParser()
    globs, skipped = {}, []
    with warnings.catch_warnings():
        warnings.simplefilter("error", veslide.VeslideWarning)      # a sound example warns of nothing
        for page, body in readme_blocks():
            why = next((reason for key, reason in SKIPPED.items() if key in body), None)
            if why:
                skipped.append(why)
                continue
            test = parser.get_doctest(body, globs, page.relative_to(ROOT).as_posix(), str(page), 0)
            runner.run(test, clear_globs=False)
            globs = test.globs                      # DocTest copies its globals: the next block goes on
    plt.close("all")
    summary = runner.summarize(verbose=False)
    assert summary.failed == 0, "examples failed (see the captured output above)"
    assert summary.attempted >= 20 and skipped == [SKIPPED["veslide.refine("]]
    assert list(scratch.iterdir()) == []            # runs without output= left nothing behind
    assert sorted(p.name for p in tmp_path.iterdir()) == ["aniso.h5", "case.h5", "case.nml", "speeds.h5", "tmp"]


def test_readme_study_quick_start(tmp_path, exe):
    """Quick start 3 as written (the MPI line aside): the study's file, its per-case table, and
    no warning; the memory line prints a process's need."""
    r = run_shell(quick_start(3), exe, tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stderr == "" and "a study on 4 processes" in r.stdout
    s = veslide.read(tmp_path / "study.h5")
    assert len(s.summary) == 24 and (s.summary["warnings"] == 0).all() and s.ensemble is not None
