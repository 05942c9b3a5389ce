# The Python module in use: the cells of docs/python.md, runnable as a script from the
# repository's root (`PYTHONPATH=build/python /usr/bin/python3 docs/python_example.py`) or
# cell by cell in an editor that knows `# %%`. tests/python/test_example.py runs it and
# checks that docs/python.md shows these cells and exactly the output they print.

# %% One realisation: numpy arrays and the summary the command line prints
import tomllib

import numpy as np

import stengmc

study = stengmc.load_study("studies/paper/fig2_k155.toml")
run = study.run()
print(run)
print(run.time_s.shape, run.traces["x_m"].shape, run.asperities["stiffness_n_per_m"])
print(f"V_rms {run.summary['voltage_rms_v']:.4g} V, peak {run.summary['voltage_peak_v']:.4g} V, "
      f"{len(run.events['kind'])} stick/slip events")

# %% A random surface: realisation 2 of the Greenwood-Williamson example
run = stengmc.load_study("studies/surfaces/gw_vb10.toml").run(realisation=2)
slides = run.asperities["slip_fraction"] > 0
print(f"{slides.sum()} of {slides.size} asperities slide; their median stiffness "
      f"{np.median(run.asperities['stiffness_n_per_m'][slides]):.4g} N/m")

# %% The same realisation's surface alone: summits and contact, without a run
sample = stengmc.load_study("studies/surfaces/gw_vb10.toml").surface.sample(realisation=2)  # the study's seed
summits, asperities, contact = sample["summits"], sample["asperities"], sample["contact"]
print(f"{summits['height_m'].size} summits, {asperities['summit'].size} in contact carrying {contact['total_load_n']:.3g} N "
      f"on {contact['real_area_m2']:.3g} m^2; the run's stiffnesses: "
      f"{np.array_equal(asperities['stiffness_n_per_m'], run.asperities['stiffness_n_per_m'])}")
print("heights of the first summits in contact [um]:", np.round(1e6 * summits["height_m"][asperities["summit"]][:5], 3))

# %% A study edited as a dict: the quick ensemble, one grid point, 8 realisations
with open("studies/ensembles/identifiability_quick.toml", "rb") as f:
    quick = tomllib.load(f)
del quick["ensemble"]["sweep"]
quick["ensemble"]["realisations"] = 8
ensemble = stengmc.load_study(quick, name="studies/ensembles/quick_8.toml").run_ensemble(threads=2)
v = ensemble.summary["voltage_rms_v"]
print(ensemble)
print(f"V_rms mean {v['mean'][0]:.4g} V, 95 % CI [{v['mean_low'][0]:.4g}, {v['mean_high'][0]:.4g}] ({v['mean_method'][0]})")
print("FFT identifiable per realisation:", ensemble.realisations["fft_identifiable"])

# %% A sweep from the command line in xarray: select by the swept parameters
import subprocess
import tempfile

sweep_file = f"{tempfile.mkdtemp()}/quick.h5"
subprocess.run(["build/src/stengmc", "run", "studies/ensembles/identifiability_quick.toml", "-o", sweep_file],
               check=True, capture_output=True)
groups = stengmc.open(sweep_file).to_xarray()
table = groups["summary/voltage_rms_v"]["mean"]  # one dimension per swept parameter
print(f"V_rms mean at 8 summits, sigma_log 0.5: {table.sel(surface_summits_count=8, surface_stiffness_sigma_log=0.5).item():.4g} V")
print("summits", "".join(f"{s:>10}" for s in table.surface_stiffness_sigma_log.values), " <- sigma_log; V_rms mean [V]")
for summits in table.surface_summits_count.values:
    print(f"{summits:7.0f}", "".join(f"{v:10.4g}" for v in table.sel(surface_summits_count=summits).values))

import matplotlib

matplotlib.use("Agg")  # a notebook shows the figure inline instead
import matplotlib.pyplot as plt

figure, axes = plt.subplots()
for sigma_log in table.surface_stiffness_sigma_log.values:
    table.sel(surface_stiffness_sigma_log=sigma_log).plot(ax=axes, marker="o", label=f"sigma_log {sigma_log}")
axes.set(xscale="log", yscale="log", xlabel="summits in contact", ylabel="V_rms mean [V]")
axes.legend()
figure.savefig(f"{tempfile.mkdtemp()}/vrms_vs_count.png")
print("V_rms against the swept count:", len(axes.lines), "curves of", len(axes.lines[0].get_xdata()), "points")

# %% The inverse estimator on a measured record (here the shipped demo CSV)
t, voltage = np.loadtxt("studies/inverse/demo_record.csv", delimiter=",", skiprows=1, unpack=True)
estimate = stengmc.invert(voltage, known="studies/inverse/demo_device.toml", time_s=t)
count = estimate["count"]
print(f"n = {count['estimate']} (90 % interval {count['interval_low']}-{count['interval_high']}), "
      f"P(n = {count['estimate']}) = {count['probability'][count['counts'] == count['estimate']][0]:.3f}")
print("k [N/m]:", np.round(estimate["lines"]["stiffness_n_per_m"], 2))

# %% Bad input is a ValueError naming the file and the key
try:
    stengmc.load_study({"duration_s": 1e-3, "sample_rate_hz": -1.0}, name="my_study.toml")
except ValueError as error:
    print(type(error).__name__, "-", error)
