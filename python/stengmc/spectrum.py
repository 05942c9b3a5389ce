"""stengmc.spectrum: the spectral analysis of `stengmc spectrum` on a numpy array (a record
from an oscilloscope, or a run's voltage), with the [spectrum] keys as keyword arguments."""
import numpy as np

from . import _core
from .toml_text import toml_text


def spectrum(voltage_v, sample_rate_hz, **settings):
    """The amplitude spectrum, peaks and (by default) ESPRIT lines of a voltage record.

    voltage_v        1-D array of voltages [V], uniformly sampled
    sample_rate_hz   its sample rate [Hz]
    settings         any key of a study's [spectrum] table (README: study files), e.g.
                     window="hann" | "rectangular" | "blackman_harris", start_s=0.0 [s] (skip a
                     transient), end_s [s], zero_pad_factor, high_resolution=True (ESPRIT),
                     prominence_over_floor, min_frequency_hz [Hz], spectrogram={...}

    Returns a dict named as the spectrum file's datasets (a Run's `spectra`): frequency_hz
    [Hz], voltage_v (single-sided amplitudes A_k [V]; A_0 is the interval's mean, which is
    removed first), resolution_hz, mean_v, noise_floor_v, peaks (frequency_hz, amplitude_v,
    prominence_v), lines (frequency_hz, amplitude_v, damping_per_s, phase_rad), ...
    A bad key or value raises stengmc.InputError (a ValueError) naming it.
    """
    text = toml_text({"spectrum": settings})
    return _core.spectrum(np.asarray(voltage_v, dtype=float), float(sample_rate_hz), text, "stengmc.spectrum()")
