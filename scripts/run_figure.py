"""The figure of one `stengmc run` (or `circuit`) output file: one panel per trace the file
holds, over time: x with the imposed x0 and the element length l, x', friction, V, Q and
the element currents i_i (the paper's Figs. 2-5).

Units are figure_style's (µm, m/s, mN, mV, fC, nA, µs). Asperities are told apart by a
legend up to eight of them, by a stiffness colour bar beyond (x' then as an image: rows of
asperities sorted by k, since 25 overlaid velocity traces are a tangle). A V or Q that is
round-off of cancelling element currents, or a trace that is exactly zero, is not drawn:
its panel says "identically zero" and why. Debian's python3-h5py and matplotlib."""
import textwrap

import matplotlib.pyplot as plt
import numpy as np
from figure_style import ELEMENTARY_CHARGE_C, StiffnessColours, is_round_off, micro, say_identically_zero, unit
from stengmc_h5 import attribute

PANELS = [("x", "asperity/x"), ("v", "asperity/v"), ("friction", "asperity/friction"),
          ("voltage", "circuit/voltage"), ("charge", "circuit/charge"), ("current", "asperity/current")]


def silent(f):
    """{panel: (peak |value|, why)} for the traces that are exactly zero or round-off, judged
    against what the physics would give: V against R_load x the largest sum of |i_i|, Q
    against one electron's charge."""
    quiet = {}
    slipped = "asperity/v" not in f or not is_round_off(f["asperity/v"][:], 0.0)
    never = "" if slipped else "no asperity slips: x′ = 0 throughout"
    if not slipped:
        quiet["v"] = (0.0, never)
    current = f["asperity/current"][:] if "asperity/current" in f else None
    if current is not None and is_round_off(current, 0.0):
        quiet["current"] = (float(np.max(np.abs(current), initial=0.0)), never)
    load = float(f["circuit"].attrs.get("load_resistance_ohm", 0.0)) if "circuit" in f else 0.0
    cancel = "the element currents cancel: Σ i_i = 0" if slipped else never
    if "circuit/voltage" in f:
        v = f["circuit/voltage"][:]
        scale = load * float(np.max(np.sum(np.abs(current), axis=0), initial=0.0)) if current is not None else 0.0
        if is_round_off(v, scale):
            quiet["voltage"] = (float(np.max(np.abs(v), initial=0.0)), cancel)
    if "circuit/charge" in f:
        peak = float(np.max(np.abs(f["circuit/charge"][:]), initial=0.0))
        if peak <= ELEMENTARY_CHARGE_C:  # less than one electron moved: no charge at all
            quiet["charge"] = (peak, cancel)
    return quiet


def draw_lines(ax, t, values, colours, factor, lw=0.8):
    for i, row in enumerate(values):
        ax.plot(t, row * factor, lw=lw, color=colours.colour(i), label=colours.label(i))


def x_panel(ax, f, t, colours):
    factor, m_unit = unit("m")
    draw_lines(ax, t, f["asperity/x"][:], colours, factor, lw=1)
    if "asperity/x0" in f:
        for i, row in enumerate(f["asperity/x0"][:]):
            ax.plot(t, row * factor, lw=0.8, ls="--", color="grey", label="imposed x0" if i == 0 else None)
    for length in np.unique(f["asperity/l"][:]):
        ax.axhline(length * factor, color="red", lw=0.8, ls=":", label=f"element length l = {length * factor:g} {m_unit}")
    ax.set_ylabel(f"x [{m_unit}]")


def velocity_image(fig, ax, f, t, colours):
    """x' of many asperities as rows of an image, sorted by stiffness (k on the y axis)."""
    v = f["asperity/v"][:]
    order = np.argsort(colours.k)
    limit = float(np.max(np.abs(v), initial=0.0)) or 1.0
    mesh = ax.pcolormesh(t, np.arange(v.shape[0]), v[order], cmap="RdBu_r", vmin=-limit, vmax=limit, shading="nearest",
                         rasterized=True)
    fig.colorbar(mesh, ax=ax, pad=0.01, fraction=0.03, label="x′ [m/s]")
    ticks = np.unique(np.linspace(0, v.shape[0] - 1, 5).round().astype(int))
    ax.set_yticks(ticks)
    ax.set_yticklabels([f"{colours.k[order[i]]:.3g}" for i in ticks])
    ax.set_ylabel("asperity by k [N/m]")


def run_figure(f, path):
    """The Figure of the run file `f` (opened from `path`)."""
    t_factor, t_unit = unit("s")
    t = f["time"][:] * t_factor
    tc = t[: f["circuit/voltage"].shape[0]] if "circuit/voltage" in f else t
    if "asperity/k" in f:
        colours = StiffnessColours(f["asperity/k"][:], f["asperity/phi"][:] if "asperity/phi" in f else None)
    else:  # a `stengmc circuit` file: elements driven by given displacements, no stiffness
        elements = f["asperity/x"].shape[0] if "asperity/x" in f else 0
        colours = StiffnessColours(np.arange(1.0, elements + 1), known=False)
    panels = [name for name, dataset in PANELS if dataset in f]  # a study may leave traces out
    quiet = silent(f)
    heights = [0.55 if p in quiet else 1.0 for p in panels]
    fig, axes = plt.subplots(len(panels), 1, figsize=(10.5, 0.6 + 2.1 * sum(heights)), sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": heights}, layout="constrained")
    axes = axes[:, 0]
    quantity = {"v": ("x′", "m/s"), "current": ("i_i", "A"), "voltage": ("V", "V"), "charge": ("Q", "C")}
    for ax, panel in zip(axes, panels):
        if panel in quiet:
            what, si = quantity[panel]
            say_identically_zero(ax, what, quiet[panel][0], si, quiet[panel][1])
            ax.set_ylabel(f"{what} [{unit(si)[1]}]")
        elif panel == "x":
            x_panel(ax, f, t, colours)
        elif panel == "v" and colours.scaled:
            velocity_image(fig, ax, f, t, colours)
        elif panel == "v":
            draw_lines(ax, t, f["asperity/v"][:], colours, 1.0)
            ax.set_ylabel("x′ [m/s]")
        elif panel == "friction":
            factor, n_unit = unit("N")
            draw_lines(ax, t, f["asperity/friction"][:], colours, factor)
            ax.set_ylabel(f"friction [{n_unit}]")
        elif panel == "voltage":
            factor, v_unit = unit("V")
            ax.plot(tc, f["circuit/voltage"][:] * factor, lw=0.8, color="k")
            ax.set_ylabel(f"V [{v_unit}]")
        elif panel == "charge":
            factor, q_unit = unit("C")
            ax.plot(tc, f["circuit/charge"][:] * factor, lw=1, color="k")
            ax.set_ylabel(f"Q [{q_unit}]")
        elif panel == "current":
            factor, a_unit = unit("A")
            draw_lines(ax, tc, f["asperity/current"][:], colours, factor)
            ax.set_ylabel(f"i_i [{a_unit}]")
        if panel in ("x", "friction", "current") and panel not in quiet:
            colours.colour_bar(fig, ax)
        if panel in ("voltage", "charge", "current") and tc.size < t.size and panel not in quiet:
            # An invalid run: say where the circuit stops rather than leave the rest blank.
            ax.text(0.6, 0.5, f"circuit cut at t = {tc[-1]:.3g} {t_unit}: x reached l", transform=ax.transAxes,
                    ha="center", va="center", fontsize=9, color="red")
        mark_domain_exits(ax, f, t_factor)
    # One legend, beside the top panel: the same colours hold in every panel. A run without
    # per-asperity traces (`[output] traces = []`, a long record) has nothing to label.
    if axes[0].get_legend_handles_labels()[0]:
        axes[0].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    axes[-1].set_xlabel(f"t [{t_unit}]")
    fig.suptitle(title(f, path), fontsize=9)
    return fig


def mark_domain_exits(ax, f, t_factor):
    if "events/kind" not in f:
        return
    kinds = [k.decode() if isinstance(k, bytes) else k for k in f["events/kind"][:]]
    for time, kind in zip(f["events/time"][:], kinds):
        if kind == "domain_exit":
            ax.axvline(time * t_factor, color="red", lw=1)


def title(f, path):
    text = micro(attribute(f, "title")) or path
    if not int(f.attrs.get("valid", 1)):
        text += "  [INVALID: x reached l (red line); circuit cut there]"
    return "\n".join(textwrap.wrap(text, 110))
