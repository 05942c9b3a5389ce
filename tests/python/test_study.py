"""What a notebook user reads off a study before running it: every documented attribute
answers (dir() lists them), with the value the study file says (tomllib reads the file
independently) or, for random_surface, what running two realisations shows."""
import tomllib

import numpy as np

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
    names = ("file", "text", "title", "seed", "duration_s", "sample_rate_hz", "model", "surface_file",
             "output_file", "random_surface", "is_ensemble", "realisations")
    missing = [name for name in names if name not in dir(study)]
    assert not missing, f"dir(study) lacks {missing}"
    with open(source(FIG2), "rb") as f:
        toml = tomllib.load(f)
    assert study.duration_s == toml["duration_s"]
    assert study.sample_rate_hz == toml["sample_rate_hz"]
    assert study.model == toml["model"]["kind"]
    assert study.is_ensemble is ("ensemble" in toml) and study.realisations is None
