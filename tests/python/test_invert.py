"""The module's inverse estimate of a record is `stengmc invert`'s on the same record,
bitwise: P(n), the count and its interval, each line's stiffness with its interval, the
population's median and spread, with a calibration bank and without one."""
import tomllib

import numpy as np
import pytest

from conftest import assert_bitwise, read_datasets, run_cli, source

# The shipped demo device (Table 1-2 values, Model 2 at v_b = 10 m/s, l = 50 um, 1 MOhm)
# with 20 us records and a small prior, 1-3 asperities around 60-90 N/m, as
# tests/cli/test_invert_command.cpp uses: a 50-record bank takes seconds.
SMALL_PRIOR = {"count": [1, 3], "median_n_per_m": [60, 90], "sigma_log": [0.1, 0.2], "snr_db": [25, 35],
               "calibration_records": 50, "seed": 5}


def small_device():
    with open(source("studies", "inverse", "demo_device.toml"), "rb") as f:
        device = tomllib.load(f)
    device["duration_s"] = 20e-6
    device["inverse"] = SMALL_PRIOR
    return device


@pytest.fixture(scope="module")
def device(tmp_path_factory):
    """The device study, its bank, and a record of it: two asperities (55 and 85 N/m)
    simulated by the module, plus white noise of 1e-4 V (~40 dB) from a fixed seed."""
    import stengmc
    folder = tmp_path_factory.mktemp("invert")
    known = folder / "device.toml"
    known.write_text(stengmc.toml_text(small_device()))
    bank = folder / "bank.h5"
    run_cli("calibrate", known, "-o", bank, "-j", 2)
    record = small_device()
    del record["inverse"]
    record["surface"]["asperity"] = [{"stiffness_n_per_m": 55.0}, {"stiffness_n_per_m": 85.0}]
    record = stengmc.load_study(record, name=str(folder / "record.toml")).run()
    voltage = record.voltage_v + np.random.default_rng(3).normal(0.0, 1e-4, record.voltage_v.size)
    csv = folder / "record.csv"
    # repr: the shortest decimal that reads back as the same double, so the CLI reads these values.
    csv.write_text("t,V\n" + "".join(f"{t!r},{v!r}\n" for t, v in zip(record.time_s.tolist(), voltage.tolist())))
    return {"known": known, "bank": bank, "csv": csv, "time_s": record.time_s, "voltage_v": voltage, "folder": folder}


# /inverse/ datasets of one record and where the module puts them; the CPU time is left out.
INVERSE_FILE = {
    "count/counts": ("count", "counts"), "count/estimate": ("count", "estimate"),
    "count/interval_low": ("count", "interval_low"), "count/interval_high": ("count", "interval_high"),
    "count/naive_fft": ("count", "naive_fft"), "count/probability": ("count", "probability"),
    "count/raw_probability": ("count", "raw_probability"),
    "lines/stiffness_n_per_m": ("lines", "stiffness_n_per_m"), "lines/stiffness_low": ("lines", "stiffness_low"),
    "lines/stiffness_high": ("lines", "stiffness_high"), "lines/log_stiffness_se": ("lines", "log_stiffness_se"),
    "lines/se_inflation": ("lines", "se_inflation"),
    "lines/frequency_hz": ("lines", "frequency_hz"), "lines/amplitude_v": ("lines", "amplitude_v"),
    "lines/nearest_separation_hz": ("lines", "nearest_separation_hz"),
    "stiffness/median": ("stiffness", "median"), "stiffness/median_low": ("stiffness", "median_low"),
    "stiffness/median_high": ("stiffness", "median_high"), "stiffness/sd_log": ("stiffness", "sd_log"),
    "stiffness/sd_log_low": ("stiffness", "sd_log_low"), "stiffness/sd_log_high": ("stiffness", "sd_log_high"),
    "records/noise_sigma_v": ("record", "noise_sigma_v"), "records/residual_sigma_v": ("record", "residual_sigma_v"),
    "records/signal_to_noise_db": ("record", "signal_to_noise_db"),
    "records/band_power_ratio": ("record", "band_power_ratio"),
    "traces/record_0/model": ("model_v",),
}


@pytest.mark.parametrize("calibrated", [True, False])
def test_invert_equals_the_command_line_bitwise(stengmc, device, calibrated):
    out = device["folder"] / f"inverse_{calibrated}.h5"
    bank = ["--bank", device["bank"]] if calibrated else []
    run_cli("invert", device["csv"], "--known", device["known"], *bank, "--out", out)
    ours = stengmc.invert(device["voltage_v"], known=device["known"], time_s=device["time_s"],
                          bank=device["bank"] if calibrated else None)
    file = read_datasets(out, "inverse")
    for dataset, path in INVERSE_FILE.items():
        value = ours
        for key in path:
            value = value[key]
        expected = file[dataset]
        # One record: the file's per-record vectors (and P(n) rows) hold it at index 0.
        if dataset.startswith(("count/estimate", "count/interval", "count/naive", "stiffness/", "records/")):
            expected = expected[0]
        elif dataset.endswith("probability"):
            expected = expected[0]
        assert_bitwise(value, np.asarray(expected), dataset)
    assert ours["calibrated"] == calibrated
    # The record was made with two asperities of 55 and 85 N/m at ~40 dB: the answer says so
    # (as test_invert_command.cpp's InvertsARecordAndDrawsItsFigure, to 1 %).
    assert ours["count"]["estimate"] == 2
    assert np.allclose(ours["lines"]["stiffness_n_per_m"] / [55.0, 85.0], 1.0, rtol=0, atol=1e-2)


def test_a_sample_rate_gives_the_same_answer_as_the_times(stengmc, device):
    by_times = stengmc.invert(device["voltage_v"], known=device["known"], time_s=device["time_s"])
    by_rate = stengmc.invert(device["voltage_v"], known=device["known"], sample_rate_hz=100e6)
    assert np.array_equal(by_times["count"]["probability"], by_rate["count"]["probability"])
    assert np.array_equal(by_times["lines"]["stiffness_n_per_m"], by_rate["lines"]["stiffness_n_per_m"])
