"""The spectrum figure of a run or `stengmc spectrum` output file (<stem>_spectrum.png): the
voltage spectrum with its FFT peaks, ESPRIT lines and the expected lines (paper Fig. 6e/f),
the element-current spectra (Fig. 7a/b) and the spectrogram (Fig. 8), when present.

The frequency axis is set by the physics, not by the data's strongest bin (a drift bin of a
few kHz in any record with drift): it reaches past the highest expected line (the sliding
asperities' natural frequencies), or, without expected lines (a measured record), up to
the study's [spectrum] max_frequency_hz, else past the highest peak the analysis found
above the noise floor, else to the Nyquist frequency. Peaks and lines found beyond it are
counted in the title. Debian's python3-h5py and matplotlib."""
import textwrap

import matplotlib.pyplot as plt
import numpy as np
from figure_style import StiffnessColours, micro, unit
from stengmc_h5 import attribute

try:
    import tomllib  # Python >= 3.11: the study's [spectrum] band from the recorded input
except ImportError:  # pragma: no cover
    tomllib = None

# The axis ends this far past the highest expected line, so its peak shows whole.
HEADROOM = 1.3


def expected_lines(f):
    """The frequencies [Hz] the sliding asperities should show: /spectrum/expected_frequency
    (or, in older files, every asperity's natural frequency)."""
    for name in ("spectrum/expected_frequency", "asperity/natural_frequency"):
        if name in f:
            return f[name][:]
    return np.empty(0)


def configured_band(f):
    """The study's [spectrum] max_frequency_hz (0 or missing: none)."""
    if tomllib is None:
        return 0.0
    try:
        table = tomllib.loads(attribute(f, "input_text"))
    except (tomllib.TOMLDecodeError, TypeError):
        return 0.0
    band = table.get("spectrum", {}).get("max_frequency_hz", 0.0) if isinstance(table.get("spectrum"), dict) else 0.0
    return float(band) if isinstance(band, (int, float)) else 0.0


def frequency_limit(f, nyquist):
    """The top of the frequency axis [Hz] (see the module's docstring)."""
    lines = expected_lines(f)
    if lines.size:
        return min(nyquist, HEADROOM * float(lines.max()))
    band = configured_band(f)
    if band > 0:
        return min(nyquist, band)
    peaks = f["spectrum/peaks/frequency"][:] if "spectrum/peaks/frequency" in f else np.empty(0)
    return min(nyquist, HEADROOM * float(peaks.max())) if peaks.size and peaks.max() > 0 else nyquist


def beyond(f, name, top_hz):
    """How many of the dataset's frequencies lie above the axis."""
    return int(np.count_nonzero(f[name][:] > top_hz)) if name in f else 0


def voltage_panel(ax, f, freq, top_hz, colours):
    f_factor, _ = unit("Hz")
    ax.semilogy(freq * f_factor, f["spectrum/voltage"][:], lw=0.8, color="k", label="|V| (FFT)")
    floor = f["spectrum"].attrs.get("noise_floor_v", 0.0)
    if floor > 0:
        ax.axhline(floor, color="grey", lw=0.8, ls=":", label="noise floor")
    if "spectrum/peaks/frequency" in f and f["spectrum/peaks/frequency"].shape[0]:
        ax.plot(f["spectrum/peaks/frequency"][:] * f_factor, f["spectrum/peaks/amplitude"][:], "rv", ms=6,
                label="FFT peaks")
    if "spectrum/lines/frequency" in f and f["spectrum/lines/frequency"].shape[0]:
        ax.plot(f["spectrum/lines/frequency"][:] * f_factor, f["spectrum/lines/amplitude"][:], "b^", ms=6, mfc="none",
                label="ESPRIT lines")
    for i, fn in enumerate(expected_lines(f)):
        ax.axvline(fn * f_factor, color=colours.colour(i), lw=0.8, ls="--")
    if expected_lines(f).size:
        colours.legend_proxy(ax, "expected lines", lw=0.8, ls="--")
    ax.set_xlim(0, top_hz * f_factor)
    ax.set_ylabel("amplitude [V]")
    title = "voltage spectrum"
    id_group = "spectrum/identifiability/fft"
    if id_group in f and int(f[id_group].attrs.get("n_sliding", 0)) > 0:  # a measured record has no truth
        g = f[id_group]
        title += f"  (FFT: {int(g.attrs['n_identifiable'])}/{int(g.attrs['n_sliding'])} identifiable"
        hr = "spectrum/identifiability/high_resolution"
        if hr in f:
            title += f", ESPRIT: {int(f[hr].attrs['n_identifiable'])}/{int(f[hr].attrs['n_sliding'])}"
        title += ")"
    hidden = [(beyond(f, "spectrum/peaks/frequency", top_hz), "FFT peaks"),
              (beyond(f, "spectrum/lines/frequency", top_hz), "ESPRIT lines")]
    hidden = [f"{n} {what}" for n, what in hidden if n]
    if hidden:
        past = ", past every expected line" if expected_lines(f).size else ""
        title += f"\n{' and '.join(hidden)} above {top_hz * f_factor:.3g} MHz{past}, not shown"
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)  # beside: peaks fill the top


def current_panel(fig, ax, f, freq, top_hz, colours):
    f_factor, _ = unit("Hz")
    for i, spectrum in enumerate(f["spectrum/current"][:]):
        ax.semilogy(freq * f_factor, spectrum, lw=0.8, color=colours.colour(i),
                    label=colours.label(i) if i < colours.k.size else None)
    ax.set_xlim(0, top_hz * f_factor)
    ax.set_ylabel("amplitude [A]")
    ax.set_title("element-current spectra", fontsize=9)
    if colours.scaled:
        colours.colour_bar(fig, ax)
    else:
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)


def spectrogram_panel(fig, ax, f, top_hz):
    f_factor, f_unit = unit("Hz")
    t_factor, t_unit = unit("s")
    s = f["spectrogram/voltage"][:]
    db = 20 * np.log10(np.maximum(s, s.max() * 1e-5)).T
    # Segment centres: window_time since issue 25 (a "time" here shadowed the root's /time).
    centres = f["spectrogram/window_time" if "spectrogram/window_time" in f else "spectrogram/time"][:]
    mesh = ax.pcolormesh(centres * t_factor, f["spectrogram/frequency"][:] * f_factor, db,
                         shading="nearest", cmap="magma", rasterized=True)
    fig.colorbar(mesh, ax=ax, label="dB V", pad=0.01, fraction=0.03)
    ax.set_ylim(0, top_hz * f_factor)
    ax.set_xlabel(f"t [{t_unit}]")
    ax.set_ylabel(f"f [{f_unit}]")
    ax.set_title("spectrogram of V", fontsize=9)


def spectrum_figure(f, path):
    """The Figure of the spectra in `f` (opened from `path`)."""
    freq = f["spectrum/frequency"][:]
    top_hz = frequency_limit(f, float(freq[-1]))
    has_currents = "spectrum/current" in f
    has_spectrogram = "spectrogram/voltage" in f
    rows = 1 + has_currents + has_spectrogram
    fig, axes = plt.subplots(rows, 1, figsize=(10.5, 0.6 + 3.2 * rows), squeeze=False, layout="constrained")
    axes = axes[:, 0]
    if "asperity/k" in f:
        colours = StiffnessColours(f["asperity/k"][:], f["asperity/phi"][:] if "asperity/phi" in f else None)
    else:  # a `stengmc spectrum` file: elements without stiffnesses
        rows = f["spectrum/current"].shape[0] if has_currents else expected_lines(f).size
        colours = StiffnessColours(np.arange(1.0, rows + 1), known=False)
    voltage_panel(axes[0], f, freq, top_hz, colours)
    if has_currents:
        current_panel(fig, axes[1], f, freq, top_hz, colours)
    for ax in axes[: 1 + has_currents]:
        ax.set_xlabel(f"f [{unit('Hz')[1]}]")
    if has_spectrogram:
        spectrogram_panel(fig, axes[-1], f, top_hz)
    fig.suptitle("\n".join(textwrap.wrap(micro(attribute(f, "title")) or path, 110)), fontsize=9)
    return fig
