#!/usr/bin/env python3
"""Figures of `stengmc surface` output files (file_type "stengmc-surface"), beside each file
(PNG, or --figure-format pdf|svg; --dpi).

    plot_surface.py SURFACE.h5 [SURFACE2.h5 ...]    one multi-panel figure, <stem>.png

Panels, each drawn only when the file holds its data (a fixed asperity list holds none):
  summit heights against the target law; stiffnesses against theirs (or, when the contact
  sets them, the in-contact stiffnesses); the first realisation's load-separation curve;
  the first realisation's summits on the nominal square; load redistribution against
  contact density over the realisations; a summary of counts and warnings.

Reads only the layout of src/io/surface_file.hpp and src/io/population_file.hpp; run
with Debian's python3 (python3-h5py, python3-matplotlib). plot_run.py hands surface
files to plot_surface().
"""
import argparse
import math
import os
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from stengmc_h5 import add_output_options, array, attribute, figure_path, save_figures, use_output_options  # noqa: E402
from stengmc_h5 import open_checked as open_stengmc_file  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

try:
    import tomllib  # Python >= 3.11: read the nominal area from the recorded input text
except ImportError:  # pragma: no cover
    tomllib = None

FILE_TYPE = "stengmc-surface"
UM = 1e6  # m -> µm
MN = 1e3  # N -> mN








def input_table(f):
    """The recorded surface file (input_text, or surface_text for a study), parsed; {} if unreadable."""
    if tomllib is None:
        return {}
    for name in ("surface_text", "input_text"):
        text = attribute(f, name)
        if not text:
            continue
        try:
            table = tomllib.loads(text)
        except (tomllib.TOMLDecodeError, TypeError):
            continue
        if "nominal_area_m2" in table:
            return table
        if isinstance(table.get("surface"), dict):  # a study with its surface inline
            return table["surface"]
    return {}


def bins_for(values, extra=()):
    """Histogram edges over the sample (and the target's range), sqrt(n) bins within [10, 60]."""
    lo = min([values.min()] + [e.min() for e in extra if e.size])
    hi = max([values.max()] + [e.max() for e in extra if e.size])
    if not hi > lo:
        lo, hi = lo - 0.5 * max(abs(lo), 1e-12) * 1e-3, hi + 0.5 * max(abs(hi), 1e-12) * 1e-3
    count = int(np.clip(np.sqrt(values.size), 10, 60))
    return np.linspace(lo, hi, count + 1)


def ks_distance(sample, grid, pdf):
    """Kolmogorov-Smirnov distance between a sample and the law tabulated as a pdf on a grid
    (the CDF by the trapezoid rule, renormalised: the grid spans the 1e-4..1-1e-4 quantiles)."""
    cdf = np.concatenate([[0.0], np.cumsum(0.5 * (pdf[1:] + pdf[:-1]) * np.diff(grid))])
    if not cdf[-1] > 0:
        return float("nan")
    cdf /= cdf[-1]
    x = np.sort(sample)
    f = np.interp(x, grid, cdf, left=0.0, right=1.0)
    n = x.size
    i = np.arange(1, n + 1)
    return float(max(np.max(i / n - f), np.max(f - (i - 1) / n)))


def draw_law(ax, sample, target, scale, unit, what, contact_sample=None):
    """Histogram of `sample` (SI) against a target law group (pdf on a grid or point
    probabilities), in units of 1/scale of SI (scale = 1e6 for µm)."""
    n = sample.size
    discrete = target is not None and int(target.attrs.get("discrete", 0)) == 1
    x = sample * scale
    if target is not None and discrete:
        values = target["value"][()] * scale
        probability = target["density"][()]
        seen, counts = np.unique(x, return_counts=True)
        frequency = counts / n
        # Bar width from the spacing of the support; a single value (a fixed height) has none.
        support = np.unique(np.concatenate([values, seen]))
        spacing = np.min(np.diff(support)) if support.size > 1 else max(abs(support[0]) * 0.01, 1e-3)
        width = 0.35 * spacing
        if support.size == 1:  # a fixed value: two bars of probability 1 say nothing more
            ax.text(0.5, 0.55, f"every {what[:-1]} at {support[0]:.4g} {unit.strip('()')},\nas the target law (a single value)",
                    transform=ax.transAxes, ha="center", va="center", fontsize=9)
            ax.set_xlim(support[0] - 5 * spacing, support[0] + 5 * spacing)
        ax.bar(seen - width / 2, frequency, width=width, color="C0", alpha=0.7, label=f"sample frequency ({n} {what})")
        ax.bar(values + width / 2, probability, width=width, color="C3", alpha=0.7, label="target probability")
        # Expected frequency at the listed values: deviation in binomial standard deviations.
        observed = np.array([frequency[seen == v].sum() if np.any(seen == v) else 0.0 for v in values])
        sd = np.sqrt(np.maximum(probability * (1 - probability), 1e-300) / n)
        off_list = 1.0 - observed.sum()
        note = f"largest deviation {np.max(np.abs(observed - probability) / sd):.1f} sd"
        if off_list > 1e-12:
            note += f"; {100 * off_list:.2g} % off the list"
        ax.set_ylabel("probability [1]")
        ax.set_ylim(0, 1.3 * max(np.max(frequency, initial=0), np.max(probability, initial=0)))
        return note
    edges = bins_for(x, () if target is None else (target["value"][()] * scale,))
    ax.hist(x, bins=edges, density=True, color="C0", alpha=0.55, label=f"sampled ({n} {what})")
    if contact_sample is not None and contact_sample.size and contact_sample.size < n:
        # Scaled by all summits: the in-contact part of the same density.
        weights = np.full(contact_sample.size, 1.0 / (n * (edges[1] - edges[0])))
        ax.hist(contact_sample * scale, bins=edges, weights=weights, histtype="step", color="C1", lw=1.3,
                label=f"in contact ({100 * contact_sample.size / n:.2g} % of them)")
    note = ""
    if target is not None:
        grid = target["value"][()]
        pdf = target["density"][()]
        ax.plot(grid * scale, pdf / scale, color="C3", lw=1.5, label="target pdf")
        distance = ks_distance(sample, grid, pdf)
        note = f"KS distance {distance:.3g} (5 % critical {1.358 / math.sqrt(n):.2g})"
    ax.set_ylabel(f"probability density [1/{unit}]")
    return note


def panel_heights(ax, f, d):
    target = f["target/heights"] if "target/heights/value" in f else None
    note = draw_law(ax, d["heights"], target, UM, "µm", "summits", d["contact_heights"])
    separation = array(f, "realisations/separation_m")
    if separation.size:
        ax.axvline(np.median(separation) * UM, color="k", ls="--", lw=0.9,
                   label=f"rigid flat d (median of {separation.size})")
    ax.set_xlabel("summit height z [µm]")
    ax.ticklabel_format(axis="x", useOffset=False)
    ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(6))
    ax.set_title("summit heights" + (" vs target law" if target is not None else " (no target law in file)")
                 + (f"\n{note}" if note else ""), fontsize=9)
    ax.legend(fontsize=7)


def panel_stiffness(ax, f, d):
    if d["sampled_stiffness"].size:
        target = f["target/stiffness"] if "target/stiffness/value" in f else None
        note = draw_law(ax, d["sampled_stiffness"], target, 1.0, "(N/m)", "summits", d["contact_stiffness"])
        ax.set_title("sampled stiffnesses" + (" vs target law" if target is not None else " (no target law in file)")
                     + (f"\n{note}" if note else ""), fontsize=9)
        ax.set_ylabel("probability density [m/N]" if target is None or not int(target.attrs.get("discrete", 0))
                      else "probability [1]")
    else:
        k = d["contact_stiffness"]
        edges = bins_for(k)
        ax.hist(k, bins=edges, density=True, color="C1", alpha=0.6, label=f"{k.size} asperities in contact")
        rule = d["table"].get("stiffness", {}).get("rule", "") if isinstance(d["table"].get("stiffness"), dict) else ""
        how = "Mindlin k = 8 G* a" if rule == "mindlin" else "derived from the contact"
        ax.set_title(f"in-contact stiffnesses, {how}\n(no target law: the heights and loads set them)", fontsize=9)
        ax.set_ylabel("probability density [m/N]")
    ax.set_xlabel("shear stiffness k [N/m]")
    ax.legend(fontsize=7)


def panel_load_separation(ax, f, d):
    g = f["load_separation"]
    solved = float(g.attrs.get("solved_separation_m", np.nan))
    nominal = float(g.attrs.get("nominal_load_n", np.nan))
    realisation = int(g.attrs.get("realisation", 0))
    separation = g["separation_m"][()]
    load = g["total_load_n"][()]
    positive = load > 0
    ax.semilogy((separation[positive] - solved) * UM, load[positive], color="k", lw=1.2,
                label="Hertz, independent summits")
    if np.isfinite(nominal) and nominal > 0:
        ax.axhline(nominal, color="C3", lw=0.9, ls="--", label=f"nominal load W = {nominal:g} N")
        ax.plot([0.0], [nominal], "o", color="C3", mfc="none", ms=8, mew=1.5, label="solved separation")
    # With the interaction applied the solve includes the extra displacements, so the
    # independent curve does not pass through (d_solved, W): say so rather than hide it.
    order = np.argsort(separation)
    at_solved = float(np.interp(solved, separation[order], load[order]))
    note = ""
    if np.isfinite(nominal) and nominal > 0 and abs(at_solved / nominal - 1) > 0.01:
        note = f"\ncurve at d_solved: {at_solved:.3g} N = {at_solved / nominal:.2g} W (loads solved with the interaction)"
    ax.set_xlabel(f"separation d − d_solved [µm]  (d_solved = {solved * UM:.4f} µm)")
    ax.set_ylabel("total load [N]")
    ax.set_title(f"load–separation curve of realisation {realisation}{note}", fontsize=9)
    ax.grid(True, which="major", lw=0.3, alpha=0.5)
    ax.legend(fontsize=7, loc="lower left")


def nice_factor(needed):
    """Smallest of 1, 2, 5, 10, 20, 50, ... at least `needed`."""
    if needed <= 1:
        return 1
    decade = 10 ** math.floor(math.log10(needed))
    for m in (1, 2, 5, 10):
        if m * decade >= needed:
            return int(m * decade)
    return int(10 * decade)


def panel_positions(fig, ax, f, d):
    j = d["map_realisation"]
    offset = d["summit_offset"]
    a_offset = d["asperity_offset"]
    lo, hi = int(offset[j]), int(offset[j + 1])
    x = array(f, "summits/x_m")[lo:hi] * UM
    y = array(f, "summits/y_m")[lo:hi] * UM
    contact = np.zeros(hi - lo, bool)
    index = array(f, "asperities/summit_index")
    if index.size and a_offset.size > j + 1:
        mine = index[int(a_offset[j]):int(a_offset[j + 1])].astype(int)
        contact[mine[(mine >= 0) & (mine < contact.size)]] = True
    elif "summits/patch_radius_m" in f:
        contact = array(f, "summits/patch_radius_m")[lo:hi] > 0
    load = array(f, "summits/normal_load_n")[lo:hi] * MN
    radius = array(f, "summits/patch_radius_m")[lo:hi] * UM
    side = d["side_um"] or max(np.max(x, initial=0), np.max(y, initial=0)) or 1.0
    if np.any(~contact):
        ax.plot(x[~contact], y[~contact], ".", color="0.6", ms=2.5, label=f"not in contact ({np.count_nonzero(~contact)})")
    scale_note = ""
    n_contact = int(np.count_nonzero(contact))
    # Equal loads (a discrete height law, a fixed load) need no colour scale.
    equal = n_contact > 0 and np.ptp(load[contact]) <= 1e-9 * np.max(np.abs(load[contact]))
    if n_contact and radius.size and np.any(radius[contact] > 0):
        # Real patches are a few µm on a square of hundreds: enlarge them by a round factor
        # until the median patch spans ~0.6 % of the side, and say so.
        factor = nice_factor(0.006 * side / np.median(radius[contact]))
        circles = [Circle((cx, cy), r * factor) for cx, cy, r in zip(x[contact], y[contact], radius[contact])]
        if equal:
            patches = PatchCollection(circles, facecolor="C2", edgecolor="k", linewidth=0.3)
            ax.add_collection(patches)
            ax.plot([], [], "o", mfc="C2", mec="k", ls="none",
                    label=f"in contact ({n_contact}), N = {load[contact][0]:.3g} mN each")
        else:
            patches = PatchCollection(circles, cmap="viridis", edgecolor="k", linewidth=0.3)
            patches.set_array(load[contact])
            ax.add_collection(patches)
            fig.colorbar(patches, ax=ax, label="normal load N [mN]", fraction=0.046, pad=0.03)
            ax.plot([], [], "o", mfc=plt.get_cmap("viridis")(0.5), mec="k", ls="none", label=f"in contact ({n_contact})")
        scale_note = "patch radii to scale" if factor == 1 else f"patch radii enlarged ×{factor} for visibility"
    elif n_contact:
        if not equal:
            points = ax.scatter(x[contact], y[contact], c=load[contact], cmap="viridis", s=18, edgecolor="k", lw=0.3,
                                label=f"in contact ({n_contact})")
            fig.colorbar(points, ax=ax, label="normal load N [mN]", fraction=0.046, pad=0.03)
        else:
            ax.scatter(x[contact], y[contact], color="C2", s=18, edgecolor="k", lw=0.3,
                       label=f"in contact ({n_contact}), N = {load[contact][0]:.3g} mN each")
        scale_note = "no patch radii (no [materials]): markers only"
    else:
        scale_note = "no summit in contact"
    ax.add_patch(plt.Rectangle((0, 0), side, side, fill=False, lw=0.8, ls=":", color="k"))
    ax.set_xlim(-0.02 * side, 1.02 * side)
    ax.set_ylim(-0.02 * side, 1.02 * side)
    ax.set_aspect("equal")
    ax.set_xlabel("x [µm]")
    ax.set_ylabel("y [µm]")
    realisation = int(d["realisation_ids"][j]) if d["realisation_ids"].size > j else j
    if j > 0:
        scale_note += "; realisations before it drew no summits"
    ax.set_title(f"summits of realisation {realisation} on the nominal area ({hi - lo} summit{'s' * (hi - lo != 1)})"
                 f"\n{scale_note}", fontsize=9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)


def panel_redistribution(ax, f, d):
    density = array(f, "realisations/contact_density") * 100
    moved = array(f, "realisations/load_redistribution") * 100
    threshold = float(f.attrs.get("load_redistribution_threshold", np.nan)) * 100
    above = moved > threshold if np.isfinite(threshold) else np.zeros(moved.size, bool)
    if np.any(~above):
        ax.scatter(density[~above], moved[~above], s=14, color="C0", alpha=0.8,
                   label=f"independent enough ({np.count_nonzero(~above)})")
    if np.any(above):
        ax.scatter(density[above], moved[above], s=14, color="C3", alpha=0.8,
                   label=f"above threshold ({np.count_nonzero(above)})")
    pairs = array(f, "realisations/overlapping_pairs")
    if pairs.size == moved.size and np.any(pairs > 0):
        ax.scatter(density[pairs > 0], moved[pairs > 0], s=60, facecolor="none", edgecolor="k", lw=0.8,
                   label=f"with overlapping patches ({np.count_nonzero(pairs > 0)})")
    if np.isfinite(threshold):
        ax.axhline(threshold, color="C3", ls="--", lw=0.9, label=f"threshold {threshold:g} %")
    ax.set_ylim(bottom=0, top=max(np.max(moved, initial=0), threshold if np.isfinite(threshold) else 0) * 1.15 or 1)
    ax.set_xlabel("contact density A_r / A0 [%]")
    ax.set_ylabel("load redistribution [% of W]")
    mode = ""
    iterations = array(f, "realisations/interacting_iterations")
    if iterations.size and np.any(iterations > 0):
        converged = array(f, "realisations/interacting_converged")
        mode = f"\ninteracting mode: loads include it; converged in {int(np.sum(converged))} of {converged.size}"
    ax.set_title(f"interaction between spots, over {moved.size} realisation(s){mode}", fontsize=9)
    ax.legend(fontsize=7)


def summary_lines(f, d):
    def spread(values, fmt="{:.3g}"):
        if not values.size:
            return "–"
        return (fmt + " (min " + fmt + ", max " + fmt + ")").format(np.mean(values), np.min(values), np.max(values))

    k = d["realisation_count"]
    lines = [f"realisations: {k} (ids {d['realisation_ids'][0]}..{d['realisation_ids'][-1]}, seed {f.attrs.get('seed', '?')})"
             if d["realisation_ids"].size else f"realisations: {k}"]
    lines.append("summits / realisation: " + spread(array(f, "realisations/summit_count").astype(float)))
    asperities = array(f, "realisations/asperity_count").astype(float)
    lines.append("in contact / realisation: " + spread(asperities))
    total = array(f, "realisations/total_load_n")
    if total.size:
        lines.append("total load W [N]: " + spread(total))
    area = array(f, "realisations/contact_density") * 100
    if area.size:
        lines.append("contact density A_r/A0 [%]: " + spread(area))
    pairs = array(f, "realisations/overlapping_pairs")
    if pairs.size:
        lines.append(f"overlapping patch pairs: {int(pairs.sum())} in {np.count_nonzero(pairs)} of {pairs.size} realisations")
    n_asperities = int(asperities.sum())
    for name, what in (("cannot_slip_model1_count", "cannot slip (Model 1)"),
                       ("near_length_model2_count", "x near l (Model 2)")):
        counts = array(f, f"realisations/{name}")
        if counts.size:
            lines.append(f"{what}: {int(counts.sum())} of {n_asperities} asperities, "
                         f"in {np.count_nonzero(counts)} of {counts.size} realisations")
    warnings = array(f, "realisations/warnings")
    if warnings.size:
        warned = sum(1 for w in warnings if (w.decode() if isinstance(w, bytes) else str(w)).strip())
        lines.append(f"realisations with validity warnings: {warned} of {warnings.size}")
    return lines


def collect(f):
    """Everything the panels share, read once."""
    d = {}
    d["table"] = input_table(f)
    area = d["table"].get("nominal_area_m2")
    d["side_um"] = math.sqrt(area) * UM if isinstance(area, (int, float)) and area > 0 else None
    d["heights"] = array(f, "summits/height_m")
    d["sampled_stiffness"] = array(f, "summits/sampled_stiffness_n_per_m")
    d["contact_heights"] = array(f, "asperities/height_m")
    d["contact_stiffness"] = array(f, "asperities/stiffness_n_per_m")
    d["summit_offset"] = array(f, "realisations/summit_offset").astype(int)
    d["asperity_offset"] = array(f, "realisations/asperity_offset").astype(int)
    d["realisation_ids"] = array(f, "realisations/realisation").astype(int)
    d["realisation_count"] = int(f.attrs.get("realisation_count", max(d["summit_offset"].size - 1, 0)))
    # The map shows the first realisation, or the first with summits when it has none.
    counts = np.diff(d["summit_offset"]) if d["summit_offset"].size > 1 else np.empty(0, int)
    d["map_realisation"] = int(np.argmax(counts > 0)) if np.any(counts > 0) else None
    return d


def figures(path):
    """[(output path, Figure)] of the surface file `path`, not yet written: <stem>.png, or
    nothing when the file has nothing to plot (a fixed asperity list draws no summits)."""
    f = open_stengmc_file(path, FILE_TYPE, "`stengmc surface` output file")
    d = collect(f)
    panels = []
    if d["heights"].size:
        panels.append("heights")
    if d["sampled_stiffness"].size or (d["heights"].size and d["contact_stiffness"].size):
        panels.append("stiffness")
    if "load_separation/total_load_n" in f and np.any(array(f, "load_separation/total_load_n") > 0):
        panels.append("load_separation")
    if d["map_realisation"] is not None and "summits/x_m" in f:
        panels.append("positions")
    if array(f, "realisations/load_redistribution").size and array(f, "realisations/contact_density").size:
        panels.append("redistribution")
    input_file = attribute(f, "input_file") or path
    if not panels:
        why = ("the realisations drew no summits" if "target/heights/value" in f
               else "no sampled summits: a fixed asperity list draws none")
        print(f"{path}: nothing to plot for {input_file} ({why}); no figure written")
        return []
    panels.append("summary")
    columns = len(panels) if len(panels) < 3 else 2 if len(panels) == 4 else 3
    rows = math.ceil(len(panels) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(5.4 * columns, 4.9 * rows), squeeze=False)
    axes = axes.ravel()
    for letter, (ax, panel) in zip("abcdefgh", zip(axes, panels)):
        if panel == "heights":
            panel_heights(ax, f, d)
        elif panel == "stiffness":
            panel_stiffness(ax, f, d)
        elif panel == "load_separation":
            panel_load_separation(ax, f, d)
        elif panel == "positions":
            panel_positions(fig, ax, f, d)
        elif panel == "redistribution":
            panel_redistribution(ax, f, d)
        elif panel == "summary":
            ax.axis("off")
            text = "\n".join("\n".join(textwrap.wrap(line, 56, subsequent_indent="    "))
                             for line in summary_lines(f, d))
            ax.text(0.0, 1.0, text, va="top", ha="left", fontsize=8.5, transform=ax.transAxes, family="monospace")
            ax.set_title("summary over the realisations", fontsize=9)
        ax.set_title(f"({letter}) " + ax.get_title(), fontsize=9)
    for ax in axes[len(panels):]:
        ax.axis("off")
    title = f"stengmc surface: {input_file}, {d['realisation_count']} realisation(s)"
    surface_title = d["table"].get("title")
    if surface_title:
        title += f"\n{surface_title}"
    fig.suptitle("\n".join(w for line in title.split("\n") for w in textwrap.wrap(line, 130)), fontsize=10)
    fig.tight_layout()
    return [(figure_path(os.path.splitext(path)[0]), fig)]


def plot_surface(path):
    """Writes the figure of `path` beside it and returns its name; None when there is none."""
    written = save_figures(figures(path))
    return written[0] if written else None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("files", nargs="+", help="HDF5 files written by `stengmc surface`")
    add_output_options(parser)
    args = parser.parse_args()
    use_output_options(args)
    for path in args.files:
        plot_surface(path)


if __name__ == "__main__":
    main()
