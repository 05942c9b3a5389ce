#!/usr/bin/env python3
"""The inverse validation's results table (docs/inverse.md, "validation").

    inverse_validation_table.py VALIDATION.h5 INVERTED.h5 BANK.h5 [VALIDATION2.h5 INVERTED2.h5 BANK2.h5 ...]

Each triple: an ensemble file of validation signals (`stengmc run studies/inverse/
validation*/...toml`: the truth, in /asperities and /draws), the `stengmc invert` output of the
same file (records named FILE#realisation_<r>), and the bank the inversion used. A triple's
family is its validation file's name without `.h5` (the family of issue 23's validation:
ideal, loads, onset, tolerance, noise, vb1, all, pure_noise). Prints Markdown tables, by
family, by bin of the true count and of the drawn SNR, of
  n RMSE, exact rate, coverage of the 90 % interval of n, the median absolute relative
  error of the median k, the RMSE of sd(ln k) (records with >= 2 true and identified lines),
  the coverage of the median's and sd's 90 % intervals, the coverage of each line's 90 %
  interval of k (records whose count is right: lines and truth paired in order of k), the
  share of wrong and of right counts that carry a warning, and beside them the naive FFT
  count's RMSE and exact rate on the same signals;
then what a randomised (smoothed) conformal set for n would cover (Vovk, Gammerman & Shafer
2005, ch. 2: ties broken by a uniform draw), from the banks' own records.

Reads only the layouts of src/io/ensemble_file.hpp, src/io/inverse_file.hpp and
src/io/calibration_bank_file.hpp; Debian's python3 (python3-h5py, numpy).
"""
import re
import sys

import h5py
import numpy as np

RNG = np.random.default_rng(20240611)  # the smoothed sets' tie-breaking draws (fixed: the table is reproducible)


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def truth(path):
    """realisation id -> (true stiffnesses, drawn SNR [dB]) of the valid realisations."""
    with h5py.File(path, "r") as f:
        ids = f["realisations/realisation"][:]
        valid = f["realisations/valid"][:]
        offset = f["realisations/asperity_offset"][:]
        k = f["asperities/stiffness_n_per_m"][:]
        names = [text(p) for p in f["draws/parameter"][:]]
        snr = f["draws/values"][:, names.index("noise.snr_db")] if "noise.snr_db" in names else np.full(len(ids), np.nan)
    return {int(r): (k[offset[j]:offset[j + 1]], snr[j]) for j, r in enumerate(ids) if valid[j]}


def sd_log(k):
    return float(np.std(np.log(k), ddof=1)) if len(k) >= 2 else 0.0


def worst_line_se(k, se):
    """The largest ln k error among the lines apart from every other by more than it
    (stengmc's worst_line_se, inverse/calibration_maps.hpp)."""
    worst = 0.0
    for i in range(len(k)):
        others = np.delete(np.asarray(k, float), i)
        if not np.any(np.abs(np.log(k[i] / others)) <= se[i]):
            worst = max(worst, float(se[i]))
    return worst


def bank_scores(path):
    """Per bank record: the calibrated P(n) as invert computes it (raw posterior through its
    fit class's confusion), and the true count: for the smoothed conformal sets."""
    with h5py.File(path, "r") as f:
        confusions = [f["maps/fits/confusion"][:], f["maps/misfits/confusion"][:]]
        boundary = float(f["maps"].attrs["misfit_ratio"])
        line_se_bound = float(f["maps"].attrs["line_se_bound"])
        line_se = f["records/log_stiffness_se"][:]
        line_k = f["records/stiffness"][:]
        line_off = f["records/estimate_offset"][:]
        noise = f["records/noise_sigma"][:]
        residual = f["records/residual_sigma"][:]
        cmin = int(f["maps"].attrs["count_min"])
        valid = f["records/valid"][:]
        true_n = f["records/true_count"][:]
        orders = f["records/orders"][:]
        evidence = f["records/log_evidence"][:]
        off = f["records/order_offset"][:]
    out = []
    for j in range(len(valid)):
        if not valid[j]:
            continue
        misfit = residual[j] / noise[j] if noise[j] > 0 else 1.0
        worst = worst_line_se(line_k[line_off[j]:line_off[j + 1]], line_se[line_off[j]:line_off[j + 1]])
        conf = confusions[1 if misfit > boundary or worst > line_se_bound else 0]
        o = orders[off[j]:off[j + 1]].astype(int)
        e = evidence[off[j]:off[j + 1]]
        raw = np.exp(e - e.max())
        raw /= raw.sum()
        p = np.zeros(conf.shape[0])
        for m, pm in zip(o, raw):
            if cmin <= m < cmin + conf.shape[0]:
                p += pm * conf[m - cmin]
        out.append((p, int(true_n[j]) - cmin))
    return out, cmin


def smoothed_set_covers(p_record, n_true_index, calibration_scores):
    """Smoothed conformal prediction set {n: p-value(n) > 0.1} with score 1 - P(n)."""
    s_true = 1.0 - p_record[n_true_index]
    s = np.asarray(calibration_scores)
    greater = np.sum(s > s_true)
    ties = np.sum(s == s_true)
    p_value = (greater + RNG.uniform() * (ties + 1)) / (len(s) + 1)
    return p_value > 0.1


def main(argv):
    if len(argv) < 3 or len(argv) % 3:
        sys.exit(__doc__)
    rows = []
    smoothed = []
    for validation, inverted, bank in zip(argv[0::3], argv[1::3], argv[2::3]):
        family = re.sub(r"\.h5$", "", validation.rsplit("/", 1)[-1])
        truths = truth(validation)
        scores, cmin = bank_scores(bank)
        calibration_scores = [1.0 - p[i] for p, i in scores]
        with h5py.File(inverted, "r") as f:
            names = [text(n) for n in f["inverse/records/name"][:]]
            est = f["inverse/count/estimate"][:]
            low = f["inverse/count/interval_low"][:]
            high = f["inverse/count/interval_high"][:]
            naive = f["inverse/count/naive_fft"][:]
            prob = f["inverse/count/probability"][:]
            med = f["inverse/stiffness/median"][:]
            med_lo, med_hi = f["inverse/stiffness/median_low"][:], f["inverse/stiffness/median_high"][:]
            sd = f["inverse/stiffness/sd_log"][:]
            sd_lo, sd_hi = f["inverse/stiffness/sd_log_low"][:], f["inverse/stiffness/sd_log_high"][:]
            line_record = f["inverse/lines/record"][:]
            line_k = f["inverse/lines/stiffness_n_per_m"][:]
            line_lo, line_hi = f["inverse/lines/stiffness_low"][:], f["inverse/lines/stiffness_high"][:]
            warned = [bool(text(w).strip()) for w in f["inverse/records/warnings"][:]]
            vb = float(re.search(r"belt_velocity_m_per_s = ([0-9.eE+-]+)", text(f.attrs["input_text"])).group(1))
        for j, name in enumerate(names):
            r = int(name.rsplit("realisation_", 1)[1])
            if r not in truths:
                continue
            k, snr = truths[r]
            n = len(k)
            m_true, s_true = (float(np.median(k)), sd_log(k)) if n else (float("nan"), float("nan"))
            lines = line_record == j
            line_cover = []
            if est[j] == n and n > 0:  # pair the identified lines with the truth in order of k
                order = np.argsort(line_k[lines])
                lo_sorted, hi_sorted = line_lo[lines][order], line_hi[lines][order]
                line_cover = [bool(a <= kt <= b) for a, kt, b in zip(lo_sorted, np.sort(k), hi_sorted)]
            rows.append(dict(family=family, vb=vb, n=n, warned=warned[j], line_cover=line_cover, snr=snr, est=int(est[j]), low=int(low[j]), high=int(high[j]), naive=naive[j],
                             med_ok=n > 0 and est[j] > 0,
                             med_err=abs(med[j] / m_true - 1.0) if n else float("nan"), med_cover=med_lo[j] <= m_true <= med_hi[j],
                             sd_ok=n >= 2 and est[j] >= 2, sd_err=sd[j] - s_true, sd_cover=sd_lo[j] <= s_true <= sd_hi[j]))
            smoothed.append(smoothed_set_covers(prob[j], n - cmin, calibration_scores))

    def share(values):
        return f"{np.mean(values):.3f}" if len(values) else "–"

    def line(label, keep):
        sel = [r for r in rows if keep(r)]
        if not sel:
            return
        e = np.array([r["est"] - r["n"] for r in sel])
        cover = np.mean([r["low"] <= r["n"] <= r["high"] for r in sel])
        ne = np.array([r["naive"] - r["n"] for r in sel])
        medsel = [r for r in sel if r["med_ok"]]
        med_err = f"{np.median([r['med_err'] for r in medsel]):.2e}" if medsel else "–"
        sdsel = [r for r in sel if r["sd_ok"]]
        sd_rmse = f"{np.sqrt(np.mean([r['sd_err'] ** 2 for r in sdsel])):.4f}" if sdsel else "–"
        lines = [c for r in sel for c in r["line_cover"]]
        wrong = [r["warned"] for r in sel if r["est"] != r["n"]]
        right = [r["warned"] for r in sel if r["est"] == r["n"]]
        print(f"| {label} | {len(sel)} | {np.sqrt(np.mean(e ** 2)):.3f} | {100 * np.mean(e == 0):.1f} % | {cover:.3f} | "
              f"{med_err} | {share([r['med_cover'] for r in medsel])} | "
              f"{sd_rmse} | {share([r['sd_cover'] for r in sdsel])} | {share(lines)} | {share(wrong)} | {share(right)} | "
              f"{np.sqrt(np.mean(ne ** 2)):.2f} | {100 * np.mean(ne == 0):.1f} % |")

    header = ("| {} | signals | n RMSE | exact | 90 % interval of n covers | median k: median abs. rel. error | "
              "its 90 % interval covers | sd(ln k) RMSE | its 90 % interval covers | each line's 90 % k interval covers | "
              "warned: wrong counts | warned: right counts | naive FFT count: n RMSE | naive exact |")
    rule = "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    print(header.format("family"))
    print(rule)
    line("every record", lambda r: True)
    for family in dict.fromkeys(r["family"] for r in rows):
        line(family, lambda r, family=family: r["family"] == family)
    print()
    print(header.format("bin"))
    print(rule)
    for vb in sorted({r["vb"] for r in rows}, reverse=True):
        line(f"v_b = {vb:g} m/s", lambda r, vb=vb: r["vb"] == vb)
    line("n = 0", lambda r: r["n"] == 0)
    for lo, hi in ((1, 4), (5, 8), (9, 12), (13, 16)):
        line(f"n {lo}-{hi}", lambda r, lo=lo, hi=hi: lo <= r["n"] <= hi)
    line("SNR 20-30 dB", lambda r: r["snr"] < 30)
    line("SNR 30-40 dB", lambda r: r["snr"] >= 30)
    print()
    print(f"A randomised (smoothed) conformal 90 % set for n would cover {np.mean(smoothed):.3f} of these signals "
          f"({len(smoothed)}), by construction ~0.90, at the price of an empty set for some signals.")


if __name__ == "__main__":
    main(sys.argv[1:])
