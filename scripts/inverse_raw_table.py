#!/usr/bin/env python3
"""The held-out families inverted without a bank (docs/inverse.md, "validation"): what the
estimator itself counts, before any calibration, and which records its rules without a bank
warn about.

    inverse_raw_table.py VALIDATION.h5 INVERTED.h5 [VALIDATION2.h5 INVERTED2.h5 ...]

Each pair: an ensemble file of validation signals and the `stengmc invert` output of the same
file made with no --bank (the raw posterior's count). A pair's family is its validation file's
name without `.h5`. Prints a Markdown table by family: the exact-count rate, over- and
undercounts, the count's RMSE, and the share of wrong and of right counts in the misfit class
by the rules without a bank (residual rms > 1.1 x the noise, or a line's ln k error > 1e-3:
inverse/calibration_maps.hpp), with which rule fired, and the CPU time per record.

Reads only the layouts of src/io/ensemble_file.hpp and src/io/inverse_file.hpp; Debian's
python3 (python3-h5py, numpy).
"""
import os
import sys

import h5py
import numpy as np

from inverse_validation_table import text, truth, worst_line_se

MISFIT_RATIO = 1.1       # DEFAULT_MISFIT_RATIO
LINE_SE_BOUND = 1e-3     # DEFAULT_LINE_SE_BOUND


def family_rows(signals, inverted):
    """(true n, n-hat, residual rule fired, line rule fired, CPU s) per valid record."""
    t = truth(signals)
    with h5py.File(inverted, "r") as f:
        g = f["inverse"]
        names = [text(n) for n in g["records/name"][:]]
        estimate = g["count/estimate"][:]
        seconds = g["records/seconds"][:]
        residual, noise = g["records/residual_sigma_v"][:], g["records/noise_sigma_v"][:]
        k, se, offset = g["lines/stiffness_n_per_m"][:], g["lines/log_stiffness_se"][:], g["lines/offset"][:]
    rows = []
    for j, name in enumerate(names):
        r = int(name.rsplit("realisation_", 1)[1])
        if r not in t:
            continue
        misfit = residual[j] / noise[j] if noise[j] > 0 else 1.0
        worst = worst_line_se(k[offset[j]:offset[j + 1]], se[offset[j]:offset[j + 1]])
        rows.append((len(t[r][0]), int(estimate[j]), misfit > MISFIT_RATIO, worst > LINE_SE_BOUND, seconds[j]))
    return rows


def main(argv):
    if len(argv) < 2 or len(argv) % 2:
        sys.exit(__doc__)
    print("| family | signals | n exact | over | under | n RMSE | warned: wrong counts (residual, line) | "
          "warned: right counts | CPU s per record |")
    print("|---|---|---|---|---|---|---|---|---|")
    every = []
    for signals, inverted in zip(argv[0::2], argv[1::2]):
        rows = family_rows(signals, inverted)
        every += rows
        print(row(os.path.basename(signals)[:-3], rows))
    print(row("every record", every))


def row(label, rows):
    n, m = np.array([r[0] for r in rows]), np.array([r[1] for r in rows])
    by_residual, by_line = np.array([r[2] for r in rows]), np.array([r[3] for r in rows])
    warned, wrong = by_residual | by_line, m != n
    return "| %s | %d | %.1f %% | %d | %d | %.2f | %d of %d (%d, %d) | %d of %d | %.1f |" % (
        label, len(rows), 100 * np.mean(~wrong), np.sum(m > n), np.sum(m < n), np.sqrt(np.mean((m - n) ** 2)),
        np.sum(warned & wrong), np.sum(wrong), np.sum(by_residual & wrong), np.sum(by_line & wrong),
        np.sum(warned & ~wrong), np.sum(~wrong), np.mean([r[4] for r in rows]))


if __name__ == "__main__":
    main(sys.argv[1:])
