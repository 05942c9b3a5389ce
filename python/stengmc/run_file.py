"""A run file written by `stengmc run` read back as a Run: the same attribute names, units
and nesting as study.run() returns (docs/python.md), so a notebook treats a result computed
in Python and one computed on the command line (or a cluster) alike. The names below are the
run file's datasets (README: output files); Python.open checks them against study.run()."""
import numpy as np

from .output_file import OutputFile, _h5py, _text
from .results import Run

# Run file dataset -> where Run keeps it (attribute, then keys of nested dicts). The one
# statement of that correspondence: tests/python/test_run.py checks it, dataset by dataset,
# against a run file and study.run().
RUN_FILE_DATASETS = {
    "time": ("time_s",),
    "circuit/voltage": ("voltage_v",),
    "circuit/charge": ("charge_c",),
    "circuit/measured_voltage": ("measured_voltage_v",),
    "asperity/k": ("asperities", "stiffness_n_per_m"),
    "asperity/m": ("asperities", "mass_kg"),
    "asperity/N": ("asperities", "normal_load_n"),
    "asperity/h": ("asperities", "height_m"),
    "asperity/phi": ("asperities", "drive_phase_rad"),
    "asperity/sigma": ("asperities", "charge_density_c_per_m2"),
    "asperity/d0": ("asperities", "effective_thickness_m"),
    "asperity/w": ("asperities", "width_m"),
    "asperity/l": ("asperities", "length_m"),
    "asperity/natural_frequency": ("asperities", "natural_frequency_hz"),
    "asperity/slip_fraction": ("asperities", "slip_fraction"),
    "asperity/max_x_over_l": ("asperities", "max_x_over_l"),
    "asperity/rms_velocity": ("asperities", "rms_velocity_m_per_s"),
    "asperity/solver_steps": ("asperities", "solver_steps"),
    "asperity/x": ("traces", "x_m"),
    "asperity/v": ("traces", "v_m_per_s"),
    "asperity/friction": ("traces", "friction_n"),
    "asperity/current": ("traces", "current_a"),
    "asperity/charge": ("traces", "charge_c"),
    "asperity/x0": ("traces", "x0_m"),
    "events/time": ("events", "time_s"),
    "events/asperity": ("events", "asperity"),
    "events/kind": ("events", "kind"),
    "spectrum/frequency": ("spectra", "frequency_hz"),
    "spectrum/voltage": ("spectra", "voltage_v"),
    "spectrum/current": ("spectra", "current_a"),
    "spectrum/expected_frequency": ("spectra", "expected_frequency_hz"),
    "spectrum/sliding": ("spectra", "sliding"),
    "spectrum/peaks/frequency": ("spectra", "peaks", "frequency_hz"),
    "spectrum/peaks/amplitude": ("spectra", "peaks", "amplitude_v"),
    "spectrum/peaks/prominence": ("spectra", "peaks", "prominence_v"),
    "spectrum/lines/frequency": ("spectra", "lines", "frequency_hz"),
    "spectrum/lines/amplitude": ("spectra", "lines", "amplitude_v"),
    "spectrum/lines/damping": ("spectra", "lines", "damping_per_s"),
    "spectrum/lines/phase": ("spectra", "lines", "phase_rad"),
    "spectrogram/window_time": ("spectra", "spectrogram", "time_s"),
    "spectrogram/frequency": ("spectra", "spectrogram", "frequency_hz"),
    "spectrogram/voltage": ("spectra", "spectrogram", "voltage_v"),
}
for _method in ("fft", "high_resolution"):
    for _name, _ours in (("identified", "identified"), ("matched_line", "matched_line"),
                         ("frequency_error", "frequency_error_hz"), ("amplitude", "amplitude_v")):
        RUN_FILE_DATASETS[f"spectrum/identifiability/{_method}/{_name}"] = ("spectra", "identifiability", _method, _ours)

# Files written before a dataset was renamed: its old name.
_OLDER_NAMES = {"spectrogram/window_time": "spectrogram/time"}


def _put(fields, path, value):
    for key in path[:-1]:
        fields = fields.setdefault(key, {})
    fields[path[-1]] = value


def _values(dataset):
    data = dataset[()]
    if dataset.dtype.kind in ("O", "S"):  # strings (event kinds): a list of str, as the module gives
        return [d.decode() if isinstance(d, bytes) else d for d in np.atleast_1d(data)]
    return data


class RunFile(Run, OutputFile):
    """A run file as a Run (time_s, voltage_v, asperities, traces, events, spectra, summary;
    see Run) that is also an OutputFile (attrs, groups, to_xarray()). summary holds what the
    file records of the printed summary: /circuit's attributes (voltage_rms_v [V],
    voltage_peak_v [V], final_charge_c [C], ...), valid, asperity_count; its `text` is None."""

    def __init__(self, path):
        OutputFile.__init__(self, path)
        h5py = _h5py()
        fields = {"asperities": {}, "traces": {}, "events": {}}
        with h5py.File(self.path, "r") as f:
            for dataset, where in RUN_FILE_DATASETS.items():
                found = dataset if dataset in f else _OLDER_NAMES.get(dataset)
                if found is not None and found in f:
                    _put(fields, where, _values(f[found]))
            if "spectra" in fields:  # resolution_hz, mean_v, ... and the identifiability counts are attributes
                fields["spectra"].update({k: _text(v) for k, v in f["spectrum"].attrs.items()})
                for method, ours in fields["spectra"].get("identifiability", {}).items():
                    ours.update({k: _text(v) for k, v in f[f"spectrum/identifiability/{method}"].attrs.items()})
            summary = {k: _text(v) for k, v in f["circuit"].attrs.items()} if "circuit" in f else {}
        summary["valid"] = bool(self.attrs.get("valid", 1))
        summary["asperity_count"] = len(fields["asperities"].get("stiffness_n_per_m", ()))
        summary["text"] = None
        fields["summary"] = summary
        fields["realisation"] = self.attrs.get("realisation", 0)
        Run.__init__(self, fields)

    def __repr__(self):
        return "<stengmc.RunFile " + Run.__repr__(self).removeprefix("<stengmc.Run ")
