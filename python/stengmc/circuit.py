"""stengmc.circuit: the S-TENG elements and their load driven by displacements given as
numpy arrays (from a FEM model, a measurement, another run), as `stengmc circuit` drives
them from a displacement file."""
import numpy as np

from . import _core


def circuit(x_m, time_s=None, sample_rate_hz=None, *, charge_density_c_per_m2=80e-6, effective_thickness_m=50e-6,
            width_m=10e-6, length_m=10e-6, load_resistance_ohm=1e6, load_capacitance_f=0.0, interpolation="spline",
            substeps=4):
    """The terminal voltage, charge and element currents for given displacements.

    x_m                      displacement x [m]: one element's (1-D, one per sample) or
                             elements x samples (2-D); every x < length_m
    time_s / sample_rate_hz  the sample times [s] (strictly increasing), or the rate [Hz] of
                             samples from t = 0; one of the two
    charge_density_c_per_m2, effective_thickness_m, width_m, length_m
                             each element's sigma [C/m^2], d0 [m], w [m], l [m]: one value for
                             all elements or one per element (defaults: the paper's Table 2)
    load_resistance_ohm      R [Ohm]; load_capacitance_f: C_L in parallel [F]
    interpolation            x between samples: "spline" (not-a-knot) or "linear" (SPICE PWL)
    substeps                 Radau IIA steps per sample interval

    Returns a dict: time_s [s], voltage_v [V], charge_c (through R) [C], current_a and
    element_charge_c (elements x samples) [A], [C], the circuit file's /circuit datasets.
    Bad input raises stengmc.InputError (a ValueError) naming the argument.
    """
    x = np.asarray(x_m, dtype=float)
    if (time_s is None) == (sample_rate_hz is None):
        raise TypeError("circuit: give time_s [s] or sample_rate_hz [Hz], one of the two")
    if time_s is None:
        rate = float(sample_rate_hz)
        if not (np.isfinite(rate) and rate > 0):
            raise ValueError(f"circuit: sample_rate_hz = {sample_rate_hz!r} must be a finite number > 0 [Hz]")
        time_s = np.arange(x.shape[-1]) / rate
    elements = [np.atleast_1d(np.asarray(v, dtype=float))
                for v in (charge_density_c_per_m2, effective_thickness_m, width_m, length_m)]
    return _core.circuit(x, np.asarray(time_s, dtype=float), *elements, float(load_resistance_ohm),
                         float(load_capacitance_f), str(interpolation), int(substeps), "circuit")
