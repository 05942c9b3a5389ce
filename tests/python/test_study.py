"""What a notebook user reads off a study before running it: every documented attribute
answers (dir() lists them), with the value the study file says (tomllib reads the file
independently) or, for random_surface, what running two realisations shows."""
import tomllib

import numpy as np
import pytest

from conftest import source

FIG2 = "studies/paper/fig2_k155.toml"  # a fixed list of asperities
GW = "studies/surfaces/gw_vb10.toml"   # a Greenwood-Williamson surface drawn per realisation


def test_random_surface_is_a_bool_that_says_whether_realisations_differ(stengmc):
    # It raised "TypeError: Unable to convert function return value ... stengmc::RandomSurface".
    for path, expected in ((FIG2, False), (GW, True)):
        study = stengmc.load_study(source(path))
        assert study.random_surface is expected, path
        # What the flag promises: realisations 0 and 1 draw different asperities, or the same.
        k0, k1 = (study.run(realisation=r).asperities["stiffness_n_per_m"] for r in (0, 1))
        differ = k0.shape != k1.shape or not np.array_equal(k0, k1)
        assert differ is expected, path


def test_every_documented_attribute_is_listed_and_matches_the_file(stengmc):
    study = stengmc.load_study(source(FIG2))
    names = ("file", "text", "title", "seed", "duration_s", "sample_rate_hz", "surface_file",
             "output_file", "random_surface", "is_ensemble", "realisations",
             "model", "surface", "circuit", "domain", "noise", "spectrum", "output", "ensemble", "inverse")
    missing = [name for name in names if name not in dir(study)]
    assert not missing, f"dir(study) lacks {missing}"
    with open(source(FIG2), "rb") as f:
        toml = tomllib.load(f)
    assert study.duration_s == toml["duration_s"]
    assert study.sample_rate_hz == toml["sample_rate_hz"]
    assert study.model.kind == toml["model"]["kind"]
    assert study.is_ensemble is ("ensemble" in toml) and study.realisations is None


NOISY = "studies/inverse/demo_record.toml"  # has [noise] snr_db = 30


def test_a_set_key_runs_as_the_study_edited_by_hand(stengmc):
    study = stengmc.load_study(source(NOISY))
    study.noise.snr_db = 12.5
    study.model.belt_velocity_m_per_s = 8.0
    assert study.noise.snr_db == 12.5 and study.model.belt_velocity_m_per_s == 8.0
    with open(source(NOISY), "rb") as f:  # the same edit made on tomllib's dict
        edited = tomllib.load(f)
    edited["noise"]["snr_db"] = 12.5
    edited["model"]["belt_velocity_m_per_s"] = 8.0
    by_hand = stengmc.load_study(edited, name=source(NOISY)).run()
    ours = study.run()
    assert np.array_equal(ours.measured_voltage_v, by_hand.measured_voltage_v)
    assert not np.array_equal(ours.measured_voltage_v, stengmc.load_study(source(NOISY)).run().measured_voltage_v)


def test_a_refused_value_names_the_key_and_leaves_the_study_as_it_was(stengmc):
    study = stengmc.load_study(source(NOISY))
    text = study.text
    with pytest.raises(ValueError, match=r"noise\.snr_db = 'loud' refused: .*snr_db is a string; expected a number"):
        study.noise.snr_db = "loud"
    with pytest.raises(ValueError, match=r"noise\.snr_dB = 3 refused: .*unknown key 'noise\.snr_dB'"):
        study.noise.snr_dB = 3
    with pytest.raises(ValueError, match=r"duration_s = -1 refused: .*must be > 0"):
        study.duration_s = -1
    assert study.text == text and study.noise.snr_db == 30
    with pytest.raises(AttributeError, match=r"noise\.bandwidth_hz: not set"):
        study.noise.bandwidth_hz
