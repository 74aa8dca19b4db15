"""pipelines/vresstore.py - what the h5py scripts that edit a vres store in place share
(pipelines/tgv_init.py, cases/channel_uniform_vres2d/init_uniform.py, cases/cavity_vres2d/set_lid.py):
one message naming the tool and exit 1, the store opened for writing with its format checked,
its domains in order, and a line naming the command at the top of its history. The file is
plain HDF5 (vres-store(5)).
"""
import sys
import time

import h5py
import numpy as np


def fail(tool, msg):
    """Print one message naming the tool and exit 1."""
    print(f"{tool}: {msg}", file=sys.stderr)
    sys.exit(1)


def open_rw(tool, path, dim=None):
    """The store at path open for writing (an h5py.File), or exit 1 with one message when it cannot
    be opened or is not a vres store (of dimension dim, when given)."""
    try:
        f = h5py.File(path, "r+")
    except OSError as e:
        fail(tool, f"{path}: cannot open: {e}")
    if (f.attrs.get("format", b"") not in (b"vres-store", "vres-store") or "Domains" not in f
            or (dim is not None and int(f.attrs.get("dim", 0)) != dim)):
        f.close()
        fail(tool, f"{path}: not a {'%d-D ' % dim if dim is not None else ''}vres store")
    return f


def domains(f):
    """The names of the store's domains, D0, D1, ..., in order."""
    return sorted((k for k in f["Domains"].keys() if k[0] == "D" and k[1:].isdigit()), key=lambda k: int(k[1:]))


def note_history(f, tool):
    """Put a line naming this command (UTC time, the tool, its arguments) at the top of the
    store's history attribute."""
    old = f.attrs.get("history", b"")
    old = old.decode() if isinstance(old, bytes) else str(old)
    line = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()) + " " + " ".join([tool] + sys.argv[1:])
    f.attrs.create("history", np.bytes_(line + ("\n" + old if old else "")))
