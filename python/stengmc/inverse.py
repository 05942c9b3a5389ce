"""The inverse estimator on a measured record (README: inverse estimation)."""
import math
import os

import numpy as np

from . import _core
from .errors import InputError


def invert(voltage_v, known, sample_rate_hz=None, time_s=None, start_s=0.0, bank=None, name="record",
           max_memory_gb=8.0, max_steps=1e11):
    """How many asperities slide, and their stiffnesses, from one record of a known device.

    voltage_v        the measured voltage [V] (1-D)
    known            the known device's study file (with its [inverse] prior)
    sample_rate_hz   the record's sample rate [Hz], its first sample at start_s [s]; or
    time_s           the sample times [s] (uniform, as `stengmc invert` demands of a CSV)
    bank             a calibration bank from `stengmc calibrate` (None: uncalibrated answer)
    max_memory_gb    refuse, before starting, an inversion estimated to need more memory [GB]
    max_steps        ... or more solver steps (~100 ns each): `stengmc invert`'s --max-memory-gb
                     and --max-steps, with the same defaults

    Returns a dict named as the inverse file's /inverse/ datasets: count (counts,
    probability = P(n), estimate, interval_low, interval_high, ...), lines (stiffness_n_per_m
    and its 90 % interval stiffness_low/high, frequency_hz, ...), stiffness (median,
    sd_log and their intervals, laws), record (noise, SNR), verdict, warnings, model_v.
    """
    voltage = np.asarray(voltage_v, dtype=np.float64)
    if (sample_rate_hz is None) == (time_s is None):
        raise TypeError("invert: give sample_rate_hz or time_s (one of them)")
    if time_s is None:
        rate = float(sample_rate_hz)
        if not (math.isfinite(rate) and rate > 0.0):
            raise InputError(f"{name}: sample_rate_hz = {sample_rate_hz!r} must be a finite number > 0 [Hz]")
        times = start_s + np.arange(voltage.size, dtype=np.float64) / rate
    else:
        times = np.asarray(time_s, dtype=np.float64)
    return _core.invert(os.fspath(known), times, voltage, None if bank is None else os.fspath(bank), name,
                        float(max_memory_gb), float(max_steps))
