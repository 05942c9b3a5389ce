#!/usr/bin/env python3
"""Figures of stengmc output files (HDF5), beside each file.

    plot_run.py RUN.h5 [RUN2.h5 ...] [--figure-format png|pdf|svg] [--dpi N]
        <stem>.png: the run (run_figure.py); <stem>_spectrum.png when the file has
        spectra (plot_spectrum.py); other formats with --figure-format
    plot_run.py --compare A.h5 B.h5 --out F.png   voltages of several runs on one axis

`stengmc surface` files (file_type "stengmc-surface") go to plot_surface.py, ensemble
files (file_type "stengmc-ensemble") to plot_ensemble.py, `stengmc invert` files
(file_type "stengmc-inverse") to plot_inverse.py, `stengmc track` files
(file_type "stengmc-tracking") to plot_tracking.py.

Reads only the file layout documented in the README; run with Debian's python3
(python3-h5py, python3-matplotlib).
"""
import argparse
import os
import sys
import textwrap

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_ensemble  # noqa: E402  (beside this script)
import plot_inverse  # noqa: E402  (beside this script)
import plot_tracking  # noqa: E402  (beside this script)
import plot_spectrum  # noqa: E402  (beside this script)
import plot_surface  # noqa: E402  (beside this script)
from figure_style import micro, unit  # noqa: E402
from run_figure import run_figure  # noqa: E402
from stengmc_h5 import add_output_options, attribute, figure_path, refuse, save_figure, save_figures, use_output_options  # noqa: E402

# Colour words a study title may use to name its curve, as matplotlib knows them.
NAMED_COLOURS = ("blue", "red", "green", "orange", "gray", "purple")

SUPPORTED_FORMAT = 1


def open_checked(path):
    f = h5py.File(path, "r")
    kind = attribute(f, "file_type")
    if kind == plot_surface.FILE_TYPE:
        refuse(f"{path}: a `stengmc surface` file has no voltages to compare; plot it without --compare")
    if kind == plot_ensemble.FILE_TYPE:
        refuse(f"{path}: an ensemble file has no single voltage to compare; plot it without --compare")
    if kind not in ("stengmc-run", "stengmc-circuit", "stengmc-spectrum"):
        refuse(f"{path}: not a stengmc output file (file_type = {kind!r})")
    if int(f.attrs.get("format_version", 0)) != SUPPORTED_FORMAT:
        refuse(f"{path}: format_version {f.attrs.get('format_version')} is not {SUPPORTED_FORMAT}")
    return f


def figures(path):
    """[(output path, Figure)] of any stengmc output file, not yet written: the run figure
    and, when the file has spectra, the spectrum figure; surface, ensemble and inverse files
    go to their scripts. Raises what h5py raises on a file that lacks what it promises."""
    with h5py.File(path, "r") as peek:
        kind = attribute(peek, "file_type")
    for module in (plot_surface, plot_ensemble, plot_inverse, plot_tracking):
        if kind == module.FILE_TYPE:
            return module.figures(path)
    f = open_checked(path)
    stem = os.path.splitext(path)[0]
    found = []
    if "time" in f:
        found.append((figure_path(stem), run_figure(f, path)))
    elif "spectrum/voltage" not in f:  # a `stengmc spectrum` output has spectra only
        refuse(f"{path}: neither /time nor /spectrum/voltage: nothing to plot (a damaged or partial file?)")
    if "spectrum/voltage" in f:
        found.append((figure_path(stem + "_spectrum"), plot_spectrum.spectrum_figure(f, path)))
    return found


def plot_run(path):
    """Writes every figure of `path` beside it (plot_run.py FILE, `stengmc plot FILE`)."""
    save_figures(figures(path))


def compare_figure(paths):
    """The voltages of several runs on one axis (Fig. 4c: four asperities against one of
    the same area). A title that names its curve's colour, "(red)", gets that colour."""
    fig, ax = plt.subplots(figsize=(10, 4.6))
    factor, v_unit = unit("V")
    t_factor, t_unit = unit("s")
    for i, path in enumerate(paths):
        f = open_checked(path)
        v = f["circuit/voltage"][:]
        t = f["time"][: v.shape[0]]
        title = micro(attribute(f, "title")) or path
        named = [c for c in NAMED_COLOURS if f"({c})" in title]
        ax.plot(t * t_factor, v * factor, lw=0.9, color=f"tab:{named[0]}" if named else f"C{i}",
                label="\n".join(textwrap.wrap(title, 90)))
    ax.set_xlabel(f"t [{t_unit}]")
    ax.set_ylabel(f"V [{v_unit}]")
    # Above the axes: the traces fill the whole panel.
    ax.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 1.02), frameon=False)
    fig.tight_layout()
    return fig


def plot_compare(paths, out):
    fig = compare_figure(paths)
    save_figure(fig, out)
    plt.close(fig)
    print(f"figure: {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="stengmc HDF5 output files")
    parser.add_argument("--compare", action="store_true", help="overlay the voltages of all files in one figure")
    parser.add_argument("--out", help="output figure for --compare (its extension should match --figure-format)")
    add_output_options(parser)
    args = parser.parse_args()
    use_output_options(args)
    if args.compare:
        if not args.out:
            parser.error("--compare needs --out")
        if os.path.splitext(args.out)[1] != "." + args.figure_format:
            parser.error(f"--out {args.out} does not end in .{args.figure_format} (--figure-format)")
        plot_compare(args.files, args.out)
        return
    for path in args.files:
        try:
            plot_run(path)
        except (KeyError, OSError, ValueError, IndexError, TypeError) as e:
            # A file that says it is a stengmc output but lacks what its layout promises.
            refuse(f"{path}: cannot plot it: {e} (a damaged or partial file?)")


if __name__ == "__main__":
    main()
