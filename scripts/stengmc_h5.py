"""What every stengmc figure script needs from an output file: text attributes and a
checked open (docs/output-files.md). Debian's python3-h5py and numpy."""
import os
import socket
import sys

import h5py
import numpy as np

SUPPORTED_FORMAT = 1


def refuse(message):
    """Stops with `message` and exit code 2, stengmc's code for bad input (README: exit codes)."""
    print(message, file=sys.stderr)
    sys.exit(2)


def save_figure(fig, out, dpi=110):
    """Writes `fig` as the PNG `out`, whole or not at all, as stengmc writes its outputs: under
    the temporary name <out>.<host>.<pid>.tmp beside it, renamed into place when complete. A
    write that fails (a full disk) removes the temporary and stops with the system's reason
    and exit code 1, a failure that is not bad input: no partial figure is left to look like
    a whole one."""
    temporary = f"{out}.{socket.gethostname()}.{os.getpid()}.tmp"
    try:
        fig.savefig(temporary, dpi=dpi, format="png")
        os.replace(temporary, out)
    except OSError as e:
        try:
            os.remove(temporary)
        except OSError:
            pass
        print(f"{out}: cannot write the figure: {e.strerror or e}", file=sys.stderr)
        sys.exit(1)


def attribute(node, name, default=""):
    """An attribute, with HDF5 byte strings decoded."""
    value = node.attrs.get(name, default)
    return value.decode() if isinstance(value, bytes) else value


def open_checked(path, file_type, what):
    """The file, after checking it exists, is HDF5, is a `file_type` file (`what` names it
    in the message) and has a format version this script reads; exits with a message otherwise."""
    if not os.path.isfile(path):
        refuse(f"{path}: no such file")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        refuse(f"{path}: not an HDF5 file ({e})")
    kind = attribute(f, "file_type")
    if kind != file_type:
        refuse(f"{path}: not a {what} (file_type = {kind!r}, expected {file_type!r})")
    if int(f.attrs.get("format_version", 0)) != SUPPORTED_FORMAT:
        refuse(f"{path}: format_version {f.attrs.get('format_version')} is not {SUPPORTED_FORMAT}")
    return f


def array(f, name):
    """A dataset as a numpy array, or an empty one when the file lacks it."""
    return f[name][()] if name in f and isinstance(f[name], h5py.Dataset) else np.empty(0)
