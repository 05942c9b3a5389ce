"""The module's ensemble is the command line's ensemble file, bitwise: every record
(/realisations, /asperities), kept trace and statistic (/summary), on 1 and 2 threads
(the records depend on the study and the realisation id alone, README: ensembles), from
the study's file and from its text; and the [[ensemble.draw]] values (/draws)."""
import tomllib

import numpy as np

from conftest import assert_bitwise, read_datasets, run_cli, source


def quick_study_with(ensemble):
    """studies/ensembles/identifiability_quick.toml shrunk to 20 us records, [noise] and
    [spectrum] as shipped, with the given [ensemble] table, as TOML text."""
    import stengmc
    with open(source("studies", "ensembles", "identifiability_quick.toml"), "rb") as f:
        study = tomllib.load(f)
    study["duration_s"] = 20e-6
    study["surface"]["file"] = source("surfaces", "lognormal_count.toml")
    study["ensemble"] = ensemble
    return stengmc.toml_text(study)


def small_ensemble_text(realisations=4):
    """The quick study with a two-point sweep of the count, four realisations each, one kept
    trace: a second or two."""
    return quick_study_with({"realisations": realisations, "trace_realisations": [1],
                             "sweep": [{"parameter": "surface.summits.count", "values": [2, 3]}]})


# The module's names for the trace datasets (the file's /traces/<point>/realisation_<r>/<name>).
TRACE_NAMES = {"time": "time_s", "voltage": "voltage_v", "charge": "charge_c", "measured_voltage": "measured_voltage_v"}


def xarray_coordinate(ensemble, path):
    """The coordinates the file adds for xarray (io/ensemble_coordinates.hpp), derived from
    the module's records and grid: None for any other path."""
    parts = path.split("/")
    members = len(ensemble.realisations["realisation"])
    offsets = np.asarray(ensemble.realisations["asperity_offset"])
    derived = {"realisations/member": np.arange(members), "draws/member": np.arange(members),
               "asperities/member": np.arange(members), "realisations/realisation_boundary": np.arange(members + 1),
               "asperities/asperity": np.arange(offsets[-1]), "asperities/asperity_count": np.diff(offsets)}
    if path in derived:
        return derived[path]
    grid = getattr(ensemble, "grid", None)
    if parts[0] in ("grid", "summary") and parts[-1] == "grid_point":
        return np.arange(len(grid["values"]) if grid else 1)  # without a sweep: one point
    if parts[0] in ("grid", "summary", "realisations") and grid:
        values = np.asarray(grid["values"], dtype=float).reshape(len(grid["values"]), -1)
        swept = [name.replace(".", "_") for name in grid["parameter"]]
        if parts[-1] in swept:
            column = values[:, swept.index(parts[-1])]
            # /realisations: each member's grid point's value.
            return column[np.asarray(ensemble.realisations["grid_point"])] if parts[0] == "realisations" else column
    return None


def lookup(ensemble, path):
    """The module's value for a dataset path of the ensemble file."""
    coordinate = xarray_coordinate(ensemble, path)
    if coordinate is not None:
        return coordinate
    parts = path.split("/")
    value = getattr(ensemble, parts[0])
    for key in parts[1:-1]:
        value = value[key]
    last = TRACE_NAMES[parts[-1]] if parts[0] == "traces" else parts[-1]
    return value[last]


def test_ensemble_equals_the_command_line_file_bitwise(stengmc, tmp_path):
    text = small_ensemble_text()
    study_path = tmp_path / "ensemble.toml"
    study_path.write_text(text)
    out = tmp_path / "ensemble.h5"
    run_cli("run", study_path, "--out", out, "--threads", 2)

    # The study from its file on one thread, from its text (no file read) on two.
    from_file = stengmc.load_study(study_path)
    from_text = stengmc.load_study(text, name=str(tmp_path / "not_written.toml"))
    for threads, study in ((1, from_file), (2, from_text)):
        ensemble = study.run_ensemble(threads=threads)
        assert ensemble.threads == threads
        compared = 0
        for group in ("realisations", "asperities", "traces", "summary", "grid"):
            for name, data in read_datasets(out, group).items():
                assert_bitwise(lookup(ensemble, f"{group}/{name}"), data, f"{group}/{name} on {threads} threads")
                compared += 1
        # 2 x 4 realisations: every scalar, column, statistic; one trace per point.
        assert compared > 300
        assert len(ensemble.realisations["realisation"]) == 8
        assert set(ensemble.traces) == {"point_0", "point_1"}
        assert "realisation_1" in ensemble.traces["point_0"]


def test_summary_counts_match_the_records(stengmc, tmp_path):
    # The statistics are over the valid realisations: their count per point is the records'.
    study_path = tmp_path / "ensemble.toml"
    study_path.write_text(small_ensemble_text())
    ensemble = stengmc.load_study(study_path).run_ensemble(threads=2)
    r = ensemble.realisations
    for point in (0, 1):
        valid = np.sum(r["valid"][r["grid_point"] == point])
        assert ensemble.summary["voltage_rms_v"]["count"][point] == valid


def test_drawn_parameters_equal_the_command_line_file_and_the_records(stengmc, tmp_path):
    # [[ensemble.draw]] instead of a sweep: the module's draws, records and statistics are
    # the file's bitwise, and each row of the drawn count is the number of asperities its
    # realisation simulated (the /asperities rows between its offsets), an independent fact.
    study_path = tmp_path / "drawn.toml"
    study_path.write_text(quick_study_with({"realisations": 6, "draw": [
        {"parameter": "surface.summits.count", "kind": "integer", "min": 1, "max": 4},
        {"parameter": "surface.stiffness.sigma_log", "kind": "uniform", "min": 0.1, "max": 0.3}]}))
    out = tmp_path / "drawn.h5"
    run_cli("run", study_path, "--out", out)
    ensemble = stengmc.load_study(study_path).run_ensemble(threads=2)
    for group in ("realisations", "summary", "draws"):
        for name, data in read_datasets(out, group).items():
            assert_bitwise(lookup(ensemble, f"{group}/{name}"), data, f"{group}/{name}")
    assert ensemble.draws["parameter"] == ["surface.summits.count", "surface.stiffness.sigma_log"]
    counts = ensemble.draws["values"][:, 0]
    assert np.array_equal(counts, np.diff(ensemble.realisations["asperity_offset"]))
    assert len(set(counts)) > 1, "six realisations all drew the same count"


def test_python_threads_run_while_the_ensemble_computes(stengmc, tmp_path):
    # The GIL is released around the C++: a Python thread ticking every ~10 ms gets many
    # ticks in while the ensemble runs (~0.5 s). With the GIL held it would get at most the
    # one or two the interpreter's 5 ms switch interval allows at the call's edges.
    import threading
    import time
    study = stengmc.load_study(small_ensemble_text(realisations=100), name=str(tmp_path / "ensemble.toml"))
    ticks, stop = [], threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)

    thread = threading.Thread(target=ticker)
    thread.start()
    try:
        start = time.monotonic()
        study.run_ensemble(threads=1)
        end = time.monotonic()
    finally:
        stop.set()
        thread.join()
    inside = [t for t in ticks if start < t < end]
    assert end - start > 0.2, "the ensemble ran too briefly to tell"
    assert len(inside) >= 10, f"{len(inside)} ticks in {end - start:.2f} s"
