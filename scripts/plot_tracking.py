#!/usr/bin/env python3
"""Figure of a `stengmc track` output file (file_type "stengmc-tracking"), beside it
(PNG, or --figure-format pdf|svg; --dpi).

    plot_tracking.py TRACKING.h5

<stem>.png, three panels sharing the time axis:
  (a) the record's spectrogram (Hann windows of the tracking's length and hop) with every
      track's line over it (its windows heard), events marked (onset ^, release v, step o);
  (b) n(t): the tracked count with its 90 % band, and the naive per-window FFT peak count;
  (c) k(t) per track with its 90 % band (held values, between sightings, as a dashed line
      whose band widens with the prior's largest wear), events as vertical ticks.

Reads only the layout of src/io/tracking_file.hpp; run with Debian's python3
(python3-h5py, python3-matplotlib). plot_run.py hands tracking files to plot_tracking().
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from stengmc_h5 import add_output_options, attribute, figure_path, save_figures, use_output_options  # noqa: E402
from stengmc_h5 import open_checked as open_stengmc_file  # noqa: E402

FILE_TYPE = "stengmc-tracking"
MARKERS = {"onset": "^", "release": "v", "step": "o"}


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def spectrogram(t, v, length, hop):
    """Amplitude spectra (Hann, as the project's spectrogram) of windows `length` long every `hop`."""
    window = np.hanning(length)
    starts = range(0, len(v) - length + 1, hop)
    frames = np.array([(v[s:s + length] - v[s:s + length].mean()) * window for s in starts])
    amplitude = 2.0 * np.abs(np.fft.rfft(frames, axis=1)) / window.sum()
    dt = t[1] - t[0]
    centres = np.array([t[s] + 0.5 * (length - 1) * dt for s in starts])
    return centres, np.fft.rfftfreq(length, dt), amplitude


def tracking_figure(path):
    f = open_stengmc_file(path, FILE_TYPE, "`stengmc track` output file")
    g = f["tracking"]
    t = g["window_time"][()] * 1e6
    t_rec = g["record/time"][()]
    v_rec = g["record/voltage"][()]
    dt = t_rec[1] - t_rec[0]
    length = int(round(float(f.attrs["window_s"]) / dt))
    hop = int(round(float(f.attrs["hop_s"]) / dt))
    band = (float(f.attrs["band_low_hz"]), float(f.attrs["band_high_hz"]))
    freq = g["frequency_hz"][()]
    k, k_low, k_high = g["stiffness_n_per_m"][()], g["stiffness_low"][()], g["stiffness_high"][()]
    kinds = [text(x) for x in g["events/kind"][()]]
    times = g["events/time_s"][()] * 1e6
    tracks = g["events/track"][()]
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]

    fig, axes = plt.subplots(3, 1, figsize=(10, 10), sharex=True, gridspec_kw={"height_ratios": [1.4, 0.8, 1.2]})
    ax = axes[0]
    centres, f_bins, amplitude = spectrogram(t_rec, v_rec, length, hop)
    keep = (f_bins >= 0.8 * band[0]) & (f_bins <= min(band[1], 0.5 / dt))
    image = 20.0 * np.log10(np.maximum(amplitude[:, keep].T, 1e-30))
    top = image.max()
    ax.pcolormesh(centres * 1e6, f_bins[keep] / 1e6, image, shading="nearest", cmap="viridis", vmin=top - 60, vmax=top)
    for i in range(freq.shape[0]):
        ax.plot(t, freq[i] / 1e6, ".", ms=2.5, color="white")
        ax.plot(t, freq[i] / 1e6, "-", lw=0.8, color=colours[i % len(colours)])
    for kind, time, track in zip(kinds, times, tracks):
        row = freq[track]
        finite = np.isfinite(row)
        if finite.any():
            nearest = np.argmin(np.where(finite, np.abs(t - time), np.inf))
            ax.plot(time, row[nearest] / 1e6, MARKERS[kind], color="red", ms=6, mfc="none")
    ax.set_ylabel("frequency [MHz]")
    ax.set_title("(a) spectrogram (dB, 60 dB range) with the tracks; onset ^, release v, step o", fontsize=9, loc="left")

    ax = axes[1]
    ax.fill_between(t, g["count_low"][()], g["count_high"][()], step="mid", alpha=0.3, label="90 % interval")
    ax.step(t, g["count"][()], where="mid", label="tracked n(t)")
    ax.step(t, g["naive_count"][()], where="mid", ls=":", color="grey", label="naive FFT peak count")
    ax.set_ylabel("asperities")
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title("(b) how many slide", fontsize=9, loc="left")

    ax = axes[2]
    for i in range(k.shape[0]):
        c = colours[i % len(colours)]
        heard = np.isfinite(freq[i])
        ax.fill_between(t, k_low[i], k_high[i], alpha=0.2, color=c, lw=0)
        ax.plot(t, np.where(heard, k[i], np.nan), "-", color=c, lw=1.2, label=f"track {i}")
        ax.plot(t, np.where(heard, np.nan, k[i]), "--", color=c, lw=0.8)
    for kind, time in zip(kinds, times):
        ax.axvline(time, color="red" if kind == "step" else "grey", lw=0.6, ls="-" if kind == "step" else ":")
    heard_k = k[np.isfinite(freq) & np.isfinite(k)]
    if heard_k.size:  # a held interval can grow wide: the axis follows the heard values
        ax.set_ylim(0.8 * heard_k.min(), 1.2 * heard_k.max())
    ax.set_ylabel("stiffness k [N/m]")
    ax.set_xlabel("time [µs]")
    if k.shape[0] <= 12:
        ax.legend(fontsize=7, ncol=4, loc="upper right")
    ax.set_title("(c) stiffness per track, 90 % band (dashed: held, widening with the prior's wear)", fontsize=9, loc="left")
    fig.suptitle(f"{attribute(f, 'record')}  (known device {attribute(f, 'input_file')}, {attribute(f, 'regime')} regime)",
                 fontsize=9)
    fig.tight_layout()
    return fig


def figures(path):
    """[(output path, Figure)] of the tracking file `path`, not yet written."""
    return [(figure_path(os.path.splitext(path)[0]), tracking_figure(path))]


def plot_tracking(path):
    save_figures(figures(path))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file")
    add_output_options(parser)
    args = parser.parse_args()
    use_output_options(args)
    plot_tracking(args.file)


if __name__ == "__main__":
    main()
