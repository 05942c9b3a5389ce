#!/usr/bin/env python3
"""Figures of `stengmc run` ensemble output files (file_type "stengmc-ensemble"), beside each file
(PNG, or --figure-format pdf|svg; --dpi).

    plot_ensemble.py ENSEMBLE.h5 [ENSEMBLE2.h5 ...]

<stem>.png, for every ensemble file: the distributions over the valid realisations of
  V_rms and of the final charge (histograms, or one strip per grid point in a sweep)
  with the mean and its 95 % CI from /summary; the per-realisation FFT (and ESPRIT,
  when non-zero) identifiability ratios as counts; the first stored voltage trace.
<stem>_sweep.png, for a sweep (more than one grid point): against the first count
  parameter of the sweep (or else its first axis), one line per value of the other axes:
  the pooled identifiability ratio with its 95 % CI band and the mean per-realisation
  ratio as markers; the mean V_rms and the mean final charge with their 95 % CI bands.

Invalid realisations are kept out of every statistic (as in the file's /summary); their
count and reasons go in the title. A grid point with no valid realisation is left out of
the lines; an interval the file marks as not trustworthy (<name>_known = 0) is drawn dotted.

Reads only the layout of src/io/ensemble_file.hpp; run with Debian's python3
(python3-h5py, python3-matplotlib). plot_run.py hands ensemble files to plot_ensemble().
"""
import argparse
import math
import os
import re
import textwrap

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from figure_style import log_axis, unit as fixed_unit  # noqa: E402
from stengmc_h5 import add_output_options, array, attribute, figure_path, save_figures, use_output_options  # noqa: E402
from stengmc_h5 import open_checked as open_stengmc_file  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator  # noqa: E402

FILE_TYPE = "stengmc-ensemble"
US = fixed_unit("s")[0]  # s -> µs

# Units of sweep parameters, from the suffix of their study-file key (README: keys say
# their unit); a key without one is dimensionless or in the unit its section documents.
PARAMETER_UNITS = [("_m_per_s", "m/s"), ("_n_per_m", "N/m"), ("_c_per_m2", "C/m²"), ("_m2", "m²"), ("_hz", "Hz"),
                   ("_kg", "kg"), ("_db", "dB"), ("_m", "m"), ("_n", "N"), ("_s", "s"), ("_v", "V"), ("count", "1")]




def text(values):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]






def short(parameter):
    """surface.stiffness.sigma_log -> sigma_log."""
    return parameter.rsplit(".", 1)[-1]


def parameter_label(parameter):
    name = short(parameter)
    for suffix, unit in PARAMETER_UNITS:
        if name.endswith(suffix):
            return f"{name} [{unit}]"
    return name


def parameter_value(parameter, value):
    """belt_velocity_m_per_s, 10 -> "belt_velocity = 10 m/s": the unit after the number."""
    name = short(parameter)
    for suffix, unit_text in PARAMETER_UNITS:
        if name.endswith(suffix) and suffix != "count":
            return f"{name[: -len(suffix)]} = {value:g} {unit_text}"
    return f"{name} = {value:g}"


def si_scale(values, si_unit):
    """(factor, label) of the quantity's unit: fixed per quantity across all stengmc figures
    (figure_style.UNITS: V in mV, Q in fC), so an ensemble figure reads as a run figure."""
    return fixed_unit(si_unit)


def fmt(value):
    return f"{value:.3g}" if np.isfinite(value) else "–"


class Ensemble:
    """Everything the panels share, read once; per-grid-point arrays have length G."""

    def __init__(self, f, path):
        self.f = f
        self.path = path
        self.input_file = attribute(f, "input_file") or path
        self.title = attribute(f, "title")
        self.point = array(f, "realisations/grid_point").astype(int)
        self.ids = array(f, "realisations/realisation").astype(int)
        n = self.point.size
        valid = array(f, "realisations/valid")
        self.valid = valid.astype(bool) if valid.size == n else np.ones(n, bool)
        self.failure = text(array(f, "realisations/failure"))
        self.parameters = text(array(f, "grid/parameter"))
        values = array(f, "grid/values")
        self.grid = values.reshape(values.shape[0], -1) if values.size else np.empty((0, 0))
        self.G = int(f.attrs.get("grid_points", 0)) or max(self.grid.shape[0], int(self.point.max(initial=-1)) + 1, 1)
        if self.grid.shape[0] != self.G or self.grid.shape[1] != len(self.parameters):
            self.parameters, self.grid = [], np.empty((0, 0))
        self.run = int(f.attrs.get("realisations_run", n))
        self.valid_count = int(f.attrs.get("valid_realisations", np.count_nonzero(self.valid)))
        self.recomputed_note = ""

    def scalar(self, name):
        """Per-realisation values of a scalar (NaN-filled when the file lacks it)."""
        values = array(self.f, f"realisations/{name}").astype(float)
        return values if values.size == self.point.size else np.full(self.point.size, np.nan)

    def interval(self, group, name):
        """(estimate, low, high, known) over the grid points; all NaN where the file has no
        value or the grid point no valid realisation. known False: low/high are the file's
        stand-ins, not a trustworthy interval (too few realisations; ensemble_statistics.hpp)."""
        def get(suffix):
            # A product grid's statistics have one axis per swept parameter, the first
            # slowest: flattened they are in grid-point order again.
            values = array(self.f, f"{group}/{name}{suffix}").astype(float).ravel()
            return values if values.size == self.G else np.full(self.G, np.nan)

        counts = self.valid_per_point()
        if f"{group}/{name}" not in self.f:
            return self.recomputed(group, name)
        estimate, low, high = (np.where(counts > 0, get(s), np.nan) for s in ("", "_low", "_high"))
        known = get("_known")
        known = np.where(np.isfinite(known), known, 1).astype(bool) & (counts > 0)
        return estimate, low, high, known

    def recomputed(self, group, name):
        """A file without /summary (older or hand-made): the estimate from /realisations,
        no interval (low/high NaN)."""
        estimate = np.full(self.G, np.nan)
        pooled = {"fft_ratio": "fft_identifiable", "hr_ratio": "hr_identifiable"}
        for g in range(self.G):
            mine = self.valid & (self.point == g)
            if not np.any(mine):
                continue
            if group == "summary/pooled" and name in pooled:
                sliding = np.nansum(self.scalar("n_sliding")[mine])
                identified = np.nansum(self.scalar(pooled[name])[mine])
                estimate[g] = identified / sliding if sliding > 0 else np.nan
            elif group.startswith("summary/") and name in ("mean", "median"):
                values = self.scalar(group.split("/", 1)[1])[mine]
                if np.any(np.isfinite(values)):
                    estimate[g] = np.nanmean(values) if name == "mean" else np.nanmedian(values)
        if np.any(np.isfinite(estimate)):
            self.recomputed_note = "no /summary in the file: estimates recomputed from /realisations, without CI"
        nothing = np.full(self.G, np.nan)
        return estimate, nothing, nothing.copy(), np.zeros(self.G, bool)

    def summary(self, scalar, statistic="mean"):
        return self.interval(f"summary/{scalar}", statistic)

    def pooled(self, name):
        return self.interval("summary/pooled", name)

    def valid_per_point(self):
        return np.array([np.count_nonzero(self.valid & (self.point == g)) for g in range(self.G)])

    def point_label(self, g, separator=", "):
        if not self.parameters:
            return f"grid point {g}"
        return separator.join(f"{short(p)} = {v:g}" for p, v in zip(self.parameters, self.grid[g]))

    def has_spectra(self):
        """False for a study without [spectrum]: no lines were looked for."""
        sliding = self.scalar("n_sliding")
        return sliding is not None and bool(np.any(np.asarray(sliding) > 0))

    def has_esprit(self):
        hr = self.scalar("hr_ratio")[self.valid]
        pooled = self.pooled("hr_ratio")[0]
        return bool(np.any(np.nan_to_num(hr) != 0) or np.any(np.nan_to_num(pooled) != 0))

    def invalid_note(self):
        """"41 invalid (x reached l: 41)", or "" when every realisation is valid."""
        invalid = np.flatnonzero(~self.valid)
        count = max(self.run - self.valid_count, invalid.size)
        if count == 0:
            return ""
        reasons = {}
        for i in invalid:
            why = self.failure[i] if i < len(self.failure) else ""
            why = re.sub(r"\s*\(.*", "", why).strip() or "no reason recorded"
            reasons[why] = reasons.get(why, 0) + 1
        listed = "; ".join(f"{why}: {k}" for why, k in sorted(reasons.items(), key=lambda item: -item[1]))
        return f"{count} INVALID, kept out of the statistics" + (f" ({listed})" if listed else "")

    def traces(self):
        """[(grid point, realisation id, group)] of the stored traces, in file order."""
        found = []
        if "traces" not in self.f:
            return found

        def visit(name, node):
            if isinstance(node, h5py.Group) and "time" in node and "voltage" in node:
                g = re.search(r"point_(\d+)", name)
                r = re.search(r"realisation_(\d+)", name)
                found.append((int(g.group(1)) if g else 0, int(r.group(1)) if r else 0, node))

        self.f["traces"].visititems(visit)
        return sorted(found, key=lambda item: (item[0], item[1]))

    def suptitle(self, what):
        lines = [f"stengmc ensemble{what}: {self.input_file}",
                 f"{self.run} realisations" + (f" over {self.G} grid points" if self.G > 1 else "")
                 + f", {self.valid_count} valid"]
        note = self.invalid_note()
        if note:
            lines[-1] += f"  [{note}]"
        if self.recomputed_note:
            lines.append(f"[{self.recomputed_note}]")
        if self.title:
            lines.append(self.title)
        return "\n".join(w for line in lines for w in textwrap.wrap(line, 130))


def wants_log(values):
    values = np.asarray(values, float)
    values = values[np.isfinite(values)]
    return values.size > 1 and np.all(values > 0) and values.max() > 10 * values.min()


UNTRUSTED = "interval not trustworthy (too few valid realisations): dotted"


# ---------------------------------------------------------------- <stem>.png


def histogram_with_mean(ax, e, scalar, unit, what, color):
    """Single ensemble: histogram of the valid values, the mean and its CI from /summary."""
    values = e.scalar(scalar)[e.valid]
    values = values[np.isfinite(values)]
    mean, low, high, known = (a[0] for a in e.summary(scalar))
    factor, label = si_scale(np.concatenate([values, [mean]]), unit)
    ax.set_xlabel(f"{what} [{label}]")
    if not values.size:
        ax.text(0.5, 0.5, "no valid realisation", ha="center", va="center", transform=ax.transAxes)
        ax.set_title(f"{what}: nothing to show", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        return
    bins = int(np.clip(2 * np.sqrt(values.size), 6, 40))
    span = np.ptp(values)
    if span > 0:
        edges = np.linspace(values.min() - 0.02 * span, values.max() + 0.02 * span, bins + 1) * factor
    else:  # every realisation gave the same value
        edges = values[0] * factor * np.array([0.99, 1.01]) if values[0] else np.array([-0.5, 0.5])
    ax.hist(values * factor, bins=edges, color=color, alpha=0.55, edgecolor="white",
            label=f"{values.size} valid realisations")
    if np.isfinite(mean):
        if known:
            ax.axvspan(low * factor, high * factor, color="k", alpha=0.15,
                       label=f"95 % CI of the mean [{fmt(low * factor)}, {fmt(high * factor)}]")
        elif high > low:
            ax.axvspan(low * factor, high * factor, facecolor="none", edgecolor="k", hatch="...", lw=0.5,
                       label=f"CI stand-in [{fmt(low * factor)}, {fmt(high * factor)}], not trustworthy")
        ax.axvline(mean * factor, color="k", lw=1.3, label=f"mean {fmt(mean * factor)} {label}")
    median = e.summary(scalar, "median")[0][0]
    if np.isfinite(median):
        ax.axvline(median * factor, color="k", lw=0.9, ls=":", label=f"median {fmt(median * factor)} {label}")
    ax.set_ylabel("realisations")
    ax.yaxis.get_major_locator().set_params(integer=True)
    ax.set_title(f"{what} over the valid realisations", fontsize=9)
    ax.legend(fontsize=7, loc="best")


def mark_empty_points(ax, e):
    """Grid points without a valid realisation: say so where their data would be."""
    for g in np.flatnonzero(e.valid_per_point() == 0):
        ax.text(g, 0.5, "no valid\nrealisation", transform=ax.get_xaxis_transform(), ha="center", va="center",
                fontsize=7, color="C3", rotation=90)


def strips_with_mean(ax, e, scalar, unit, what, color):
    """Sweep: one strip of valid values per grid point, the mean and its CI as an error bar."""
    values = e.scalar(scalar)
    mean, low, high, known = e.summary(scalar)
    factor, label = si_scale(np.concatenate([values[e.valid], mean]), unit)
    rng = np.random.default_rng(0)  # jitter only; fixed so figures do not change between runs
    for g in range(e.G):
        mine = values[e.valid & (e.point == g)]
        mine = mine[np.isfinite(mine)]
        ax.plot(g + rng.uniform(-0.18, 0.18, mine.size), mine * factor, ".", color=color, ms=3.5, alpha=0.5,
                label="valid realisations" if g == 0 else None)
    err = np.vstack([mean - low, high - mean]) * factor
    err = np.where(np.isfinite(err), np.maximum(err, 0), 0)
    has_interval = np.isfinite(low) & np.isfinite(high)
    for trusted, style, name in ((True, "-", "mean, 95 % CI"), (False, ":", "mean, CI not trustworthy")):
        pick = np.isfinite(mean) & (known == trusted) & has_interval
        if not np.any(pick):
            continue
        bars = ax.errorbar(np.flatnonzero(pick), mean[pick] * factor, yerr=err[:, pick], fmt="_", ms=14, mew=1.8,
                           color="k", ecolor="k", elinewidth=1.2, capsize=3, label=name, zorder=3)
        bars[2][0].set_linestyle(style)
    bare = np.isfinite(mean) & ~has_interval
    if np.any(bare):
        ax.plot(np.flatnonzero(bare), mean[bare] * factor, "_", ms=14, mew=1.8, color="k", label="mean (no CI in the file)",
                zorder=3)
    mark_empty_points(ax, e)
    if wants_log(values[e.valid]):
        log_axis(ax)
    grid_axis(ax, e)
    ax.set_ylabel(f"{what} [{label}]")
    ax.set_title(f"{what} over the valid realisations, by grid point", fontsize=9)
    ax.legend(fontsize=7, loc="best")


def grid_axis(ax, e):
    """Grid points along x, labelled with their parameter values (one line per axis)."""
    ax.set_xlim(-0.6, e.G - 0.4)
    step = max(1, math.ceil(e.G / 24))
    ticks = list(range(0, e.G, step))
    ax.set_xticks(ticks)
    if e.parameters:
        ax.set_xticklabels(["\n".join(f"{v:g}" for v in e.grid[g]) for g in ticks], fontsize=7)
        ax.set_xlabel("grid point: " + " / ".join(short(p) for p in e.parameters), fontsize=8)
    else:
        ax.set_xlabel("grid point")


def ratio_counts(ax, e):
    """How many valid realisations reached each identifiable fraction (FFT, and ESPRIT)."""
    methods = [("fft_ratio", "FFT", "C0")] + ([("hr_ratio", "ESPRIT", "C3")] if e.has_esprit() else [])
    if not e.has_spectra():
        ax.text(0.5, 0.5, "the study has no [spectrum]:\nno lines were looked for", ha="center", va="center",
                transform=ax.transAxes)
        ax.set_title("identifiability ratio: not computed", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        return
    if not np.any(e.valid):
        ax.text(0.5, 0.5, "no valid realisation", ha="center", va="center", transform=ax.transAxes)
        ax.set_title("identifiability ratio: nothing to show", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        return
    if e.G == 1:
        ratio_bars(ax, e, methods)
    else:
        ratio_bubbles(ax, e, methods)


def ratio_bars(ax, e, methods):
    """Single ensemble: realisations per ratio reached, on the 0..1 axis, with the pooled ratio."""
    reached = np.concatenate([e.scalar(s)[e.valid] for s, _, _ in methods])
    levels = np.unique(np.round(reached[np.isfinite(reached)], 6))
    n_sliding = e.scalar("n_sliding")[e.valid]
    n = n_sliding[0] if n_sliding.size and np.ptp(n_sliding) == 0 else 0
    if 0 < n <= 16 and n == round(n):  # the same n sliding in each: every k/n is possible
        levels = np.union1d(levels, np.round(np.arange(int(n) + 1) / n, 6))
    gap = np.min(np.diff(levels)) if levels.size > 1 else 0.25
    width = min(0.8 * gap, 0.08) / len(methods)
    title = []
    for j, (scalar, name, color) in enumerate(methods):
        values = np.round(e.scalar(scalar)[e.valid], 6)
        counts = [np.count_nonzero(values == level) for level in levels]
        ax.bar(levels + (j - (len(methods) - 1) / 2) * width, counts, width, color=color, alpha=0.75,
               label=f"{name}: realisations")
        pooled, low, high, known = (a[0] for a in e.pooled(scalar))
        if np.isfinite(pooled):
            ax.axvline(pooled, color=color, lw=1.3, ls="--")
            if high > low:
                ax.axvspan(low, high, color=color, alpha=0.12 if known else 0.0, hatch=None if known else "...",
                           lw=0, zorder=0)
            interval = f" [{fmt(low)}, {fmt(high)}]" if np.isfinite(low) and np.isfinite(high) else ""
            title.append(f"{name} pooled {fmt(pooled)}{interval}" + (" (CI not trustworthy)" if interval and not known else ""))
    if title:
        ax.plot([], [], "k--", lw=1.3, label="pooled ratio (Σ identifiable / Σ sliding), 95 % CI shaded")
    reach = width * len(methods) / 2 + 0.02
    ax.set_xlim(min(-0.03, levels.min() - reach), max(1.03, levels.max() + reach))
    if levels.size <= 17:
        ax.set_xticks(levels)
        ax.set_xticklabels([f"{level:.3g}" for level in levels], fontsize=8 if levels.size <= 9 else 6)
    ax.set_xlabel("identifiable / sliding asperities in a realisation [1]")
    ax.set_ylabel("realisations")
    ax.yaxis.get_major_locator().set_params(integer=True)
    sliding = ""
    if n_sliding.size:
        sliding = (f"{fmt(n_sliding[0])} sliding in each realisation" if np.ptp(n_sliding) == 0
                   else f"{fmt(np.min(n_sliding))}–{fmt(np.max(n_sliding))} sliding per realisation")
    ax.set_title("identifiability ratio per realisation\n" + "; ".join([", ".join(title)] * bool(title)
                                                                     + [sliding] * bool(sliding)), fontsize=9)
    ax.legend(fontsize=7, loc="upper left")


def ratio_bubbles(ax, e, methods):
    """Sweep: per grid point, a disc per ratio reached, area proportional to its count."""
    offset = 0.0 if len(methods) == 1 else 0.17
    biggest = max(1, max(np.count_nonzero(e.valid & (e.point == g)) for g in range(e.G)))
    for j, (scalar, name, color) in enumerate(methods):
        values = np.round(e.scalar(scalar), 6)
        shift = (j - (len(methods) - 1) / 2) * 2 * offset
        for g in range(e.G):
            mine = values[e.valid & (e.point == g)]
            levels, counts = np.unique(mine[np.isfinite(mine)], return_counts=True)
            ax.scatter(np.full(levels.size, g + shift), levels, s=8 + 220 * counts / biggest, color=color, alpha=0.5,
                       edgecolor="k", linewidth=0.3)
        pooled = e.pooled(scalar)[0]
        has = np.isfinite(pooled)
        ax.plot(np.flatnonzero(has) + shift, pooled[has], "_", color="k", ms=12, mew=1.8)
        ax.scatter([], [], s=60, color=color, alpha=0.5, edgecolor="k", linewidth=0.3, label=f"{name}: realisations")
    ax.plot([], [], "_", color="k", ms=12, mew=1.8, label="pooled ratio")
    mark_empty_points(ax, e)
    ax.set_ylim(-0.05, 1.08)
    grid_axis(ax, e)
    ax.set_ylabel("identifiable / sliding asperities [1]")
    ax.set_title(f"identifiability ratio per realisation (disc area ∝ count, largest = {biggest})", fontsize=9)
    ax.legend(fontsize=7, loc="best")


def trace_panel(ax, e):
    traces = e.traces()
    if not traces:
        ax.text(0.5, 0.5, "no traces in the file\n(study: [ensemble] trace_realisations)", ha="center", va="center",
                transform=ax.transAxes)
        ax.set_title("voltage trace: none stored", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        return
    # The first stored trace; in a sweep also the first of the last grid point that has one.
    chosen = [traces[0]]
    if e.G > 1 and traces[-1][0] != traces[0][0]:
        last = traces[-1][0]
        chosen.append(next(t for t in traces if t[0] == last))
    voltages = [node["voltage"][()] for _, _, node in chosen]
    factor, label = si_scale(np.concatenate(voltages), "V")
    notes = []
    for j, ((g, r, node), v) in enumerate(zip(chosen, voltages)):
        t = node["time"][()][: v.size] * US
        row = np.flatnonzero((e.point == g) & (e.ids == r))
        valid = bool(e.valid[row[0]]) if row.size else True
        name = f"realisation {r}" + (f" ({e.point_label(g)})" if e.G > 1 else "")
        if not valid:
            why = e.failure[row[0]] if row[0] < len(e.failure) else ""
            notes.append(f"{name}: {why or 'invalid'}")
            name += " — INVALID, cut at the failure"
        ax.plot(t, v * factor, lw=0.7, color=f"C{j}" if len(chosen) > 1 else "k", alpha=0.9 if j == 0 else 0.75,
                label=name)
    ax.set_xlabel("t [µs]")
    ax.set_ylabel(f"V (clean) [{label}]")
    title = ("first stored voltage trace" if len(chosen) == 1 else "voltage traces: first stored, first of the last point") \
        + f" ({len(traces)} stored)"
    if notes:
        title += "\n" + "\n".join(textwrap.wrap("; ".join(notes), 80))
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="best")


def overview_figure(e):
    size = (13, 8.6) if e.G == 1 else (min(30, max(13, 0.75 * e.G + 5)), 9.2)
    fig, axes = plt.subplots(2, 2, figsize=size)
    axes = axes.ravel()
    if e.G == 1:
        histogram_with_mean(axes[0], e, "voltage_rms_v", "V", "V_rms", "C0")
        histogram_with_mean(axes[1], e, "final_charge_c", "C", "final charge Q", "C2")
    else:
        strips_with_mean(axes[0], e, "voltage_rms_v", "V", "V_rms", "C0")
        strips_with_mean(axes[1], e, "final_charge_c", "C", "final charge Q", "C2")
    ratio_counts(axes[2], e)
    trace_panel(axes[3], e)
    for letter, ax in zip("abcd", axes):
        ax.set_title(f"({letter}) " + ax.get_title(), fontsize=9)
    fig.suptitle(e.suptitle(""), fontsize=10)
    fig.tight_layout()
    return fig


# ---------------------------------------------------------------- <stem>_sweep.png


def x_axis(e):
    """Index of the sweep axis to plot against: the first count, else the first."""
    for i, p in enumerate(e.parameters):
        if short(p).endswith("count"):
            return i
    return 0


def powers_of_two(values):
    v = np.unique(values)
    return v.size >= 2 and np.all(v > 0) and np.allclose(np.log2(v), np.round(np.log2(v)))


def lines(e, axis):
    """[(label, grid points sorted by x)]: one line per value of the other axes."""
    others = [i for i in range(len(e.parameters)) if i != axis]
    groups = {}
    for g in range(e.G):
        groups.setdefault(tuple(e.grid[g, i] for i in others), []).append(g)
    result = []
    for key, points in groups.items():
        label = ", ".join(parameter_value(e.parameters[i], v) for i, v in zip(others, key))
        result.append((label, sorted(points, key=lambda g: e.grid[g, axis])))
    return result


def band(ax, x, estimate, low, high, known, color, ls="-", marker=None, hatch=None):
    """A line with its CI band, segment by segment: filled (or `hatch`ed) between two points
    whose intervals are trustworthy, dotted-hatched where either is not; an error bar for a
    point with no neighbour. NaN (no valid realisation) breaks the line."""
    ax.plot(x, estimate, ls=ls, color=color, lw=1.5, marker=marker, ms=4)
    ok = np.isfinite(low) & np.isfinite(high)
    for i in range(len(x) - 1):
        if not (ok[i] and ok[i + 1]):
            continue
        segment = slice(i, i + 2)
        if known[i] and known[i + 1]:
            if hatch:
                ax.fill_between(x[segment], low[segment], high[segment], facecolor="none", edgecolor=color,
                                hatch=hatch, lw=0, alpha=0.6)
            else:
                ax.fill_between(x[segment], low[segment], high[segment], color=color, alpha=0.2, lw=0)
        else:
            ax.fill_between(x[segment], low[segment], high[segment], facecolor="none", edgecolor=color, hatch="...",
                            lw=0, alpha=0.5)
    for i in range(len(x)):
        alone = ok[i] and not (i > 0 and ok[i - 1]) and not (i + 1 < len(x) and ok[i + 1])
        if alone:
            bars = ax.errorbar([x[i]], [estimate[i]], yerr=[[max(estimate[i] - low[i], 0)], [max(high[i] - estimate[i], 0)]],
                               fmt="none", ecolor=color, capsize=3, elinewidth=1)
            bars[2][0].set_linestyle("-" if known[i] else ":")


def identifiability_legend(ax, e, groups, colors, esprit, untrusted, counts):
    """Axis labels, limits and the two legends of the identifiability panel."""
    ax.set_ylim(-0.03, 1.05)
    ax.set_ylabel("identifiable / sliding asperities [1]")
    ax.set_title("identifiability" + (" (FFT and ESPRIT)" if esprit else " (FFT lines)"), fontsize=9)
    style = [(Patch(color="k", alpha=0.2, lw=0), Line2D([], [], color="k", lw=1.5)),
             Line2D([], [], marker="o", ls="none", mfc="none", mec="k", label="FFT mean per-realisation ratio")]
    if esprit:
        style += [(Patch(facecolor="none", edgecolor="k", hatch="////", lw=0, alpha=0.6),
                   Line2D([], [], color="k", lw=1.5, ls="--")),
                  Line2D([], [], marker="s", ls="none", mfc="none", mec="k", label="ESPRIT mean per-realisation ratio")]
    if untrusted:
        style.append(Patch(facecolor="none", edgecolor="k", hatch="...", label="CI not trustworthy (few realisations)"))
    if np.any(counts == 0):
        style.append(Line2D([], [], marker="x", ls="none", color="k", mew=2, label="no valid realisation"))
    names = ["FFT pooled ratio, 95 % CI band", "FFT mean per-realisation ratio"]
    if esprit:
        names += ["ESPRIT pooled ratio, 95 % CI hatched", "ESPRIT mean per-realisation ratio"]
    names += [h.get_label() for h in style[len(names):]]
    legend = ax.legend(style, names, fontsize=7, loc="lower left")
    if len(groups) > 1:
        ax.add_artist(legend)
        ax.legend(handles=[Line2D([], [], color=c, lw=3, label=label) for c, (label, _) in zip(colors, groups)],
                  fontsize=7, loc="upper right")


def sweep_figure(e):
    axis = x_axis(e)
    x_name = e.parameters[axis]
    groups = lines(e, axis)
    esprit = e.has_esprit()
    counts = e.valid_per_point()
    values = e.grid[:, axis]
    log2 = powers_of_two(values)
    spectra = e.has_spectra()
    fig, axes = plt.subplots(1, 3 if spectra else 2, figsize=(17, 5.6) if spectra else (12, 5.6))
    # Without [spectrum] there is nothing to identify: only V_rms and Q.
    id_ax, q_axes = (axes[0], axes[1:]) if spectra else (None, axes)
    colors = [f"C{j % 10}" for j in range(len(groups))]
    quantities = [("voltage_rms_v", "V", "mean V_rms"), ("final_charge_c", "C", "mean final charge Q")]
    scales = {s: si_scale(np.concatenate(e.summary(s)[:3]), u) for s, u, _ in quantities}
    untrusted = False
    for color, (label, points) in zip(colors, groups):
        x = values[points]
        ax = id_ax
        ratios = [("fft_ratio", "-", "o", None)] + ([("hr_ratio", "--", "s", "////")] if esprit else [])
        for scalar, ls, marker, hatch in ratios if spectra else []:
            pooled, low, high, known = (a[points] for a in e.pooled(scalar))
            band(ax, x, pooled, low, high, known, color, ls=ls, hatch=hatch)
            untrusted |= bool(np.any(np.isfinite(low) & ~known))
            mean = e.summary(scalar)[0][points]
            ax.plot(x, mean, marker, ls="none", mfc="none", mec=color, ms=7, mew=1.2)
        for ax, (scalar, _, _) in zip(q_axes, quantities):
            factor, _ = scales[scalar]
            estimate, low, high, known = (a[points] for a in e.summary(scalar))
            band(ax, x, estimate * factor, low * factor, high * factor, known, color, marker="o")
            untrusted |= bool(np.any(np.isfinite(low) & ~known))
        empty = [g for g in points if counts[g] == 0]
        for ax in axes if empty else []:  # (an empty unclipped line upsets tight_layout)
            ax.plot(values[empty], np.full(len(empty), 0.03), "x", color=color, ms=8, mew=2,
                    transform=ax.get_xaxis_transform(), clip_on=False)
    if spectra:
        identifiability_legend(id_ax, e, groups, colors, esprit, untrusted, counts)
    for ax, (scalar, _, what) in zip(q_axes, quantities):
        _, unit = scales[scalar]
        ax.set_ylabel(f"{what} [{unit}]")
        ax.set_title(f"{what} over the valid realisations, 95 % CI band", fontsize=9)
        if wants_log(e.summary(scalar)[0]):
            log_axis(ax)
        if len(groups) > 1:
            ax.legend(handles=[Line2D([], [], color=c, lw=1.5, marker="o", label=label)
                               for c, (label, _) in zip(colors, groups)], fontsize=7, loc="best")
    ticks = np.unique(values)
    for ax in axes:
        if log2:
            ax.set_xscale("log", base=2)
            ax.set_xlim(ticks[0] / 2 ** 0.3, ticks[-1] * 2 ** 0.3)
        else:
            pad = 0.05 * (ticks[-1] - ticks[0] or 1)
            ax.set_xlim(ticks[0] - pad, ticks[-1] + pad)
        if ticks.size <= 12:
            ax.xaxis.set_major_locator(FixedLocator(ticks))
            ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
            ax.xaxis.set_minor_locator(NullLocator())
        ax.set_xlabel(parameter_label(x_name) + ("  (log₂ scale)" if log2 else ""))
        ax.grid(True, lw=0.3, alpha=0.5)
    notes = []
    empty = np.flatnonzero(counts == 0)
    if empty.size:
        notes.append("× no valid realisation, left out of the lines: " + "; ".join(e.point_label(g) for g in empty))
    if untrusted:
        notes.append("dotted hatching / dotted error bars: the file marks those intervals as not trustworthy "
                     "(too few valid realisations for the bootstrap)")
    if notes:
        fig.text(0.5, 0.005, "\n".join(w for n in notes for w in textwrap.wrap(n, 200)), ha="center", va="bottom",
                 fontsize=8, color="C3")
    for letter, ax in zip("abc", axes):
        ax.set_title(f"({letter}) " + ax.get_title(), fontsize=9)
    fig.suptitle(e.suptitle(" sweep"), fontsize=10)
    fig.tight_layout(rect=(0, 0.025 * (len(notes) + 1) if notes else 0, 1, 1))
    return fig


def figures(path):
    """[(output path, Figure)] of the ensemble file `path`, not yet written: <stem>.png and,
    for a sweep, <stem>_sweep.png; [] when it records no realisation."""
    f = open_stengmc_file(path, FILE_TYPE, "stengmc ensemble output file")
    e = Ensemble(f, path)
    if e.point.size == 0:
        print(f"{path}: no realisations recorded (/realisations is empty or missing); no figure written")
        return []
    stem = os.path.splitext(path)[0]
    found = [(figure_path(stem), overview_figure(e))]
    if e.G > 1:
        if e.parameters:
            found.append((figure_path(stem + "_sweep"), sweep_figure(e)))
        else:
            print(f"{path}: {e.G} grid points but no readable /grid; no sweep figure")
    return found


def plot_ensemble(path):
    """Writes the figures of `path` beside it; returns their names."""
    return save_figures(figures(path))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="HDF5 files written by `stengmc run` for an [ensemble] study")
    add_output_options(parser)
    args = parser.parse_args()
    use_output_options(args)
    for path in args.files:
        plot_ensemble(path)


if __name__ == "__main__":
    main()
