#!/usr/bin/env python3
"""Figure of a `stengmc invert` output file (file_type "stengmc-inverse"), beside it
(PNG, or --figure-format pdf|svg; --dpi).

    plot_inverse.py INVERSE.h5 [--record I]

<stem>.png, for record I (default 0; the first 16 records keep their traces):
  (a) the record's amplitude spectrum (Hann window) with the fitted model's spectrum and the
      identified lines (their 90 % intervals as bands), the naive FFT count in the legend;
  (b) P(n), the calibrated posterior of the number of sliding asperities (the raw one as
      outlines), the 90 % interval shaded, on a linear axis with each value written;
  (c) the fitted stiffness law (best by AIC; of all records pooled when there are several)
      over the identified k_i of the record (ticks with their 90 % intervals).

Reads only the layout of src/io/inverse_file.hpp; run with Debian's python3
(python3-h5py, python3-matplotlib). plot_run.py hands inverse files to plot_inverse().
"""
import argparse
import os
import sys
import textwrap

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy import stats  # noqa: E402
from figure_style import log_axis  # noqa: E402
from stengmc_h5 import add_output_options, attribute, figure_path, save_figures, use_output_options  # noqa: E402
from stengmc_h5 import open_checked as open_stengmc_file  # noqa: E402

FILE_TYPE = "stengmc-inverse"


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def law_pdf(family, first, second, k):
    """Density of the fitted law at k (lognormal: median, sigma_log; gamma, weibull: shape, scale)."""
    if family == "lognormal":
        return stats.lognorm(s=second, scale=first).pdf(k)
    if family == "gamma":
        return stats.gamma(a=first, scale=second).pdf(k)
    return stats.weibull_min(c=first, scale=second).pdf(k)


def spectrum(v, dt, padding=4):
    """Hann-windowed amplitude spectrum (MODEL.md §3), zero-padded to draw the lines' shapes."""
    w = np.hanning(len(v))
    a = 2 * np.abs(np.fft.rfft((v - v.mean()) * w, padding * len(v))) / w.sum()
    return np.fft.rfftfreq(padding * len(v), dt), a


def count_panel(ax, counts, p, raw, low, high, calibrated):
    """P(n) on a linear axis, each non-zero probability written above its bar: on a log axis
    bars have no base, and a 0.004 beside a 0.99 is invisible on a linear one without it."""
    ax.axvspan(low - 0.5, high + 0.5, color="C2", alpha=0.15, label="90 % interval")
    ax.bar(counts, p, color="C2", width=0.7, label="P(n), calibrated" if calibrated else "P(n), raw (no bank)")
    if calibrated:
        ax.bar(counts, raw, width=0.7, fill=False, edgecolor="k", lw=0.7, label="raw posterior")
    for n, value in zip(counts, p):
        if value > 0:
            ax.text(n, value + 0.02, f"{value:.2g}", ha="center", va="bottom", fontsize=7, rotation=90)
    ax.set_ylim(0, 1.18)
    ax.set_xticks(counts)
    ax.set_xlabel("number of sliding asperities n")
    ax.set_ylabel("probability [1]")
    # Below the axes: every part of the panel may hold a bar.
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, frameon=False)


def inverse_figure(path, record=0):
    """The Figure of record `record` of the inverse file `path` (see the module's docstring)."""
    f = open_stengmc_file(path, FILE_TYPE, "`stengmc invert` output file")
    names = [text(n) for n in f["inverse/records/name"][:]]
    if record >= len(names):
        sys.exit(f"{path}: record {record} does not exist ({len(names)} records)")
    traces = f"inverse/traces/record_{record}"
    if traces not in f:
        sys.exit(f"{path}: record {record} keeps no trace (only the first 16 do)")
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8), gridspec_kw={"width_ratios": [2.2, 1, 1.4]})

    # (a) spectrum with the fitted lines
    t = f[traces + "/time"][:]
    v = f[traces + "/voltage"][:]
    model = f[traces + "/model"][:]
    freq, a = spectrum(v, t[1] - t[0])
    _, am = spectrum(model, t[1] - t[0])
    offset = f["inverse/lines/offset"][:]
    lines = slice(offset[record], offset[record + 1])
    fl = f["inverse/lines/frequency_hz"][lines]
    k = f["inverse/lines/stiffness_n_per_m"][lines]
    k_low = f["inverse/lines/stiffness_low"][lines]
    k_high = f["inverse/lines/stiffness_high"][lines]
    naive = f["inverse/count/naive_fft"][record]
    ax = axes[0]
    band = (freq > 0.5 * fl.min()) & (freq < 1.6 * fl.max()) if len(fl) else freq > 0
    # The model under the record: where they agree (the lines) the record hides it, where
    # the record is noise the model shows beneath.
    ax.semilogy(freq[band] / 1e6, am[band], color="C0", lw=1.6, label="fitted model")
    ax.semilogy(freq[band] / 1e6, a[band], color="0.3", lw=0.7, alpha=0.8, label="record")
    for i, fi in enumerate(fl):  # each line's 90 % interval of k as a frequency band
        lo, hi = fi * np.sqrt(k_low[i] / k[i]), fi * np.sqrt(k_high[i] / k[i])
        ax.axvspan(lo / 1e6, hi / 1e6, color="C3", alpha=0.25, lw=0)
        ax.axvline(fi / 1e6, color="C3", lw=0.6, alpha=0.8, label="identified lines" if i == 0 else None)
    ax.set_xlabel("frequency [MHz]")
    ax.set_ylabel("amplitude [V]")
    ax.set_title(f"(a) spectrum: {len(fl)} lines identified, naive FFT count {naive:.0f}")
    ax.legend(fontsize=8, loc="upper right")

    # (b) P(n)
    counts = f["inverse/count/counts"][:]
    p = f["inverse/count/probability"][record]
    raw = f["inverse/count/raw_probability"][record]
    low, high = f["inverse/count/interval_low"][record], f["inverse/count/interval_high"][record]
    ax = axes[1]
    calibrated = int(f.attrs.get("calibrated", 0)) == 1
    count_panel(ax, counts, p, raw, low, high, calibrated)
    ax.set_title(f"(b) n = {f['inverse/count/estimate'][record]}")

    # (c) the stiffness law over the identified k
    ax = axes[2]
    pooled = len(names) > 1
    group = "inverse/pooled/laws" if pooled else "inverse/stiffness/laws"
    rows = np.arange(len(f[group + "/family"]))
    if not pooled:
        rows = rows[f[group + "/record"][:] == record]
    fitted = [r for r in rows if f[group + "/fitted"][r] == 1]
    grid = np.geomspace(max(1e-3, 0.5 * k.min()), 2.0 * k.max(), 400) if len(k) else np.geomspace(1, 1000, 10)
    for r in fitted:
        family = text(f[group + "/family"][r])
        dens = law_pdf(family, f[group + "/first"][r], f[group + "/second"][r], grid)
        dAIC = f[group + "/delta_aic"][r]
        ax.plot(grid, dens, lw=2.0 if r == fitted[0] else 1.0,
                label=f"{family} (ΔAIC {dAIC:.1f})" + (", pooled" if pooled and r == fitted[0] else ""))
    top = ax.get_ylim()[1] if fitted else 1.0
    for i in range(len(k)):
        ax.plot([k_low[i], k_high[i]], [0.03 * top] * 2, color="C3", lw=3, alpha=0.5)
        ax.plot([k[i]], [0.03 * top], "|", color="C3", ms=12)
    log_axis(ax, "x")
    ax.set_xlabel("stiffness k [N/m]")
    ax.set_ylabel("probability density [m/N]")
    med = f["inverse/stiffness/median"][record]
    sd = f["inverse/stiffness/sd_log"][record]
    ax.set_title(f"(c) median {med:.4g} N/m, sd ln k {sd:.3f}" + ("" if fitted else " (too few lines for a law)"))
    if fitted:
        ax.legend(fontsize=8)

    name = names[record]
    warnings = text(f["inverse/records/warnings"][record])
    title = f"{name}  (known device {attribute(f, 'input_file')}" + (
        f", bank {attribute(f, 'bank')})" if calibrated else ", no calibration bank)")
    if warnings:
        title += "\n" + "\n".join(textwrap.wrap("WARNING: " + warnings, 160))
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    return fig


def figures(path, record=0):
    """[(output path, Figure)] of the inverse file `path`, not yet written."""
    return [(figure_path(os.path.splitext(path)[0]), inverse_figure(path, record))]


def plot_inverse(path, record=0):
    save_figures(figures(path, record))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file")
    parser.add_argument("--record", type=int, default=0)
    add_output_options(parser)
    args = parser.parse_args()
    use_output_options(args)
    plot_inverse(args.file, args.record)


if __name__ == "__main__":
    main()
