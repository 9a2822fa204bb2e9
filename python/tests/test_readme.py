"""The README's Python examples, run and checked, so that they cannot go stale.

Every ```python block of the README's "## Python" section and of "## Output: HDF5" (the small
h5py example) must be in doctest form (`>>> ` lines followed by their output). They are run in
one namespace, in a temporary directory, with the program under test: first the Python section's
blocks in order (the session writes aniso.h5), then the h5py block (which reads it). Output is
compared with ELLIPSIS, NORMALIZE_WHITESPACE and NUMBER: a number written with a decimal point or
an exponent matches the printed one to the digits written (pytest's doctest NUMBER option,
re-implemented here because the blocks are not collected by pytest's doctest plugin).

Skipped, and said here: the `veslide.refine` example of inputs/default.nml on five grids up to
2048^2 (66 s on two threads of an idle machine, too long for the suite); its figures are those of
docs/figures/refinement-*.csv. The README says it is not run.
"""
import doctest
import re
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

README = Path(__file__).resolve().parents[2] / "README.md"

#: blocks not run, with the reason (a block is matched by a string it contains)
SKIPPED = {"veslide.refine(": "the refinement on five grids up to 2048^2 takes a minute or more"}

_FENCE = re.compile(r"^(?P<indent>[ ]*)```python\n(?P<body>.*?)^(?P=indent)```$", re.M | re.S)

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


def readme_blocks():
    """[(section, block text)]: the Python section's python blocks, then the HDF5 section's."""
    text = README.read_text()
    out = []
    for title in ("## Python", "## Output: HDF5"):
        for m in _FENCE.finditer(_section(text, title)):
            body = "\n".join(line[len(m.group("indent")):] for line in m.group("body").splitlines())
            out.append((title, body))
    return out


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
    assert len(blocks) >= 4
    for title, body in blocks:
        assert body.lstrip().startswith(">>> "), "a python block of %s is not in doctest form:\n%s" % (title, body)


def test_readme_examples(tmp_path, monkeypatch, exe):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("VESLIDE_EXE", str(exe))
    monkeypatch.setenv("OMP_NUM_THREADS", "1")
    scratch = tmp_path / "tmp"
    scratch.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(scratch))
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    runner = doctest.DocTestRunner(checker=NumberChecker(), optionflags=flags)
    parser = doctest.DocTestParser()
    globs, skipped = {}, []
    blocks = readme_blocks()
    for title, body in [b for b in blocks if b[0] == "## Python"] + [b for b in blocks if b[0] != "## Python"]:
        why = next((reason for key, reason in SKIPPED.items() if key in body), None)
        if why:
            skipped.append(why)
            continue
        test = parser.get_doctest(body, globs, "README.md " + title, str(README), 0)
        runner.run(test, clear_globs=False)
        globs = test.globs                          # DocTest copies its globals: the next block goes on
    plt.close("all")
    summary = runner.summarize(verbose=False)
    assert summary.failed == 0, "README examples failed (see the captured output above)"
    assert summary.attempted >= 20 and skipped == [SKIPPED["veslide.refine("]]
    assert list(scratch.iterdir()) == []            # runs without output= left nothing behind
    assert sorted(p.name for p in tmp_path.iterdir()) == ["aniso.h5", "speeds.h5", "tmp"]
