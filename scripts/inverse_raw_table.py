#!/usr/bin/env python3
"""The held-out families inverted without a bank (docs/inverse.md, "validation"): what the
estimator itself counts, before any calibration, and which records its rules without a bank
warn about.

    inverse_raw_table.py VALIDATION.h5 INVERTED.h5 [VALIDATION2.h5 INVERTED2.h5 ...]

Each pair: an ensemble file of validation signals and the `stengmc invert` output of the same
file made with no --bank (the raw posterior's count). A pair's family is its validation file's
name without `.h5`. Prints two Markdown tables, by family and by bin of the true count, of the
exact-count rate, over- and undercounts, the count's RMSE, the share of wrong and of right
counts in the misfit class by the rules without a bank (residual rms > 1.1 x the noise, or a
line's ln k error > 1e-3: inverse/calibration_maps.hpp), with which rule fired, the median
absolute relative error of the median k against the realised sample's median, the RMSE of
sd(ln k) (records with >= 2 true and identified lines), the naive FFT count's RMSE and exact
rate on the same signals, and the CPU time per record. A third table, where the files carry
them (estimator version 8 on), compares the onset steps the record shows
(/inverse/records/onset_steps, inverse/onset_steps.hpp) with the true count and the estimate.

Reads only the layouts of src/io/ensemble_file.hpp and src/io/inverse_file.hpp; Debian's
python3 (python3-h5py, numpy).
"""
import os
import sys

import h5py
import numpy as np

from inverse_validation_table import sd_log, text, truth, worst_line_se

MISFIT_RATIO = 1.1       # DEFAULT_MISFIT_RATIO
LINE_SE_BOUND = 1e-3     # DEFAULT_LINE_SE_BOUND


def family_rows(signals, inverted):
    """One dict per valid record: true n, n-hat, which rule fired, point errors, naive count, CPU s."""
    t = truth(signals)
    with h5py.File(inverted, "r") as f:
        g = f["inverse"]
        names = [text(n) for n in g["records/name"][:]]
        estimate = g["count/estimate"][:]
        naive = g["count/naive_fft"][:]
        median, sd = g["stiffness/median"][:], g["stiffness/sd_log"][:]
        seconds = g["records/seconds"][:]
        residual, noise = g["records/residual_sigma_v"][:], g["records/noise_sigma_v"][:]
        k, se, offset = g["lines/stiffness_n_per_m"][:], g["lines/log_stiffness_se"][:], g["lines/offset"][:]
        steps = g["records/onset_steps"][:] if "onset_steps" in g["records"] else None
    rows = []
    for j, name in enumerate(names):
        r = int(name.rsplit("realisation_", 1)[1])
        if r not in t:
            continue
        true_k = t[r][0]
        n, m = len(true_k), int(estimate[j])
        misfit = residual[j] / noise[j] if noise[j] > 0 else 1.0
        worst = worst_line_se(k[offset[j]:offset[j + 1]], se[offset[j]:offset[j + 1]])
        rows.append(dict(record=r, n=n, est=m, by_residual=misfit > MISFIT_RATIO, by_line=worst > LINE_SE_BOUND,
                         seconds=seconds[j], naive=int(naive[j]), steps=None if steps is None else int(steps[j]),
                         med_err=abs(median[j] / np.median(true_k) - 1.0) if n and m else None,
                         sd_err=sd[j] - sd_log(true_k) if n >= 2 and m >= 2 else None))
    return rows


HEADER = ("| {} | signals | n exact | over | under | n RMSE | warned: wrong counts (residual, line) | "
          "warned: right counts | median k: median abs. rel. error | sd(ln k) RMSE | naive FFT count: n RMSE | "
          "naive exact | CPU s per record |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|")


def main(argv):
    if len(argv) < 2 or len(argv) % 2:
        sys.exit(__doc__)
    print(HEADER.format("family"))
    families = [(os.path.basename(signals)[:-3], family_rows(signals, inverted))
                for signals, inverted in zip(argv[0::2], argv[1::2])]
    every = []
    for label, rows in families:
        every += rows
        print(row(label, rows))
    print(row("every record", every))
    stepped = [(label, rows) for label, rows in families if rows and rows[0]["steps"] is not None]
    if stepped:
        print()
        print("| family | signals | onset steps = true n | records with no step | steps = n-hat: of them right |\n"
              "|---|---|---|---|---|")
        for label, rows in stepped:
            print(steps_row(label, rows))
    print()
    print(HEADER.format("true n"))
    for lo, hi in ((0, 0), (1, 4), (5, 8), (9, 12), (13, 16)):
        sel = [r for r in every if lo <= r["n"] <= hi]
        if sel:
            print(row(f"n = {lo}" if lo == hi else f"n {lo}-{hi}", sel))


def steps_row(label, rows):
    n, m, steps = (np.array([r[key] for r in rows]) for key in ("n", "est", "steps"))
    agree = steps == m
    return "| %s | %d | %.1f %% | %d | %d of %d |" % (label, len(rows), 100 * np.mean(steps == n), np.sum(steps == 0),
                                                    np.sum(agree & (m == n)), np.sum(agree))


def row(label, rows):
    n, m = np.array([r["n"] for r in rows]), np.array([r["est"] for r in rows])
    by_residual, by_line = np.array([r["by_residual"] for r in rows]), np.array([r["by_line"] for r in rows])
    warned, wrong = by_residual | by_line, m != n
    naive_error = np.array([r["naive"] for r in rows]) - n
    med = [r["med_err"] for r in rows if r["med_err"] is not None]
    sd = [r["sd_err"] for r in rows if r["sd_err"] is not None]
    return "| %s | %d | %.1f %% | %d | %d | %.2f | %d of %d (%d, %d) | %d of %d | %s | %s | %.2f | %.1f %% | %.1f |" % (
        label, len(rows), 100 * np.mean(~wrong), np.sum(m > n), np.sum(m < n), np.sqrt(np.mean((m - n) ** 2)),
        np.sum(warned & wrong), np.sum(wrong), np.sum(by_residual & wrong), np.sum(by_line & wrong),
        np.sum(warned & ~wrong), np.sum(~wrong),
        f"{np.median(med):.2e}" if med else "–", f"{np.sqrt(np.mean(np.square(sd))):.4f}" if sd else "–",
        np.sqrt(np.mean(naive_error ** 2)), 100 * np.mean(naive_error == 0), np.mean([r["seconds"] for r in rows]))


if __name__ == "__main__":
    main(sys.argv[1:])
