#!/usr/bin/env python3
"""Counts contact onsets as the unit steps they leave in a record (docs/inverse.md, "Next: the
onset steps"), beside the truth and, optionally, `stengmc invert`'s count of the same records.

    onset_steps_probe.py VALIDATION.h5 [INVERTED.h5] [--threshold 0.7] [--half-width 8] [--records]

A probe, not part of the estimator. The physics it reads: an asperity that comes into contact
at t_on is picked up by the belt's kinetic friction within m v_b / (mu_k N) (45 ns with the
shipped devices at 10 m/s, 4.5 ns at 1 m/s) and stays stuck, x' = v_b, until it breaks away,
so the voltage U = R sigma w v_b sum u_i steps up by exactly one unit R sigma w v_b at every
onset, whatever the asperity's stiffness or load; the shared load's nonlinearity
V = U / (1 - gamma U), gamma = eps0 / (sigma d0) (MODEL.md §2), is undone first. A step is
found by least squares on a window of +-W samples: a cubic for the other asperities' smooth
motion plus the ramp of one onset, whose coefficient h (in units) is a linear filter of the
record. A step is a local maximum of h above the threshold and 5 standard errors of h from the
noise (white noise's sd from the record's second differences); heights round to whole units
(two onsets within a ramp give 2); steps closer than W samples are one. Onsets within the
first 2W samples (t = 0 above all) are not seen: the record's start plateau counts those
(inverse/start_plateau.hpp).

Reads the layout of src/io/ensemble_file.hpp (the study text for the device; the realisations'
n_sliding for the truth) and of src/io/inverse_file.hpp; Debian's python3 (python3-h5py,
numpy; tomllib).
"""
import argparse
import sys
import tomllib

import h5py
import numpy as np

EPSILON_0 = 8.8541878128e-12


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def device(study):
    """Unit step [V], the pick-up ramp [s], gamma [1/V] and the sample step [s] of a study."""
    s = tomllib.loads(study)
    v_b = s["model"]["belt_velocity_m_per_s"]
    element = s["surface"]["element"]
    unit = s["circuit"]["load_resistance_ohm"] * element["charge_density_c_per_m2"] * element["width_m"] * v_b
    load = s["surface"]["load"]
    friction = s["model"]["kinetic_friction"] * load.get("normal_load_n", load.get("mean_load_n"))
    ramp = s["surface"]["mass"]["mass_kg"] * v_b / friction
    gamma = EPSILON_0 / (element["charge_density_c_per_m2"] * element["effective_thickness_m"])
    return unit, ramp, gamma, 1.0 / s["sample_rate_hz"]


def step_filter(half_width, ramp_s, step_s):
    """The row of the least-squares solution that gives the step's height h."""
    j = np.arange(-half_width, half_width + 1)
    ramp = np.clip(j * step_s / ramp_s, 0.0, 1.0)
    design = np.column_stack([(j / half_width) ** p for p in range(4)] + [ramp])
    return np.linalg.pinv(design)[-1]


def count_steps(record, unit, gamma, coefficients, half_width, threshold):
    """The onsets in `record` [V] as steps: their number (each height rounded to whole units) and heights."""
    u = record / (1.0 + gamma * record)
    h = np.correlate(u, coefficients, "valid") / unit
    second = np.diff(u, 2)
    sigma = 1.4826 * np.median(np.abs(second - np.median(second))) / np.sqrt(6.0)
    h_se = sigma * np.linalg.norm(coefficients) / unit
    # From the W-th on: before it the window holds the record's start, where every asperity
    # in contact at t = 0 ramps up at once, which the cubic cannot take (a false step).
    peaks = [i for i in range(half_width, len(h) - 1)
             if h[i] >= threshold and h[i] > 5.0 * h_se and h[i] >= h[i - 1] and h[i] > h[i + 1]]
    merged = []
    for i in peaks:
        if merged and i - merged[-1] < half_width:
            if h[i] > h[merged[-1]]:
                merged[-1] = i
        else:
            merged.append(i)
    heights = [float(h[i]) for i in merged]
    return sum(max(1, round(x)) for x in heights), heights


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("validation")
    parser.add_argument("inverted", nargs="?")
    parser.add_argument("--threshold", type=float, default=0.7, help="smallest step counted [units]")
    parser.add_argument("--half-width", type=int, default=8, help="the filter's half window W [samples]")
    parser.add_argument("--records", action="store_true", help="print every record")
    a = parser.parse_args(argv)
    for path, needs in ((a.validation, "realisations/n_sliding"), (a.inverted, "inverse/count/estimate")):
        if path is None:
            continue
        try:
            with h5py.File(path, "r") as f:
                if needs not in f:
                    raise OSError(f"no {needs}")
        except OSError as e:
            print(f"onset_steps_probe.py: {path}: not a readable file with /{needs} ({e})", file=sys.stderr)
            return 2
    with h5py.File(a.validation, "r") as f:
        unit, ramp, gamma, step = device(text(f.attrs["input_text"]))
        coefficients = step_filter(a.half_width, ramp, step)
        truth = f["realisations/n_sliding"][:]
        valid = f["realisations/valid"][:]
        estimate = {}
        if a.inverted:
            with h5py.File(a.inverted, "r") as g:
                for name, n in zip(g["inverse/records/name"][:], g["inverse/count/estimate"][:]):
                    estimate[int(text(name).rsplit("_", 1)[1])] = int(n)
        rows = []
        for r in range(len(truth)):
            key = f"traces/realisation_{r}"
            if key not in f or not valid[r]:
                continue
            found, heights = count_steps(f[key]["measured_voltage"][:], unit, gamma, coefficients, a.half_width, a.threshold)
            rows.append((int(truth[r]), found, estimate.get(r, -1)))
            if a.records:
                print(r, "true", int(truth[r]), "steps", found, "invert", estimate.get(r, "-"),
                      " ".join(f"{x:.2f}" for x in heights))
    n, steps, est = (np.array(c) for c in zip(*rows))
    print(f"{a.validation}: {len(n)} records; step count exact {np.mean(steps == n):.1%}; "
          f"records with no step {np.sum(steps == 0)}")
    if a.inverted:
        wrong = est != n
        agree = steps == est
        print(f"  invert exact {np.mean(~wrong):.1%}; on its {wrong.sum()} wrong counts the steps are right on "
              f"{np.sum(steps[wrong] == n[wrong])}; on its {(~wrong).sum()} right ones they disagree on "
              f"{np.sum(steps[~wrong] != n[~wrong])}; the two agree on {agree.sum()}, right on {np.sum(agree & ~wrong)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
