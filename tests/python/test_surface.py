"""surface.sample on numpy (issue 25): a sample is the command line's draw value for value —
`stengmc surface --seed` (its file's /summits and /asperities of each realisation) and
`stengmc run --realisation` (the run file's /asperity table) — and a surface built from
keyword arguments draws its laws: sample means, spreads and quartiles against the closed
forms within five standard errors. Errors name the argument or the key."""
import h5py
import numpy as np
import pytest
from statistics import NormalDist

from conftest import run_cli, source

SEED = 7


def file_realisations(path):
    """Per realisation id: its summits' and asperities' datasets, cut out of the flat arrays
    with the per-realisation counts (summit_count, asperity_count)."""
    out = {}
    with h5py.File(path, "r") as f:
        ids = f["realisations/realisation"][()]
        counts = {"summits": f["realisations/summit_count"][()], "asperities": f["realisations/asperity_count"][()]}
        for group, count in counts.items():
            starts = np.concatenate([[0], np.cumsum(count)])
            for name, dataset in f[group].items():
                data = dataset[()]
                assert data.shape == (starts[-1],), f"{group}/{name}: {data.shape}, {starts[-1]} rows expected"
                for j, r in enumerate(ids):
                    out.setdefault(int(r), {}).setdefault(group, {})[name] = data[starts[j]:starts[j + 1]]
    return out


# The surface file's names of the sample's arrays (the file says "element_" for the element's).
SUMMITS = ["height_m", "x_m", "y_m", "drive_phase_rad", "normal_load_n", "sampled_stiffness_n_per_m",
           "interference_m", "patch_radius_m"]
ASPERITIES = {"stiffness_n_per_m": "stiffness_n_per_m", "mass_kg": "mass_kg", "normal_load_n": "normal_load_n",
              "height_m": "height_m", "drive_phase_rad": "drive_phase_rad", "length_m": "element_length_m",
              "width_m": "element_width_m", "summit": "summit_index"}


def test_a_sample_is_the_surface_commands_draw(stengmc, tmp_path):
    path = source("surfaces/pet_on_steel_gw.toml")
    out = tmp_path / "surface.h5"
    run_cli("surface", path, "--realisations", 3, "--first", 4, "--seed", SEED, "-o", out)
    drawn = file_realisations(out)
    assert sorted(drawn) == [4, 5, 6]
    surface = stengmc.load_surface(path)
    assert surface.is_random
    for r, theirs in drawn.items():
        ours = surface.sample(realisation=r, seed=SEED)
        assert ours["realisation"] == r and ours["seed"] == SEED
        for name in SUMMITS:
            assert np.array_equal(ours["summits"][name], theirs["summits"][name]), (r, name)
        for name, dataset in ASPERITIES.items():
            assert np.array_equal(ours["asperities"][name], theirs["asperities"][dataset]), (r, name)
        assert len(ours["asperities"]["stiffness_n_per_m"]) > 0, "a realisation with nothing in contact tests little"
    # Another seed is another draw (the seed is not ignored).
    assert not np.array_equal(surface.sample(4, seed=SEED + 1)["summits"]["height_m"], drawn[4]["summits"]["height_m"])


def test_a_studys_surface_sample_is_the_run_files_asperities(stengmc, tmp_path):
    study_path = source("studies/surfaces/gw_vb10.toml")
    out = tmp_path / "run.h5"
    run_cli("run", study_path, "--realisation", 2, "--out", out)
    study = stengmc.load_study(study_path)
    sample = study.surface.sample(realisation=2)  # the study's seed
    assert sample["seed"] == study.seed
    with h5py.File(out, "r") as f:
        for name, dataset in (("stiffness_n_per_m", "k"), ("mass_kg", "m"), ("normal_load_n", "N"), ("height_m", "h"),
                              ("drive_phase_rad", "phi"), ("length_m", "l"), ("width_m", "w")):
            assert np.array_equal(sample["asperities"][name], f[f"asperity/{dataset}"][()]), name
    # A study's [surface] keys stay readable beside sample().
    assert "sample" in dir(study.surface)
    assert study.surface.to_surface().is_random


def lognormal_keys(count):
    """A surface file's keys: `count` summits, Gaussian heights, lognormal stiffnesses, every
    summit carrying a fixed load (so all are in contact), uniform drive phases."""
    return dict(kind="random", nominal_area_m2=1e-6,
                summits={"count_rule": "fixed", "count": count},
                heights={"kind": "normal", "mean": 110e-6, "std": 0.25e-6},
                stiffness={"rule": "sampled", "kind": "lognormal", "median": 60.0, "sigma_log": 0.5},
                load={"rule": "fixed", "normal_load_n": 1e-3}, drive={"phase": "uniform"})


def lognormal_surface(stengmc, count):
    return stengmc.surface(**lognormal_keys(count))


def test_a_sample_follows_its_laws(stengmc):
    # n draws of each law. Each check allows five standard errors of its statistic (the
    # sample mean: sd/sqrt(n); the sample sd: sd/sqrt(2(n-1)); the sample p-quantile of a
    # normal: sd*sqrt(p(1-p)/n)/phi(z_p)): a correct draw fails one with probability 6e-7.
    # The seed is fixed, so the outcome is reproducible either way.
    n = 4000
    sample = lognormal_surface(stengmc, n).sample(realisation=3, seed=11)
    summits, asperities = sample["summits"], sample["asperities"]
    assert len(summits["height_m"]) == n  # count_rule "fixed"
    assert np.array_equal(asperities["summit"], np.arange(n))  # a fixed load: every summit in contact

    log_k = np.log(asperities["stiffness_n_per_m"])
    mu, sigma = np.log(60.0), 0.5
    assert abs(log_k.mean() - mu) < 5 * sigma / np.sqrt(n)
    assert abs(log_k.std(ddof=1) - sigma) < 5 * sigma / np.sqrt(2 * (n - 1))
    normal = NormalDist()
    for p in (0.25, 0.5, 0.75):
        z = normal.inv_cdf(p)
        standard_error = sigma * np.sqrt(p * (1 - p) / n) / normal.pdf(z)
        assert abs(np.quantile(log_k, p) - (mu + sigma * z)) < 5 * standard_error, p

    h = summits["height_m"]
    assert abs(h.mean() - 110e-6) < 5 * 0.25e-6 / np.sqrt(n)
    assert abs(h.std(ddof=1) - 0.25e-6) < 5 * 0.25e-6 / np.sqrt(2 * (n - 1))
    assert np.array_equal(asperities["height_m"], h)

    # Uniform on [0, 2 pi) and on the square [0, sqrt(A0))^2: mean half the range, sd range/sqrt(12).
    for values, top in ((summits["drive_phase_rad"], 2 * np.pi), (summits["x_m"], 1e-3), (summits["y_m"], 1e-3)):
        assert values.min() >= 0 and values.max() < top
        assert abs(values.mean() - top / 2) < 5 * top / np.sqrt(12 * n)

    # The same (surface, seed, realisation) is the same draw; another realisation another.
    again = lognormal_surface(stengmc, n).sample(realisation=3, seed=11)
    assert np.array_equal(again["asperities"]["stiffness_n_per_m"], asperities["stiffness_n_per_m"])
    other = lognormal_surface(stengmc, n).sample(realisation=4, seed=11)
    assert not np.array_equal(other["asperities"]["stiffness_n_per_m"], asperities["stiffness_n_per_m"])


def test_a_fixed_list_gives_its_asperities(stengmc):
    surface = stengmc.load_surface(source("surfaces/paper_four_stiffnesses.toml"))
    assert not surface.is_random
    sample = surface.sample(seed=123)
    assert len(sample["summits"]["height_m"]) == 0
    assert "summit" not in sample["asperities"]
    assert len(sample["asperities"]["stiffness_n_per_m"]) == 4


def test_bad_input_names_the_argument_or_the_key(stengmc):
    surface = lognormal_surface(stengmc, 10)
    with pytest.raises(ValueError, match=r"seed = -1: expected a whole number from 0 to"):
        surface.sample(seed=-1)
    with pytest.raises(ValueError, match=r"realisation = 9223372036854775808: expected a whole number"):
        surface.sample(realisation=2**63)
    with pytest.raises(TypeError, match=r"realisation = 1.5: expected a whole number"):
        surface.sample(realisation=1.5)
    with pytest.raises(TypeError, match=r"seed = '7': expected a whole number"):
        surface.sample(seed="7")
    keys = lognormal_keys(3)
    keys["stiffness"]["sigma_log"] = -0.5
    with pytest.raises(ValueError, match=r"my_surface.toml:\d+: \[stiffness\] sigma_log = -0.5 must be > 0"):
        stengmc.surface(name="my_surface.toml", **keys)
    keys = lognormal_keys(3)
    keys["heights"]["stdev"] = 1e-6  # a key no reader takes
    with pytest.raises(ValueError, match=r"stdev"):
        stengmc.surface(**keys)
    with pytest.raises(ValueError, match=r"is a study file, not a surface file"):
        stengmc.load_surface(source("studies/paper/fig2_k155.toml"))
    with pytest.raises(TypeError, match=r"nominal_area_m2: cannot write a object in TOML"):
        stengmc.surface(kind="random", nominal_area_m2=object())
    with pytest.raises(TypeError, match=r"load_surface: expected a path"):
        stengmc.load_surface(42)
