#!/usr/bin/env python3
"""Held-out validation of `stengmc track` (issue 26, "Must show"): draws N records of 1 ms from
the issue's changing-contact prior, simulates each with `stengmc run`, tracks it with
`stengmc track`, and compares with the truth the record was drawn from.

    track_validation.py N [--seed S] [--out DIR] [--binary build/src/stengmc]

The prior (one draw per record; record i is excited when i is odd, so the halves alternate):
  asperities in contact at t = 0: 5-30 (uniform); further onsets a Poisson process of 2-8 per
  ms; lifetimes exponential of mean 0.5-3 ms (a release inside the record is simulated);
  k0 lognormal of median 40-120 N/m and sigma_log 0.2-0.6, kept in [20, 160] N/m; wear
  0-30 % per ms per asperity; one step x0.85-1.15 at a uniform time in contact in a fifth of
  the asperities; v_b 5 or 10 m/s; SNR 20-35 dB; excited: eps 0.005-0.02, lambda 0.2-1 um.

Per record and in total, by regime:
  events   truth onsets (after t = 0), releases and steps found (same kind, within +-20 us;
           each found event matched once) and the found ones that match none (false);
  n(t)     windows whose count is the number of asperities in contact at the window centre,
           and the windows whose [count_low, count_high] holds it; the naive FFT count exact;
  k(t)     each track assigned to the asperity its heard stiffnesses are closest to (median
           relative difference < 5 %, overlapping in time); over the in-contact windows of
           assigned asperities where the track gives k: within 2 % of the truth, and the 90 %
           interval covering it.
Truth: k(t) = k0 (1 - w (t - onset)/1 ms) x the steps passed, frozen at the release
(docs/model.md, section 1.4). Debian's python3 with numpy and h5py.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import time

import h5py
import numpy as np

DEVICE_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studies", "monitoring",
                           "device_unexcited.toml")


def device_keys(vb, counterface):
    """The shipped unexcited device's [model], [circuit] and [surface.defaults] (Table 1-2 values:
    m = 1e-12 kg, c = 1e-7 N s/m), at belt velocity vb [m/s] with `counterface` (a [counterface]
    table, or nothing) after [model]."""
    with open(DEVICE_FILE) as f:
        text = f.read()
    keys = text[text.index("[model]"):text.index("[[surface.asperity]]")]
    keys, replaced = re.subn(r"(?m)^belt_velocity_m_per_s = .*$", "belt_velocity_m_per_s = %g" % vb, keys)
    if replaced != 1 or "\n[circuit]" not in keys:
        sys.exit("track_validation.py: %s no longer has one belt_velocity_m_per_s and a [circuit] table" % DEVICE_FILE)
    return keys.replace("\n[circuit]", "\n" + counterface + "\n[circuit]", 1)


DURATION = 1e-3
MATCH_S = 20e-6


def draw(rng, excited):
    vb = float(rng.choice([5.0, 10.0]))
    median, sigma = rng.uniform(40, 120), rng.uniform(0.2, 0.6)
    rate, mean_life = rng.uniform(2, 8), rng.uniform(0.5, 3.0)
    onsets = [0.0] * int(rng.integers(5, 31))
    t = rng.exponential(1.0 / rate) * 1e-3
    while t < DURATION - 50e-6:
        onsets.append(round(t, 8))
        t += rng.exponential(1.0 / rate) * 1e-3
    asperities = []
    for onset in onsets:
        k0 = float(np.clip(median * math.exp(sigma * rng.standard_normal()), 20, 160))
        life = rng.exponential(mean_life) * 1e-3
        release = onset + life if onset + life < DURATION - 20e-6 else math.inf
        wear = rng.uniform(0, 0.3)
        steps = []
        if rng.uniform() < 0.2:
            end = min(release, DURATION) - 20e-6
            if end > onset + 40e-6:
                steps.append((round(rng.uniform(onset + 20e-6, end), 8), rng.uniform(0.85, 1.15)))
        asperities.append(dict(k0=k0, onset=onset, release=release, wear=wear, steps=steps))
    counterface = ""
    if excited:
        counterface = "[counterface]\nfriction_modulation_rms = %.4f\ncorrelation_length_m = %.3g\n" % (
            rng.uniform(0.005, 0.02), rng.uniform(0.2e-6, 1e-6))
    return dict(vb=vb, snr=rng.uniform(20, 35), counterface=counterface, asperities=asperities)


def record_study(d, seed):
    lines = ["duration_s = %g" % DURATION, "sample_rate_hz = 100e6", "seed = %d" % seed, "",
             device_keys(d["vb"], d["counterface"])]
    for a in d["asperities"]:
        lines.append("[[surface.asperity]]")
        lines.append("stiffness_n_per_m = %.6g" % a["k0"])
        if a["onset"] > 0:
            lines.append("onset_s = %.8g" % a["onset"])
        if math.isfinite(a["release"]):
            lines.append("release_s = %.8g" % a["release"])
        if a["wear"] > 0:
            lines.append("wear_rate_per_ms = %.4f" % a["wear"])
        if a["steps"]:
            lines.append("stiffness_steps = [" + ", ".join("[%.8g, %.5f]" % s for s in a["steps"]) + "]")
    lines += ["", "[spectrum]", "high_resolution = false", "element_currents = false", "", "[noise]", "snr_db = %.2f" % d["snr"]]
    return "\n".join(lines) + "\n"


def device_study(d):
    return ("duration_s = %g\nsample_rate_hz = 100e6\n\n" % DURATION + device_keys(d["vb"], d["counterface"]) +
            "\n[[surface.asperity]]\nstiffness_n_per_m = 75\n\n[inverse]\ncount = [1, 40]\nstiffness_law = \"lognormal\"\n"
            "median_n_per_m = [40, 120]\nsigma_log = [0.2, 0.6]\nsnr_db = [20, 35]\n")


def true_k(a, t):
    end = min(t, a["release"])
    k = a["k0"] * (1 - a["wear"] * (end - a["onset"]) / 1e-3)
    for when, factor in a["steps"]:
        if when <= end:
            k *= factor
    return k


def match(truth, found):
    """Greedy one-to-one matching within MATCH_S, closest first: (matched truth, errors, unmatched found)."""
    pairs = sorted((abs(t - f), i, j) for i, t in enumerate(truth) for j, f in enumerate(found) if abs(t - f) <= MATCH_S)
    used_t, used_f, errors = set(), set(), []
    for e, i, j in pairs:
        if i in used_t or j in used_f:
            continue
        used_t.add(i)
        used_f.add(j)
        errors.append(e)
    return len(used_t), errors, len(found) - len(used_f)


def evaluate(d, path):
    f = h5py.File(path, "r")
    g = f["tracking"]
    t = g["window_time"][()]
    count, low, high, naive = g["count"][()], g["count_low"][()], g["count_high"][()], g["naive_count"][()]
    k, k_low, k_high, freq = g["stiffness_n_per_m"][()], g["stiffness_low"][()], g["stiffness_high"][()], g["frequency_hz"][()]
    kinds = [x.decode() if isinstance(x, bytes) else x for x in g["events/kind"][()]]
    times = g["events/time_s"][()]
    A = d["asperities"]
    truth = {"onset": [a["onset"] for a in A if a["onset"] > 0],
             "release": [a["release"] for a in A if math.isfinite(a["release"])],
             "step": [s[0] for a in A for s in a["steps"]]}
    r = {}
    for kind in truth:
        found = [x for x, kk in zip(times, kinds) if kk == kind and not (kind == "onset" and x < 20e-6)]
        n, errors, false = match(truth[kind], found)
        r[kind] = (len(truth[kind]), n, len(found), false, errors)
    in_contact = np.array([[a["onset"] <= x < a["release"] for x in t] for a in A])
    n_true = in_contact.sum(axis=0)
    r["count_exact"] = (int((count == n_true).sum()), len(t))
    r["count_cover"] = (int(((low <= n_true) & (n_true <= high)).sum()), len(t))
    r["naive_exact"] = (int((naive == n_true).sum()), len(t))
    # Tracks to asperities: closest median relative difference of heard k, overlapping in time.
    within = covered = total = 0
    for i in range(k.shape[0]):
        heard = np.isfinite(freq[i]) & np.isfinite(k[i])
        if not heard.any():
            continue
        best, best_d = None, 0.05
        for j, a in enumerate(A):
            overlap = heard & in_contact[j]
            if overlap.sum() < 2:
                continue
            kt = np.array([true_k(a, x) for x in t[overlap]])
            dev = float(np.median(np.abs(k[i][overlap] / kt - 1)))
            if dev < best_d:
                best, best_d = j, dev
        if best is None:
            continue
        use = np.isfinite(k[i]) & in_contact[best]
        kt = np.array([true_k(A[best], x) for x in t[use]])
        total += int(use.sum())
        within += int((np.abs(k[i][use] / kt - 1) <= 0.02).sum())
        covered += int(((k_low[i][use] <= kt) & (kt <= k_high[i][use])).sum())
    r["k"] = (within, covered, total)
    r["seconds"] = float(f.attrs["seconds"])
    return r


def true_frequency(k):
    """Damped natural frequency of an asperity of stiffness k with the device_keys m, c [Hz]."""
    m, c = 1e-12, 1e-7
    return math.sqrt(max(k / m - (c / (2 * m)) ** 2, 0.0)) / (2 * math.pi)


def diagnose(d, path):
    """Unexcited: what each false onset, step and release is. For the event's track, its first line after
    the event (frequency, amplitude at the window's start extrapolated back to the event time
    along e^{-gamma t}) against the asperities in contact then: the nearest one, whether it had
    an event of another kind near, whether an earlier track already follows it (the line of a
    held track re-heard), whether the line is 2x or 3x another asperity's (a harmonic). Prints
    one line per false event; returns the classes counted."""
    f = h5py.File(path, "r")
    g = f["tracking"]
    t, start = g["window_time"][()], g["window_start"][()]
    freq = g["frequency_hz"][()]
    kinds = [x.decode() if isinstance(x, bytes) else x for x in g["events/kind"][()]]
    times, tracks = g["events/time_s"][()], g["events/track"][()]
    lw, lf, la = g["lines/window"][()], g["lines/frequency_hz"][()], g["lines/amplitude_v"][()]
    vb = d["vb"]
    gamma = 1e-7 / 2e-12
    onset_v = 1e6 * 80e-6 * 10e-6 * vb  # R sigma w v_b (docs/tracking.md, event amplitudes)
    A = d["asperities"]
    truth = {"onset": [a["onset"] for a in A if a["onset"] > 0], "release": [a["release"] for a in A if math.isfinite(a["release"])],
             "step": [s[0] for a in A for s in a["steps"]]}
    classes = {}
    for kind in ("onset", "step", "release"):
        found = [(x, tr) for x, kk, tr in zip(times, kinds, tracks) if kk == kind and not (kind == "onset" and x < 20e-6)]
        matched = set()
        pairs = sorted((abs(tt - x), i, j) for i, tt in enumerate(truth[kind]) for j, (x, _) in enumerate(found) if abs(tt - x) <= MATCH_S)
        used_t = set()
        for e, i, j in pairs:
            if i not in used_t and j not in matched:
                used_t.add(i)
                matched.add(j)
        for j, (x, tr) in enumerate(found):
            if j in matched:
                continue
            w = int(np.searchsorted(t, x - 5e-6))
            while w < len(t) and not np.isfinite(freq[tr][w]):
                w += 1
            if w >= len(t):  # (a release: the track's line is not given after it) its last line before
                heard = np.where(np.isfinite(freq[tr]))[0]
                if not len(heard):
                    print("    false %-7s %7.1f us track %2d: never heard" % (kind, 1e6 * x, tr))
                    continue
                w = int(heard[-1])
            fl = freq[tr][w]
            sel = np.where((lw == w) & (np.abs(lf - fl) < 1.0))[0]
            amp = float(la[sel[0]]) * math.exp(gamma * max(start[w] - x, 0.0)) if len(sel) else float("nan")
            # (an asperity released just before still rings: its release is heard after it)
            live = [(abs(true_frequency(true_k(a, x)) / fl - 1), n) for n, a in enumerate(A) if a["onset"] <= x < a["release"] + MATCH_S]
            near, n = min(live) if live else (1.0, -1)
            a = A[n] if n >= 0 else None
            other_event = None
            if a is not None:
                for name, e in [("onset", a["onset"]), ("release", a["release"])] + [("step", s[0]) for s in a["steps"]]:
                    if abs(e - x) <= MATCH_S and not (name == "onset" and e == 0):
                        other_event = name
            earlier = [o for o in range(freq.shape[0]) if o != tr and np.isfinite(freq[o][max(0, w - 60):w]).any() and
                       abs(np.nanmedian(freq[o][max(0, w - 60):w]) / fl - 1) < 0.02] if w > 0 else []
            harmonic = any(abs(fl / (m * true_frequency(true_k(b, x))) - 1) < 0.01 for b in A if b["onset"] <= x < b["release"] for m in (2, 3))
            if harmonic and near > 0.02:
                what = "harmonic"
            elif near > 0.02:
                what = "no asperity within 2 %"
            elif other_event:
                what = "the asperity's %s, mistaken" % other_event
            elif x < 150e-6 and not earlier:
                what = "ringing since t = 0, first heard now"
            elif earlier:
                what = "held track re-heard (an earlier track on it)"
            else:
                what = "asperity silent, no track on it"
            classes[(kind, what)] = classes.get((kind, what), 0) + 1
            release_v = 1e6 * 80e-6 * 10e-6 * 0.28e-3 / math.sqrt(1e-12 * 1e-12 * (2 * math.pi * fl) ** 2)  # R sigma w F / sqrt(k m)
            print("    false %-7s %7.1f us track %2d f %.4f MHz amp %.3g V (%.2f of onset's, %.2f of release's) nearest %.1f %% -> %s" % (
                kind, 1e6 * x, tr, fl / 1e6, amp, amp / onset_v, amp / release_v, 100 * near, what))
    return classes


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("n", type=int)
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--out", default="results/track_validation")
    parser.add_argument("--binary", default="build/src/stengmc")
    parser.add_argument("--diagnose", action="store_true", help="also print what each false unexcited event is")
    parser.add_argument("--regime", choices=("both", "unexcited", "excited"), default="both",
                        help="simulate and track only this half (every record is still drawn, so record i is the same)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    totals = {}
    diagnosed = {}
    print("%3s %-9s %4s %5s  %-13s %-13s %-13s %-9s %-9s %-9s %-15s %6s" % (
        "rec", "regime", "n0", "vb", "onsets f/t(x)", "releases", "steps", "n exact", "n cover", "naive", "k 2% / cover", "track s"))
    for i in range(args.n):
        excited = i % 2 == 1
        d = draw(rng, excited)
        if args.regime != "both" and args.regime != ("excited" if excited else "unexcited"):
            continue
        stem = os.path.join(args.out, "record_%03d" % i)
        with open(stem + ".toml", "w") as fh:
            fh.write(record_study(d, args.seed + i))
        with open(stem + "_device.toml", "w") as fh:
            fh.write(device_study(d))
        run = subprocess.run([args.binary, "run", stem + ".toml", "-o", stem + ".h5"], capture_output=True, text=True)
        if run.returncode != 0:
            print("record %d: run failed: %s" % (i, run.stdout[-300:] + run.stderr[-300:]), file=sys.stderr)
            continue
        tr = subprocess.run([args.binary, "track", stem + ".h5", "--known", stem + "_device.toml", "-o", stem + "_track.h5", "-j", "2"],
                            capture_output=True, text=True)
        if tr.returncode != 0:
            print("record %d: track failed: %s" % (i, tr.stdout[-300:] + tr.stderr[-300:]), file=sys.stderr)
            continue
        r = evaluate(d, stem + "_track.h5")
        regime = "excited" if excited else "unexcited"
        if args.diagnose and not excited:
            for key, value in diagnose(d, stem + "_track.h5").items():
                diagnosed[key] = diagnosed.get(key, 0) + value
        tot = totals.setdefault(regime, {})
        for key, value in r.items():
            if key == "seconds":
                tot.setdefault(key, []).append(value)
            elif key in ("onset", "release", "step"):
                a = tot.setdefault(key, [0, 0, 0, 0, []])
                for m in range(4):
                    a[m] += value[m]
                a[4] += value[4]
            else:
                a = tot.setdefault(key, [0] * len(value))
                for m in range(len(value)):
                    a[m] += value[m]
        ev = lambda e: "%d/%d (%d)" % (e[1], e[0], e[3])
        print("%3d %-9s %4d %5.0f  %-13s %-13s %-13s %-9s %-9s %-9s %-15s %6.2f" % (
            i, regime, sum(1 for a in d["asperities"] if a["onset"] == 0), d["vb"], ev(r["onset"]), ev(r["release"]), ev(r["step"]),
            "%d/%d" % r["count_exact"], "%d/%d" % r["count_cover"], "%d/%d" % r["naive_exact"],
            "%d/%d / %d" % (r["k"][0], r["k"][2], r["k"][1]), r["seconds"]))
    print("\nTotals (events: found/true, false = found matching no true event; timing = median |error|):")
    for regime, tot in totals.items():
        print("  %s (%d records):" % (regime, len(tot["seconds"])))
        for kind in ("onset", "release", "step"):
            t, n, found, false, errors = tot[kind]
            print("    %-8s found %d of %d (%.0f %%), false %d of %d found (%.0f %%), median |error| %s" % (
                kind, n, t, 100.0 * n / max(t, 1), false, found, 100.0 * false / max(found, 1),
                ("%.1f us" % (1e6 * float(np.median(errors)))) if errors else "-"))
        for key, what in (("count_exact", "n(t) exact"), ("count_cover", "n(t) 90 % interval covers"), ("naive_exact", "naive FFT count exact")):
            a, b = tot[key]
            print("    %-26s %d of %d windows (%.0f %%)" % (what, a, b, 100.0 * a / max(b, 1)))
        w, c, n = tot["k"]
        print("    k within 2 %%                %d of %d assigned in-contact windows (%.0f %%); 90 %% interval covers %.0f %%" % (
            w, n, 100.0 * w / max(n, 1), 100.0 * c / max(n, 1)))
        print("    tracking time              median %.2f s per 1 ms record (10^5 samples, 2 threads)" % float(np.median(tot["seconds"])))
    if diagnosed:
        print("\nFalse unexcited events by what they are (--diagnose):")
        for (kind, what), n in sorted(diagnosed.items()):
            print("  %-7s %-45s %d" % (kind, what, n))


if __name__ == "__main__":
    main()
