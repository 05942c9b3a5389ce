"""Bad input raises stengmc.InputError (a ValueError) with the library's message naming
the file and the key; a model leaving its domain raises stengmc.ModelError; a study given
as a dict is the study of the file it was read from (the serializer loses nothing)."""
import tomllib

import numpy as np
import pytest

from conftest import source

FIG2 = "studies/paper/fig2_k155.toml"


def fig2_dict():
    with open(source(FIG2), "rb") as f:
        return tomllib.load(f)


def test_a_bad_value_names_the_file_and_the_key(stengmc, tmp_path):
    text = open(source(FIG2)).read().replace("sample_rate_hz = 100e6", "sample_rate_hz = -100e6")
    path = tmp_path / "bad_rate.toml"
    path.write_text(text)
    with pytest.raises(stengmc.InputError) as caught:
        stengmc.load_study(path)
    assert isinstance(caught.value, ValueError)
    assert str(path) in str(caught.value) and "sample_rate_hz" in str(caught.value)


def test_an_unknown_key_in_a_dict_names_the_given_name_and_the_key(stengmc):
    study = fig2_dict()
    study["model"]["static_fricton"] = 0.3  # misspelt
    with pytest.raises(ValueError, match=r"my_study\.toml.*static_fricton"):
        stengmc.load_study(study, name="my_study.toml")


def test_a_missing_file_is_an_input_error(stengmc, tmp_path):
    with pytest.raises(stengmc.InputError, match="no_such_study.toml"):
        stengmc.load_study(tmp_path / "no_such_study.toml")


def test_x_reaching_l_under_policy_error_is_a_model_error(stengmc):
    # Fig. 2's asperity reaches 0.79 l of l = 50 um (its run summary); with l = 5 um it
    # leaves the element's domain, which policy "error" (the default) refuses.
    study = fig2_dict()
    study["surface"]["asperity"][0]["length_m"] = 5e-6
    with pytest.raises(stengmc.ModelError, match="reache"):
        stengmc.load_study(study, name=source(FIG2)).run()


def test_a_dict_study_runs_as_the_file_it_came_from(stengmc):
    # tomllib (Python's own reader) is the reference for what the file says.
    from_file = stengmc.load_study(source(FIG2)).run()
    from_dict = stengmc.load_study(fig2_dict(), name=source(FIG2)).run()
    assert np.array_equal(from_file.voltage_v, from_dict.voltage_v)
    assert np.array_equal(from_file.traces["x_m"], from_dict.traces["x_m"])


def test_toml_text_reads_back_as_the_same_dict():
    import stengmc
    study = {"duration_s": 1e-3, "seed": 7, "title": 'a "quoted" title\nand a line', "flag": True,
             "model": {"kind": "model2", "values": [0.1, 1e-300, 3]},
             "surface": {"asperity": [{"stiffness_n_per_m": 155.0}, {"stiffness_n_per_m": 1 / 3}]}}
    assert tomllib.loads(stengmc.toml_text(study)) == study


def test_ensemble_of_a_plain_study_is_an_input_error(stengmc):
    with pytest.raises(stengmc.InputError, match=r"fig2_k155\.toml.*no \[ensemble\]"):
        stengmc.load_study(source(FIG2)).run_ensemble()


def test_invert_refuses_a_two_dimensional_record(stengmc):
    with pytest.raises(stengmc.InputError, match="my_record: voltage_v: expected a one-dimensional array"):
        stengmc.invert(np.zeros((2, 100)), known=source("studies/inverse/demo_device.toml"),
                       time_s=np.arange(100) * 1e-8, name="my_record")


DEMO = "studies/inverse/demo_device.toml"


def demo_record():
    data = np.loadtxt(source("studies/inverse/demo_record.csv"), delimiter=",", skiprows=1)
    return data[:, 0], data[:, 1]


def test_invert_takes_the_command_lines_limits_as_keyword_arguments(stengmc):
    # Python's invert had no limits: invert(np.zeros(10**8)) reached 11.5 GB. It takes
    # `stengmc invert`'s --max-memory-gb / --max-steps as max_memory_gb= / max_steps=, with
    # the same defaults, and a refusal says which argument raises the limit.
    times, volts = demo_record()
    with pytest.raises(stengmc.InputError, match=r"needs ~.* GB of memory, .* x the limit of 0\.01 GB.*raise the limit with max_memory_gb"):
        stengmc.invert(volts, known=source(DEMO), time_s=times, max_memory_gb=0.01)
    with pytest.raises(stengmc.InputError, match=r"steps, .* x the limit of 1000 steps.*raise the limit with max_steps"):
        stengmc.invert(volts, known=source(DEMO), time_s=times, max_steps=1e3)
    for argument in ("max_memory_gb", "max_steps"):
        for value in (0, -1, float("nan"), float("inf")):
            with pytest.raises(ValueError, match=f"{argument} = .* must be a finite number > 0"):
                stengmc.invert(volts, known=source(DEMO), time_s=times, **{argument: value})


def test_invert_names_a_sample_rate_that_is_not_one(stengmc):
    # sample_rate_hz=0 was reported as bad times (inf and nan).
    _, volts = demo_record()
    for rate in (0, -1e8, float("nan")):
        with pytest.raises(stengmc.InputError, match="my_record: sample_rate_hz = .* must be a finite number > 0"):
            stengmc.invert(volts, known=source(DEMO), sample_rate_hz=rate, name="my_record")


def test_invert_refuses_a_constant_record_naming_it(stengmc):
    # It stopped with the internal "count_posterior: the noise level must be > 0".
    with pytest.raises(stengmc.InputError, match="my_record: the voltage is 0 V at every sample"):
        stengmc.invert(np.zeros(5001), known=source(DEMO), sample_rate_hz=100e6, name="my_record")


ENSEMBLE = "studies/ensembles/identifiability_quick.toml"


@pytest.mark.parametrize("threads", [100000, 1025, -1, 2**64])
def test_threads_out_of_range_is_an_input_error_naming_the_argument(stengmc, threads):
    # 100000 threads made the thread library crash the interpreter (SIGSEGV); 2**64 came out
    # as pybind11's "incompatible function arguments". Refused before anything runs.
    study = stengmc.load_study(source(ENSEMBLE))
    with pytest.raises(stengmc.InputError, match=rf"threads = {threads}: expected a whole number from 0 to 1024"):
        study.run_ensemble(threads=threads)
    with pytest.raises(stengmc.InputError, match="threads"):
        stengmc.run_ensemble(study, threads=threads)


@pytest.mark.parametrize("realisation", [-1, 2**63, 2**64])
def test_a_realisation_out_of_range_is_an_input_error_naming_the_argument(stengmc, realisation):
    # pybind11's raw "incompatible function arguments" before: the id is an unsigned 64-bit
    # integer in C++, and files store it as int64 (the command line's --realisation range).
    study = stengmc.load_study(source(FIG2))
    with pytest.raises(stengmc.InputError,
                       match=rf"realisation = {realisation}: expected a whole number from 0 to {2**63 - 1}"):
        study.run(realisation=realisation)


@pytest.mark.parametrize("value", [1.5, "3", None, True])
def test_arguments_that_are_not_whole_numbers_are_type_errors_naming_them(stengmc, value):
    study = stengmc.load_study(source(FIG2))
    with pytest.raises(TypeError, match=r"realisation = .*: expected a whole number"):
        study.run(realisation=value)
    with pytest.raises(TypeError, match=r"threads = .*: expected a whole number"):
        stengmc.load_study(source(ENSEMBLE)).run_ensemble(threads=value)
