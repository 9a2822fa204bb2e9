"""The warning class of the package: what the program or the package found questionable about a
scene, raised as a Python warning while the result is still returned.

Every warning has a `code` (a stable, hyphenated name scripts may filter on: 'contact-resolution',
'surface-slope', ...; docs/validity.md lists them), the number it measured (`value`), the
threshold that number crossed (`threshold`), its text, and for a study the case it belongs to
(`case`, None for a warning about the whole input). Filter them as any Python warning:

    import warnings, veslide
    warnings.filterwarnings("error", category=veslide.VeslideWarning)       # stop on any
    warnings.filterwarnings("ignore", message=r"\\[edge-jump", category=veslide.VeslideWarning)
"""
import warnings


class VeslideWarning(UserWarning):
    """A warning of veslide's: `code`, `value`, `threshold`, `text`, `case` (a study's case
    number, or None), `source` ('input', 'validity', 'preparation', ...)."""

    def __init__(self, text, code=None, value=None, threshold=None, case=None, source=None):
        self.text = text
        self.code = code
        self.value = value
        self.threshold = threshold
        self.case = case
        self.source = source
        super().__init__("[%s] %s" % (code, text) if code else text)

    def __reduce__(self):                     # picklable (multiprocessing, joblib) with its attributes
        return (type(self), (self.text, self.code, self.value, self.threshold, self.case, self.source))


def warn(text, code=None, value=None, threshold=None, *, case=None, source=None, stacklevel=2):
    """Issue a `VeslideWarning` (stacklevel as `warnings.warn`'s, counted from the caller)."""
    warnings.warn(VeslideWarning(text, code, value, threshold, case, source), stacklevel=stacklevel + 1)
