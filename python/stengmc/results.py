"""What a run and an ensemble return: their arrays (numpy, SI units in the names) and the
summary `stengmc run` prints. The names are the run and ensemble files' (README: output
files), spelled with their units."""


class _Result:
    """Attributes from the extension's dict: each of _fields, and each of _optional or None."""
    _fields = ()
    _optional = ()

    def __init__(self, fields):
        for name in self._fields:
            setattr(self, name, fields[name])
        for name in self._optional:
            setattr(self, name, fields.get(name))


class Run(_Result):
    """One realisation of a study.

    time_s, voltage_v, charge_c      the output grid [s], V [V] and Q [C]
    measured_voltage_v               V with the study's [noise], or None without it
    asperities                       dict of per-asperity arrays (stiffness_n_per_m, mass_kg, ...)
    traces                           dict of asperity x sample arrays (x_m, v_m_per_s, friction_n,
                                     current_a, charge_c; x0_m for Model 1), as [output] keeps them
    events                           dict: time_s, asperity, kind
    spectra                          with [spectrum]: dict frequency_hz, voltage_v (amplitudes),
                                     peaks, lines (ESPRIT), identifiability, spectrogram, ...;
                                     None without
    summary                          dict: voltage_rms_v, voltage_peak_v, final_charge_c, valid,
                                     notes, ..., and text (the table the CLI prints)
    """

    _fields = ("realisation", "time_s", "voltage_v", "charge_c", "asperities", "traces", "events", "summary")
    _optional = ("measured_voltage_v", "spectra")

    def __repr__(self):
        s = self.summary
        return (f"<stengmc.Run realisation {self.realisation}: {s['asperity_count']} asperities, "
                f"{len(self.time_s)} samples, V_rms {s['voltage_rms_v']:.4g} V>")


class Ensemble(_Result):
    """Every realisation of an [ensemble] study, as the ensemble file holds them.

    realisations    dict: one entry per realisation (grid point, then id): grid_point,
                    realisation, valid, failure, asperity_offset and every scalar by name
    asperities      dict: per-asperity columns, flat; realisation j's asperities are
                    [asperity_offset[j], asperity_offset[j + 1])
    traces          dict "realisation_<r>" (in a sweep "point_<g>" -> "realisation_<r>") ->
                    time_s, voltage_v, charge_c, measured_voltage_v (kept traces only)
    summary         dict scalar -> count, mean, mean_low, mean_high, std, median, p05, p95, ...
                    (one entry per grid point), plus "pooled" and "target"
    grid, draws     a sweep's parameters and values, [[ensemble.draw]] values; None without
    text            the table the CLI prints
    realisations_requested, realisations_run, valid_realisations, threads, seconds
    """

    _fields = ("realisations", "asperities", "traces", "summary", "realisations_requested", "realisations_run",
               "valid_realisations", "threads", "seconds", "text")
    _optional = ("grid", "draws")

    def __repr__(self):
        return (f"<stengmc.Ensemble {self.realisations_run} realisations ({self.valid_realisations} valid) "
                f"on {self.threads} threads>")
