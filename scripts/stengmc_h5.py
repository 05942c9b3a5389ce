"""What every stengmc figure script needs from an output file: text attributes and a
checked open (docs/output-files.md). Debian's python3-h5py and numpy."""
import argparse
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


# How every script writes its figures: set once from the command line (add_output_options,
# use_output_options) and read by save_figure, so plot_run.py's hand-offs to the other
# scripts write the same format at the same resolution.
FIGURE_FORMATS = ("png", "pdf", "svg")
OUTPUT = {"format": "png", "dpi": 150}


def add_output_options(parser):
    """--figure-format and --dpi, the same on every figure script and on `stengmc plot`."""
    parser.add_argument("--figure-format", choices=FIGURE_FORMATS, default=OUTPUT["format"],
                        help="file format of the figures (default %(default)s); pdf and svg are vector")
    parser.add_argument("--dpi", type=positive_dpi, default=OUTPUT["dpi"],
                        help="resolution of PNG figures and of the raster parts of pdf/svg (default %(default)s)")


def positive_dpi(text):
    """--dpi between 20 and 1200: below, no label is legible; above, a figure is hundreds of MB."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--dpi must be an integer, not {text!r}")
    if not 20 <= value <= 1200:
        raise argparse.ArgumentTypeError(f"--dpi must be between 20 and 1200, not {value}")
    return value


def use_output_options(args):
    OUTPUT["format"] = args.figure_format
    OUTPUT["dpi"] = args.dpi


def figure_path(stem):
    """<stem>.<format> for the chosen format."""
    return f"{stem}.{OUTPUT['format']}"


def save_figure(fig, out):
    """Writes `fig` to `out` in the chosen format, whole or not at all, as stengmc writes its
    outputs: under the temporary name <out>.<host>.<pid>.tmp beside it, renamed into place
    when complete. A write that fails (a full disk) removes the temporary and stops with the
    system's reason and exit code 1, a failure that is not bad input: no partial figure is
    left to look like a whole one."""
    temporary = f"{out}.{socket.gethostname()}.{os.getpid()}.tmp"
    try:
        fig.savefig(temporary, dpi=OUTPUT["dpi"], format=OUTPUT["format"])
        os.replace(temporary, out)
    except OSError as e:
        try:
            os.remove(temporary)
        except OSError:
            pass
        print(f"{out}: cannot write the figure: {e.strerror or e}", file=sys.stderr)
        sys.exit(1)


def save_figures(pairs):
    """Writes each (output path, Figure) of `pairs` (a plot script's figures()) with
    save_figure, closes it and prints its name; returns the names written."""
    import matplotlib.pyplot as plt  # the caller has chosen the backend before this runs

    written = []
    for out, fig in pairs:
        save_figure(fig, out)
        plt.close(fig)
        print(f"figure: {out}")
        written.append(out)
    return written


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
