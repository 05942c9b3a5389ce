"""run_ensemble's progress through Python (a notebook cell shows no C stderr): a callable
sees every realisation of the whole job once, in order, with the job's size as the study
says it (realisations x grid points, read with tomllib); tqdm gets the same counts; a
callback's exception stops the ensemble; anything else is a TypeError naming `progress`."""
import sys
import tomllib
import types

import pytest

from conftest import source


def small_sweep_dict():
    with open(source("studies/ensembles/identifiability_quick.toml"), "rb") as f:
        study = tomllib.load(f)
    study["ensemble"]["realisations"] = 3
    study["ensemble"]["sweep"] = [{"parameter": "surface.summits.count", "values": [1, 2]}]
    return study


def load(stengmc):
    return stengmc.load_study(small_sweep_dict(), name=source("studies/ensembles/small_sweep.toml"))


def test_a_callable_sees_every_realisation_of_the_whole_sweep(stengmc):
    study_dict = small_sweep_dict()
    total = study_dict["ensemble"]["realisations"] * len(study_dict["ensemble"]["sweep"][0]["values"])
    calls = []
    ensemble = load(stengmc).run_ensemble(threads=2, progress=lambda done, all_: calls.append((done, all_)))
    assert calls == [(done, total) for done in range(1, total + 1)]
    assert ensemble.realisations_run == total


def test_tqdm_when_installed_counts_the_same(stengmc, monkeypatch):
    bars = []

    class FakeTqdm:  # what run_ensemble uses of tqdm: total=, update(), n, close()
        def __init__(self, total, **_):
            self.total, self.n, self.closed = total, 0, False
            bars.append(self)

        def update(self, step):
            self.n += step

        def close(self):
            self.closed = True

    module = types.ModuleType("tqdm")
    module.auto = types.ModuleType("tqdm.auto")
    module.auto.tqdm = FakeTqdm
    monkeypatch.setitem(sys.modules, "tqdm", module)
    monkeypatch.setitem(sys.modules, "tqdm.auto", module.auto)
    load(stengmc).run_ensemble(threads=2, progress=True)
    assert len(bars) == 1 and bars[0].n == bars[0].total == 6 and bars[0].closed


def test_an_exception_in_the_callback_stops_the_ensemble(stengmc):
    def stop(done, total):
        if done == 2:
            raise RuntimeError("stopped by the user's callback")
    with pytest.raises(RuntimeError, match="stopped by the user's callback"):
        load(stengmc).run_ensemble(threads=1, progress=stop)


@pytest.mark.parametrize("value", ["yes", 3])
def test_progress_that_is_neither_a_bool_nor_callable_is_a_type_error(stengmc, value):
    with pytest.raises(TypeError, match=r"progress = .*: expected True"):
        load(stengmc).run_ensemble(progress=value)
