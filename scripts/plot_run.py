#!/usr/bin/env python3
"""Figures of stengmc output files (HDF5), as PNG beside each file.

    plot_run.py RUN.h5 [RUN2.h5 ...]          one multi-panel figure per file
    plot_run.py --compare A.h5 B.h5 --out F.png   voltages of several runs on one axis

`stengmc surface` files (file_type "stengmc-surface") go to plot_surface.py, ensemble
files (file_type "stengmc-ensemble") to plot_ensemble.py, `stengmc invert` files
(file_type "stengmc-inverse") to plot_inverse.py.

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
import numpy as np  # noqa: E402
from stengmc_h5 import attribute, refuse, save_figure  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_ensemble  # noqa: E402  (beside this script)
import plot_inverse  # noqa: E402  (beside this script)
import plot_surface  # noqa: E402  (beside this script)

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


def labels(f):
    if "asperity/k" in f:
        return [f"k = {k:g} N/m" for k in f["asperity/k"][:]]
    for rows in ("asperity/x", "spectrum/current", "spectrum/expected_frequency"):
        if rows in f:
            return [f"element {i + 1}" for i in range(f[rows].shape[0])]
    return []


def plot_run(path):
    with h5py.File(path, "r") as peek:
        kind = attribute(peek, "file_type")
    if kind == plot_surface.FILE_TYPE:
        plot_surface.plot_surface(path)
        return
    if kind == plot_ensemble.FILE_TYPE:
        plot_ensemble.plot_ensemble(path)
        return
    if kind == plot_inverse.FILE_TYPE:
        plot_inverse.plot_inverse(path)
        return
    f = open_checked(path)
    if "time" not in f:  # a `stengmc spectrum` output: spectra only
        if "spectrum/voltage" not in f:
            refuse(f"{path}: neither /time nor /spectrum/voltage: nothing to plot (a damaged or partial file?)")
        plot_spectra(path)
        return
    t_us = f["time"][:] * 1e6
    names = labels(f)
    circuit_samples = f["circuit/voltage"].shape[0]
    tc_us = t_us[:circuit_samples]
    # A study may leave traces out ([output] traces): plot what the file has.
    wanted = {"x": "asperity/x", "v": "asperity/v", "friction": "asperity/friction",
              "voltage": "circuit/voltage", "charge": "circuit/charge", "current": "asperity/current"}
    panels = [p for p in ["x", "v", "friction", "voltage", "charge", "current"] if wanted[p] in f]
    fig, axes = plt.subplots(len(panels), 1, figsize=(10, 2.3 * len(panels)), sharex=True)
    for ax, panel in zip(axes, panels):
        if panel == "x":
            x = f["asperity/x"][:]
            for i, name in enumerate(names):
                ax.plot(t_us, x[i] * 1e6, lw=1, label=name)
            if "asperity/x0" in f:
                x0 = f["asperity/x0"][:]
                for i in range(x0.shape[0]):
                    ax.plot(t_us, x0[i] * 1e6, lw=0.8, ls="--", color="grey", label="imposed x0" if i == 0 else None)
            lengths = np.unique(f["asperity/l"][:])
            for l in lengths:
                ax.axhline(l * 1e6, color="red", lw=0.8, ls=":", label=f"l = {l * 1e6:g} um")
            ax.set_ylabel("x [um]")
            ax.legend(fontsize=7, ncol=3, loc="best")
        elif panel == "v":
            v = f["asperity/v"][:]
            for i, name in enumerate(names):
                ax.plot(t_us, v[i], lw=0.8, label=name)
            ax.set_ylabel("x' [m/s]")
        elif panel == "friction":
            fr = f["asperity/friction"][:]
            for i, name in enumerate(names):
                ax.plot(t_us, fr[i] * 1e3, lw=0.8, label=name)
            ax.set_ylabel("friction [mN]")
        elif panel == "voltage":
            ax.plot(tc_us, f["circuit/voltage"][:] * 1e3, lw=0.8, color="k")
            ax.set_ylabel("V [mV]")
        elif panel == "charge":
            ax.plot(tc_us, f["circuit/charge"][:], lw=1, color="k")
            ax.set_ylabel("Q [C]")
        elif panel == "current":
            current = f["asperity/current"][:]
            for i, name in enumerate(names):
                ax.plot(tc_us, current[i], lw=0.8, label=name)
            ax.set_ylabel("i_i [A]")
        if "events/kind" in f:
            kinds = [k.decode() if isinstance(k, bytes) else k for k in f["events/kind"][:]]
            for time, kind in zip(f["events/time"][:], kinds):
                if kind == "domain_exit":
                    ax.axvline(time * 1e6, color="red", lw=1)
    axes[-1].set_xlabel("t [us]")
    title = attribute(f, "title") or path
    valid = int(f.attrs.get("valid", 1))
    if not valid:
        title += "  [INVALID: x reached l (red line); circuit cut there]"
    fig.suptitle("\n".join(textwrap.wrap(title, 110)), fontsize=9)
    fig.tight_layout()
    out = os.path.splitext(path)[0] + ".png"
    save_figure(fig, out)
    plt.close(fig)
    print(f"figure: {out}")


def plot_spectra(path):
    """Voltage spectrum with peaks, ESPRIT lines and expected lines (paper Fig. 6e/f),
    element-current spectra (Fig. 7a/b) and the spectrogram (Fig. 8), when present."""
    f = open_checked(path)
    if "spectrum/voltage" not in f:
        return
    freq_mhz = f["spectrum/frequency"][:] * 1e-6
    has_currents = "spectrum/current" in f
    has_spectrogram = "spectrogram/voltage" in f
    rows = 1 + has_currents + has_spectrogram
    fig, axes = plt.subplots(rows, 1, figsize=(10, 3.2 * rows))
    axes = np.atleast_1d(axes)
    ax = axes[0]
    ax.semilogy(freq_mhz, f["spectrum/voltage"][:], lw=0.8, color="k", label="|V| (FFT)")
    floor = f["spectrum"].attrs.get("noise_floor_v", 0.0)
    if floor > 0:
        ax.axhline(floor, color="grey", lw=0.8, ls=":", label="noise floor")
    if "spectrum/peaks/frequency" in f and f["spectrum/peaks/frequency"].shape[0]:
        ax.plot(f["spectrum/peaks/frequency"][:] * 1e-6, f["spectrum/peaks/amplitude"][:], "rv", ms=6, label="FFT peaks")
    if "spectrum/lines/frequency" in f and f["spectrum/lines/frequency"].shape[0]:
        ax.plot(f["spectrum/lines/frequency"][:] * 1e-6, f["spectrum/lines/amplitude"][:], "b^", ms=6, mfc="none",
                label="ESPRIT lines")
    expected = "spectrum/expected_frequency" if "spectrum/expected_frequency" in f else "asperity/natural_frequency"
    if expected in f:
        for i, fn in enumerate(f[expected][:]):
            ax.axvline(fn * 1e-6, color=f"C{i}", lw=0.8, ls="--")
    ax.set_xlim(0, min(freq_mhz[-1], 4.0 * max(1e-9, freq_mhz[np.argmax(f["spectrum/voltage"][1:]) + 1])))
    ax.set_ylabel("amplitude [V]")
    id_group = "spectrum/identifiability/fft"
    title = "voltage spectrum"
    if id_group in f:
        g = f[id_group]
        title += f"  (FFT: {int(g.attrs['n_identifiable'])}/{int(g.attrs['n_sliding'])} identifiable"
        hr = "spectrum/identifiability/high_resolution"
        if hr in f:
            title += f", ESPRIT: {int(f[hr].attrs['n_identifiable'])}/{int(f[hr].attrs['n_sliding'])}"
        title += "; dashed: expected lines)"
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)
    row = 1
    if has_currents:
        ax = axes[row]
        row += 1
        names = labels(f)
        for i, spectrum in enumerate(f["spectrum/current"][:]):
            ax.semilogy(freq_mhz, spectrum, lw=0.8, color=f"C{i}", label=names[i] if i < len(names) else None)
        ax.set_xlim(axes[0].get_xlim())
        ax.set_ylabel("amplitude [A]")
        ax.set_title("element-current spectra", fontsize=9)
        ax.legend(fontsize=7, ncol=4)
    for a in axes[: row]:
        a.set_xlabel("f [MHz]")
    if has_spectrogram:
        ax = axes[row]
        s = f["spectrogram/voltage"][:]
        t_us = f["spectrogram/time"][:] * 1e6
        fs_mhz = f["spectrogram/frequency"][:] * 1e-6
        db = 20 * np.log10(np.maximum(s, s.max() * 1e-5)).T
        mesh = ax.pcolormesh(t_us, fs_mhz, db, shading="nearest", cmap="magma")
        fig.colorbar(mesh, ax=ax, label="dB V")
        ax.set_ylim(0, axes[0].get_xlim()[1])
        ax.set_xlabel("t [us]")
        ax.set_ylabel("f [MHz]")
        ax.set_title("spectrogram of V", fontsize=9)
    fig.suptitle("\n".join(textwrap.wrap(attribute(f, "title") or path, 110)), fontsize=9)
    fig.tight_layout()
    out = os.path.splitext(path)[0] + "_spectrum.png"
    save_figure(fig, out)
    plt.close(fig)
    print(f"figure: {out}")


def plot_compare(paths, out):
    fig, ax = plt.subplots(figsize=(10, 4))
    for path in paths:
        f = open_checked(path)
        v = f["circuit/voltage"][:]
        t_us = f["time"][: v.shape[0]] * 1e6
        ax.plot(t_us, v * 1e3, lw=0.8, label=attribute(f, "title")[:80] or path)
    ax.set_xlabel("t [us]")
    ax.set_ylabel("V [mV]")
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, out)
    print(f"figure: {out}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="stengmc HDF5 output files")
    parser.add_argument("--compare", action="store_true", help="overlay the voltages of all files in one figure")
    parser.add_argument("--out", help="output PNG for --compare")
    args = parser.parse_args()
    if args.compare:
        if not args.out:
            parser.error("--compare needs --out")
        plot_compare(args.files, args.out)
    else:
        for path in args.files:
            try:
                plot_run(path)
                if "spectrum/voltage" in h5py.File(path, "r") and "time" in h5py.File(path, "r"):
                    plot_spectra(path)
            except (KeyError, OSError, ValueError, IndexError, TypeError) as e:
                # A file that says it is a stengmc output but lacks what its layout promises.
                refuse(f"{path}: cannot plot it: {e} (a damaged or partial file?)")


if __name__ == "__main__":
    main()
