"""Opening veslide's HDF5 files for reading, including a study's part file while it is written."""
import os
import re
import time
from pathlib import Path

import h5py
import numpy as np

# OUT.part: the file a running (or interrupted) run writes before publishing it as OUT; the
# writer holds an advisory lock on OUT.lock for as long as it lives
PART_RE = re.compile(r"^(?P<final>.+)\.part$")


def open_file(path):
    """h5py.File(path, 'r') without HDF5's file lock.

    The writer holds an exclusive lock on its part file for the whole run, so a reader that asks
    for a lock (h5py's default) fails with errno 11. Readers never need the lock: veslide flushes
    after every case, and `retry` covers a read that races a flush."""
    try:
        return h5py.File(path, "r", locking=False)
    except (TypeError, ValueError):
        # h5py < 3.5, or an HDF5 without the locking property: the environment variable works
        # for any HDF5 >= 1.10.7 and is read when a file is opened
        os.environ["HDF5_USE_FILE_LOCKING"] = "FALSE"
        return h5py.File(path, "r")


def retry(fn, partial, attempts=100, pause=0.05):
    """fn() once for a finished file; for a part file being written, again after a short pause
    when a read raced the writer's flush (a half-written group or table)."""
    if not partial:
        return fn()
    for k in range(attempts):
        try:
            return fn()
        except FileNotFoundError:
            raise
        except (OSError, KeyError, RuntimeError, ValueError):
            if k == attempts - 1:
                raise
            time.sleep(pause)


def writer_alive(final):
    """Is a veslide run writing the output `final` now? (it holds the lock on `final`.lock)"""
    import fcntl
    lock = Path(str(final) + ".lock")
    try:
        fd = os.open(lock, os.O_RDONLY)
    except FileNotFoundError:
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except BlockingIOError:
        return True
    finally:
        os.close(fd)
    return False


def published_name(path):
    """OUT for OUT.part, else None."""
    m = PART_RE.match(str(path))
    return Path(m.group("final")) if m else None


def text(value):
    """An attribute or string dataset value as str (VL UTF-8 gives str or bytes)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return text(value[()])
    return value if isinstance(value, str) else str(value)


def python_value(value):
    """numpy scalars and arrays of attributes/datasets as plain Python values (arrays stay arrays,
    except arrays of strings, which become lists of str)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        if value.ndim == 0:
            return python_value(value[()])
        if value.dtype.kind in "OSU":
            return [text(v) for v in value]
    return value
