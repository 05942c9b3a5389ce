#!/usr/bin/env python3
"""Energy harvested per second through the bridge rectifier against the asperity count.

    rectifier_harvest.py [--binary build/src/stengmc] [--counts 1 2 4 8 16] [--out results/circuits/harvest]

For each count n, a study like studies/circuits/bridge_rectifier.toml (Model 2, v_b = 10 m/s,
20 us at 100 MHz) whose surface is n asperities cycling through the paper's stiffnesses 25,
50, 100, 155 N/m (l = 50 um), runs through ngspice on studies/circuits/bridge_rectifier.cir.
The energy the S-TENG port delivers into the rectifier is the integral of V dQ over the run
(V the port voltage, Q the delivered charge: /circuit/voltage and /circuit/charge of the run
file, trapezoidal); divided by the duration it is the harvested power [J/s]. The storage
capacitor's voltage comes from the run's [circuit] probes v(vplus), v(vminus). Writes the
studies, run files, a table (<out>.csv) and a figure (<out>.png: the power against the count,
and the store's voltage over time per count); nothing here is committed.
Needs Debian's python3 with python3-h5py, python3-matplotlib, python3-numpy.
"""
import argparse
import os
import shutil
import subprocess

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STIFFNESSES_N_PER_M = (25, 50, 100, 155)
DURATION_S = 20e-6


def study_text(count, netlist):
    asperities = "".join(f"[[surface.asperity]]\nstiffness_n_per_m = {STIFFNESSES_N_PER_M[i % 4]}\n"
                         for i in range(count))
    return f'''title = "bridge rectifier harvest, {count} asperities"
duration_s = {DURATION_S}
sample_rate_hz = 100e6

[model]
kind = "model2"
belt_velocity_m_per_s = 10

[surface.defaults]
length_m = 50e-6

{asperities}
[circuit]
netlist = "{netlist}"
probes = ["v(vplus)", "v(vminus)"]   # the storage capacitor's two plates
'''


def store_voltage_v(run_file):
    """Time [s] and the storage capacitor's voltage v(vplus) - v(vminus) [V], from the probes."""
    with h5py.File(run_file, "r") as f:
        return f["/time"][:], f["/circuit/probes/v_vplus"][:] - f["/circuit/probes/v_vminus"][:]


def harvested_power_w(run_file):
    with h5py.File(run_file, "r") as f:
        t = f["/time"][:]
        v = f["/circuit/voltage"][:]
        q = f["/circuit/charge"][:]
    energy = float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(q)))
    return energy / (t[-1] - t[0])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=os.path.join(SOURCE_DIR, "build", "src", "stengmc"))
    parser.add_argument("--counts", type=int, nargs="+", default=[1, 2, 4, 8, 16])
    parser.add_argument("--out", default=os.path.join("results", "circuits", "harvest"))
    args = parser.parse_args()
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    # A study reads its netlist from its own folder only (docs/faults.md, "Netlists are
    # data"): the rectifier's netlist is copied beside the studies written here.
    netlist = os.path.basename(args.out) + "_bridge_rectifier.cir"
    shutil.copyfile(os.path.join(SOURCE_DIR, "studies", "circuits", "bridge_rectifier.cir"),
                    os.path.join(os.path.dirname(args.out) or ".", netlist))
    rows, stores = [], []
    for count in args.counts:
        study = f"{args.out}_n{count}.toml"
        run_file = f"{args.out}_n{count}.h5"
        with open(study, "w") as f:
            f.write(study_text(count, netlist))
        subprocess.run([args.binary, "run", study, "--out", run_file], check=True, stdout=subprocess.DEVNULL)
        rows.append((count, harvested_power_w(run_file)))
        stores.append((count, *store_voltage_v(run_file)))
        print(f"{count:3d} asperities: {rows[-1][1]:.4e} J/s")
    with open(args.out + ".csv", "w") as f:
        f.write("asperities,harvested_power_w\n")
        for count, power in rows:
            f.write(f"{count},{power:.6e}\n")
    counts, powers = zip(*rows)
    fig, (ax, store_ax) = plt.subplots(1, 2, figsize=(10, 3.8))
    ax.plot(counts, powers, "o-")
    ax.set_xlabel("asperities")
    ax.set_ylabel("energy harvested per second [J/s]")
    ax.set_title("S-TENG port into a bridge rectifier (ngspice)", fontsize=10)
    ax.set_xscale("log", base=2)
    ax.set_xticks(counts, [str(c) for c in counts])
    ax.minorticks_off()
    ax.set_yscale("log")
    ax.grid(True, which="both", alpha=0.3)
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(stores)))
    for colour, (count, t, v) in zip(colours, stores):
        store_ax.plot(t * 1e6, v * 1e3, color=colour, lw=1, label=f"{count} asperit{'y' if count == 1 else 'ies'}")
    store_ax.set_xlabel("time [µs]")
    store_ax.set_ylabel("storage capacitor voltage [mV]")
    store_ax.set_title("0.1 pF store, from [circuit] probes v(vplus) − v(vminus)", fontsize=10)
    store_ax.legend(fontsize=8, loc="upper left")
    store_ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out + ".png", dpi=150)
    print(f"wrote {args.out}.csv and {args.out}.png")


if __name__ == "__main__":
    main()
