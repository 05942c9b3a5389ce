"""The module's run of a realisation is the command line's, bitwise: every dataset of the
run file (but the surface's population), read back with h5py, equals the module's numpy
array value for value (one library, the same study text, the same seed: nothing may
differ), and the module returns nothing the file lacks."""
import pytest

from conftest import assert_bitwise, read_datasets, run_cli, source

# The run file's datasets (README: output files) and where the module puts each.
RUN_FILE = {
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
for method in ("fft", "high_resolution"):
    for name, ours in (("identified", "identified"), ("matched_line", "matched_line"),
                       ("frequency_error", "frequency_error_hz"), ("amplitude", "amplitude_v")):
        RUN_FILE[f"spectrum/identifiability/{method}/{name}"] = ("spectra", "identifiability", method, ours)


def module_value(run, path):
    value = getattr(run, path[0])
    for key in path[1:]:
        value = value[key]
    return value


@pytest.mark.parametrize("study, realisation", [
    ("studies/paper/fig2_k155.toml", 0),    # Model 1, a fixed asperity, every trace with x0
    ("studies/surfaces/gw_vb10.toml", 3),   # Model 2, a random surface's realisation 3, [spectrum]
    ("studies/inverse/demo_record.toml", 0),  # [noise]: the measured voltage
    ("studies/paper/fig6_vb10_l50.toml", 0),  # ESPRIT lines and a spectrogram
])
def test_run_equals_the_command_line_bitwise(stengmc, tmp_path, study, realisation):
    out = tmp_path / "run.h5"
    run_cli("run", source(study), "--realisation", realisation, "--out", out)
    run = stengmc.load_study(source(study)).run(realisation=realisation)

    # Everything of the run but the surface's population (`stengmc surface` has it).
    file = {name: data for name, data in read_datasets(out, "/").items() if not name.startswith("surface/")}
    compared = 0
    for dataset, data in file.items():
        assert dataset in RUN_FILE, f"the run file's {dataset} has no counterpart in the module's result"
        assert_bitwise(module_value(run, RUN_FILE[dataset]), data, dataset)
        compared += 1
    # The module returns nothing the file lacks (measured_voltage_v is None without [noise]).
    assert run.measured_voltage_v is None or "circuit/measured_voltage" in file
    assert set(run.traces) == {path[1] for d, path in RUN_FILE.items() if path[0] == "traces" and d in file}
    assert compared >= 20
    assert (run.spectra is None) == ("spectrum/frequency" not in file)

    # The summary the CLI prints and writes as attributes.
    with __import__("h5py").File(out, "r") as f:
        for key in ("voltage_rms_v", "voltage_peak_v", "final_charge_c"):
            assert run.summary[key] == f["circuit"].attrs[key], key
        assert run.summary["valid"] == bool(f.attrs["valid"])
        assert run.realisation == f.attrs["realisation"]
        if run.spectra is not None:
            for method, ours in run.spectra["identifiability"].items():
                for key in ("n_sliding", "n_detected", "n_identifiable", "ratio"):
                    assert ours[key] == f[f"spectrum/identifiability/{method}"].attrs[key], (method, key)


def test_run_releases_its_arrays_to_python(stengmc):
    # The arrays belong to Python: they outlive the run object and can be written to.
    run = stengmc.load_study(source("studies/paper/fig2_k155.toml")).run()
    voltage = run.voltage_v
    del run
    voltage[0] = 1.0
    assert voltage[0] == 1.0 and voltage.dtype.name == "float64"
