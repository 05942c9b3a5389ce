"""stengmc.open on the command line's files: a run file reads back as the Run that
study.run() returns (the module's own arrays are the reference, computed without the file),
and every kind of output file opens group by group in xarray with the values h5py reads."""
import tomllib

import h5py
import numpy as np
import pytest

from conftest import is_pure_dimension, run_cli, source


def assert_same(ours, theirs, what):
    """Equal values, recursively through dicts (keys included) and lists."""
    if isinstance(theirs, dict):
        assert isinstance(ours, dict), what
        assert set(theirs) <= set(ours), f"{what}: the file's lacks {set(theirs) - set(ours)}"
        for key in theirs:
            assert_same(ours[key], theirs[key], f"{what}/{key}")
    elif isinstance(theirs, (list, np.ndarray)):
        assert np.asarray(ours).shape == np.asarray(theirs).shape, what
        assert np.array_equal(np.asarray(ours), np.asarray(theirs)), what
    else:
        assert ours == theirs, what


@pytest.mark.parametrize("study, realisation", [
    ("studies/paper/fig2_k155.toml", 0),      # Model 1, traces with x0
    ("studies/surfaces/gw_vb10.toml", 3),     # a random surface's realisation 3, [spectrum]
    ("studies/inverse/demo_record.toml", 0),  # [noise]: measured_voltage_v
    ("studies/paper/fig6_vb10_l50.toml", 0),  # a spectrogram (/spectrogram/window_time)
])
def test_a_run_file_opens_as_the_run_the_module_computes(stengmc, tmp_path, study, realisation):
    out = tmp_path / "run.h5"
    run_cli("run", source(study), "--realisation", realisation, "--out", out)
    computed = stengmc.load_study(source(study)).run(realisation=realisation)
    opened = stengmc.open(out)
    assert isinstance(opened, stengmc.Run) and isinstance(opened, stengmc.OutputFile)
    assert opened.realisation == realisation
    for name in ("time_s", "voltage_v", "charge_c", "asperities", "traces", "events"):
        assert_same(getattr(opened, name), getattr(computed, name), name)
        if isinstance(getattr(computed, name), dict):  # nothing more than the module has either
            assert set(getattr(opened, name)) == set(getattr(computed, name)), name
    if computed.measured_voltage_v is None:
        assert opened.measured_voltage_v is None
    else:
        assert_same(opened.measured_voltage_v, computed.measured_voltage_v, "measured_voltage_v")
    if computed.spectra is None:
        assert opened.spectra is None
    else:
        assert_same(opened.spectra, computed.spectra, "spectra")
    for key in ("voltage_rms_v", "voltage_peak_v", "final_charge_c", "valid", "asperity_count"):
        assert opened.summary[key] == computed.summary[key], key
    assert repr(opened).startswith("<stengmc.RunFile realisation")


def small_sweep(tmp_path, stengmc):
    """The quick identifiability sweep cut to 2 x 1 grid points of 3 realisations."""
    with open(source("studies/ensembles/identifiability_quick.toml"), "rb") as f:
        study = tomllib.load(f)
    study["surface"]["file"] = source("surfaces/lognormal_count.toml")
    study["ensemble"]["realisations"] = 3
    study["ensemble"]["sweep"] = [{"parameter": "surface.summits.count", "values": [1, 2]}]
    path = tmp_path / "sweep.toml"
    path.write_text(stengmc.toml_text(study))
    return path


@pytest.fixture(scope="module")
def output_files(tmp_path_factory):
    """One file of each kind the commands write, named by kind."""
    import stengmc
    folder = tmp_path_factory.mktemp("open")
    files = {"run": folder / "run.h5", "ensemble": folder / "ensemble.h5", "inverse": folder / "inverse.h5",
             "spectrum": folder / "spectrum.h5"}
    run_cli("run", source("studies/surfaces/gw_vb10.toml"), "--out", files["run"])
    run_cli("run", small_sweep(folder, stengmc), "--out", files["ensemble"], "-j", 2)
    run_cli("invert", source("studies/inverse/demo_record.csv"), "--known", source("studies/inverse/demo_device.toml"),
            "--out", files["inverse"])
    run_cli("spectrum", files["run"], "--out", files["spectrum"])
    return files


def h5_groups(path):
    """{group path: {dataset name: values}} of the datasets h5py sees, every group that holds
    one (a run's /surface holds only the index coordinates its groups share), the values of
    pure dimensions and index coordinates left out."""
    groups = {}
    with h5py.File(path, "r") as f:
        def visit(name, item):
            if isinstance(item, h5py.Dataset):
                group, _, leaf = name.rpartition("/")
                variables = groups.setdefault(group or "/", {})
                if not is_pure_dimension(item):
                    variables[leaf] = item[()]
        f.visititems(visit)
    return groups


@pytest.mark.parametrize("kind", ["run", "ensemble", "inverse", "spectrum"])
def test_every_group_opens_in_xarray_with_the_values_h5py_reads(stengmc, output_files, kind):
    opened = stengmc.open(output_files[kind])
    with h5py.File(output_files[kind], "r") as f:
        assert opened.file_type == f.attrs["file_type"]
    datasets = opened.to_xarray()
    expected = h5_groups(output_files[kind])
    assert set(datasets) == set(expected), f"{kind}: groups {sorted(datasets)} against h5py's {sorted(expected)}"
    for group, variables in expected.items():
        dataset = datasets[group]
        for name, values in variables.items():
            assert name in dataset.variables, f"{kind}: {group}/{name} is not in the xarray.Dataset"
            ours = dataset[name].values
            if values.dtype.kind in ("O", "S"):
                decoded = [v.decode() if isinstance(v, bytes) else v for v in np.atleast_1d(values)]
                assert [str(v) for v in np.atleast_1d(ours)] == decoded, f"{kind}: {group}/{name}"
            else:
                # xarray masks a _FillValue as NaN: equal where h5py's value is not the fill value
                assert ours.shape == values.shape, f"{kind}: {group}/{name}"
                fill = dataset[name].encoding.get("_FillValue")
                keep = np.ones(values.shape, bool) if fill is None else values != fill
                assert np.array_equal(ours[keep], values[keep], equal_nan=True), f"{kind}: {group}/{name}"


def test_traces_get_the_roots_time_coordinate(stengmc, output_files):
    traces = stengmc.open(output_files["run"]).to_xarray()["asperity"]
    with h5py.File(output_files["run"], "r") as f:
        time = f["time"][()]
        x = f["asperity/x"][()]
    assert np.array_equal(traces["time"].values, time)
    assert np.array_equal(traces["x"].sel(time=time[100]).values, x[:, 100])


def test_open_names_what_is_wrong(stengmc, tmp_path, output_files):
    with pytest.raises(FileNotFoundError, match="no_such.h5"):
        stengmc.open(tmp_path / "no_such.h5")
    not_hdf5 = tmp_path / "record.csv"
    not_hdf5.write_text("t,V\n0,1\n")
    with pytest.raises(ValueError, match=r"record\.csv.*not an HDF5 output file"):
        stengmc.open(not_hdf5)
    with pytest.raises(ValueError, match=r"group = 'nope'"):
        stengmc.open(output_files["run"]).dataset("nope")
