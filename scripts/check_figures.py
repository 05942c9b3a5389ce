#!/usr/bin/env python3
"""Renders the figures of every stengmc output file in the given folders (in memory, as
`stengmc plot` would draw them) and checks each with figure_checks.py: legends inside the
figure and summarising, no cut text, no empty panel unless it says why, no round-off drawn
as signal, µm not um, and the expected lines inside the frequency axes.

    check_figures.py DIR [DIR ...] [--compare A.h5 B.h5 ...]

--compare also checks the overlay figure of those runs (run_paper_studies.sh's
fig4_comparison). Files that are not figures' sources (calibration banks) are skipped.
Exit 0: every figure passes; 1: a problem (each printed); 2: no figure found.
Debian's python3 (python3-h5py, python3-matplotlib)."""
import argparse
import glob
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_run  # noqa: E402  (beside this script)
from figure_checks import figure_problems  # noqa: E402
from stengmc_h5 import attribute  # noqa: E402

PLOTTED = ("stengmc-run", "stengmc-circuit", "stengmc-spectrum", "stengmc-surface", "stengmc-ensemble",
           "stengmc-inverse", "stengmc-tracking")


def expected_mhz(path):
    """The frequencies [MHz] a figure of `path` must show: the sliding asperities' expected
    lines of a run, the identified lines of an inversion's first record; None otherwise."""
    with h5py.File(path, "r") as f:
        for name in ("spectrum/expected_frequency", "asperity/natural_frequency"):
            if name in f and "spectrum/voltage" in f:
                return f[name][:] * 1e-6
        if "inverse/lines/frequency_hz" in f:
            offset = f["inverse/lines/offset"][:]
            return f["inverse/lines/frequency_hz"][offset[0]:offset[1]] * 1e-6
    return None


def plotted(path):
    with h5py.File(path, "r") as f:
        return attribute(f, "file_type") in PLOTTED


def check(name, fig, lines):
    problems = figure_problems(fig, lines)
    plt.close(fig)
    for problem in problems:
        print(f"FAIL {name}: {problem}")
    if not problems:
        print(f"ok   {name}")
    return len(problems)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folders", nargs="+", help="folders of stengmc output files (*.h5)")
    parser.add_argument("--compare", nargs="+", default=[], help="runs whose overlay figure is also checked")
    args = parser.parse_args()
    figures = problems = 0
    for folder in args.folders:
        for path in sorted(glob.glob(os.path.join(folder, "*.h5"))):
            if not plotted(path):
                continue
            lines = expected_mhz(path)
            rendered = plot_run.figures(path)
            if lines is not None and len(lines) and not any(
                    "MHz" in ax.get_xlabel() + ax.get_ylabel() for _, fig in rendered for ax in fig.axes):
                print(f"FAIL {path}: has expected lines but no figure with a frequency axis")
                problems += 1
            for out, fig in rendered:
                figures += 1
                problems += check(os.path.basename(out), fig, lines)
    if args.compare:
        figures += 1
        problems += check("comparison of " + ", ".join(map(os.path.basename, args.compare)),
                          plot_run.compare_figure(args.compare), None)
    print(f"{figures} figures checked, {problems} problems")
    if figures == 0:
        sys.exit(2)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
