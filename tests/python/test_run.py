"""The module's run of a realisation is the command line's, bitwise: every dataset of the
run file (but the surface's population), read back with h5py, equals the module's numpy
array value for value (one library, the same study text, the same seed: nothing may
differ), and the module returns nothing the file lacks."""
import pytest
from stengmc.run_file import RUN_FILE_DATASETS as RUN_FILE

from conftest import assert_bitwise, read_datasets, run_cli, source

# RUN_FILE: the run file's datasets (README: output files) and where the module puts each: the
# module's own table (stengmc.open reads files with it), checked here in both directions
# against a real run file: every dataset the file has must be in it and equal, bitwise, the
# module's value where it says.


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
