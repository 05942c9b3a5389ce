"""Conventions every stengmc figure follows, in one place so the figures agree:

- one unit per quantity across all figures (UNITS): a charge is in fC in a run figure and in
  an ensemble figure alike, a time in µs, a displacement in µm;
- a trace that is round-off (|values| a billionth of what the physics makes, or a charge
  below one electron) is not drawn as a signal: the panel says "identically zero";
- asperities are told apart by legend entries up to MAX_LEGEND_ENTRIES, beyond that by a
  colour scale of their stiffness with a colour bar;
- "um" typed in a study's title is shown as µm.
Debian's python3-matplotlib and numpy."""
import re

import matplotlib
import matplotlib.ticker
import numpy as np

# (factor from SI, label) per SI unit. Fixed, not chosen per figure, so that two figures of
# the same quantity read in the same unit.
UNITS = {
    "s": (1e6, "µs"),
    "m": (1e6, "µm"),
    "m/s": (1.0, "m/s"),
    "N": (1e3, "mN"),
    "V": (1e3, "mV"),
    "C": (1e15, "fC"),
    "A": (1e9, "nA"),
    "Hz": (1e-6, "MHz"),
}

ELEMENTARY_CHARGE_C = 1.602176634e-19
# A sum of element currents (or their integral) that cancels to this fraction of its
# largest term is round-off of the cancellation, not a signal (double precision: ~1e-16).
ROUND_OFF = 1e-9
MAX_LEGEND_ENTRIES = 8


def unit(si_unit):
    """(factor, label) of a quantity given in `si_unit`: unit("C") -> (1e15, "fC")."""
    return UNITS[si_unit]


def micro(text):
    """'l = 50 um' -> 'l = 50 µm' (and us -> µs): study titles are typed in ASCII."""
    text = re.sub(r"(\d)\s?um\b", r"\1 µm", text)
    return re.sub(r"(\d)\s?us\b", r"\1 µs", text)


def is_round_off(values, scale):
    """True when every |value| is at most ROUND_OFF x `scale` (the size the physics gives the
    quantity), i.e. nothing but round-off: also when `values` are exactly zero."""
    values = np.asarray(values, float)
    values = values[np.isfinite(values)]
    peak = float(np.max(np.abs(values), initial=0.0))
    return peak == 0.0 or (scale > 0 and peak <= ROUND_OFF * scale)


def say_identically_zero(ax, what, peak, si_unit, why=""):
    """Instead of a trace: a zero line and, in the panel, that `what` is identically zero
    (with the largest |value| the file holds, so the reader can judge)."""
    ax.axhline(0.0, color="0.6", lw=0.8)
    bound = "every sample 0" if peak == 0 else f"|{what}| ≤ {peak:.1g} {si_unit}, round-off"
    ax.text(0.5, 0.5, f"{what} identically zero ({bound})" + (f"\n{why}" if why else ""), transform=ax.transAxes,
            ha="center", va="center", fontsize=9, color="0.25",
            bbox=dict(boxstyle="round", facecolor="white", edgecolor="0.7"))
    ax.set_ylim(-1, 1)
    ax.set_yticks([0])


class StiffnessColours:
    """Colours of the asperities: distinct C0..C7 with a legend entry each up to
    MAX_LEGEND_ENTRIES asperities, else one colour per stiffness from a colour scale (and a
    colour bar instead of the legend). Identical stiffnesses with different drive phases are
    named by their phase. Elements of unknown stiffness (a `stengmc circuit` file) keep the
    default colours, and past MAX_LEGEND_ENTRIES no legend entry."""

    def __init__(self, k, phase=None, known=True):
        """known False: `k` are stand-ins (a file without stiffnesses); entries say "element i"."""
        self.k = np.asarray(k, float)
        self.known = known
        self.scaled = self.k.size > MAX_LEGEND_ENTRIES and known
        self.phase = None if phase is None else np.asarray(phase, float)
        if self.scaled:
            positive = self.k[self.k > 0]
            low, high = (positive.min(), positive.max()) if positive.size else (1.0, 10.0)
            if not high > low:
                low, high = 0.9 * low, 1.1 * high
            # Logarithmic only over a decade or more: below, a linear bar reads more easily.
            self.norm = matplotlib.colors.LogNorm(low, high) if high > 10 * low else matplotlib.colors.Normalize(low, high)
            self.cmap = matplotlib.colormaps["viridis"]

    def colour(self, i):
        return self.cmap(self.norm(self.k[i])) if self.scaled else f"C{i % 10}"

    def label(self, i):
        """The legend entry of asperity i; None when a colour bar tells them apart."""
        if self.scaled or (not self.known and self.k.size > MAX_LEGEND_ENTRIES):
            return None
        if not self.known:
            return f"element {i + 1}"
        same_k = np.unique(self.k).size < self.k.size
        if same_k and self.phase is not None and np.unique(np.round(self.phase, 9)).size == self.k.size:
            return f"φ = {phase_text(self.phase[i])} (k = {self.k[i]:.3g} N/m)"
        if same_k:
            return f"asperity {i + 1} (k = {self.k[i]:.3g} N/m)"
        return f"k = {self.k[i]:.3g} N/m"

    def colour_bar(self, fig, ax):
        """The stiffness colour bar beside `ax` (only in the scaled case)."""
        if not self.scaled:
            return
        mappable = matplotlib.cm.ScalarMappable(norm=self.norm, cmap=self.cmap)
        bar = fig.colorbar(mappable, ax=ax, pad=0.01, fraction=0.03, label="asperity stiffness k [N/m]")
        bar.formatter = matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}")
        bar.update_ticks()

    def legend_proxy(self, ax, label, **style):
        """A neutral legend entry for lines drawn in the asperities' colours (`style`: ls, lw)."""
        ax.plot([], [], color="0.35", label=label + (" (colour: k)" if self.scaled else ""), **style)


def log_axis(ax, axis="y"):
    """Log scale labelled at 1, 2, 3, 5 × 10^k in plain numbers: the data span one or two
    decades, where a lone "10²" tick says nothing."""
    (ax.set_yscale if axis == "y" else ax.set_xscale)("log")
    which = ax.yaxis if axis == "y" else ax.xaxis
    which.set_major_locator(matplotlib.ticker.LogLocator(base=10, subs=(1.0, 2.0, 3.0, 5.0)))
    which.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    which.set_minor_formatter(matplotlib.ticker.NullFormatter())


def phase_text(phi):
    """A drive phase in multiples of π/2 where it is one: 0, π/2, π, 3π/2; else radians."""
    quarter = phi / (np.pi / 2)
    if abs(quarter - round(quarter)) < 1e-9:
        return {0: "0", 1: "π/2", 2: "π", 3: "3π/2"}.get(int(round(quarter)) % 4)
    return f"{phi:.3g} rad"
