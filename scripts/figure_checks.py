"""What can be checked of a rendered matplotlib Figure, as a list of problems (empty: none).

- no bars on a logarithmic axis;
- every legend lies inside the figure, hides at most 5 % of its panel's data points, has at most MAX_ENTRIES entries, no two entries with
  the same label or the same look (colour, line style, marker), and an entry that names
  its colour, "(red)", is drawn in that colour;
- no text is cut: every axes with its labels, ticks and title, and every figure text,
  lies inside the figure;
- no empty panel: an axes shows data that varies (a line, bars, points, an image) or says
  in a text why it has none;
- no round-off drawn as a signal: no linear axis carries a multiplier like "1e-12" (the
  unit's prefix should be chosen, or the panel say "identically zero");
- µm and µs, never "um" or "us" after a number or in a unit bracket;
- the expected lines inside the axes: every frequency given lies within the frequency
  axis (an axis labelled in MHz) of every panel that has one.
Used by check_figures.py on the shipped figures and by tests/figures on planted faults."""
import re

import matplotlib
import matplotlib.colors
import numpy as np
from matplotlib.collections import Collection, QuadMesh
from matplotlib.image import AxesImage
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle

MAX_ENTRIES = 10  # eight asperities, the imposed x0 and the element length
TOLERANCE_PX = 2.0
MAX_COVERED = 0.05  # of a panel's data points a legend may sit on
ASCII_MICRO = re.compile(r"(\d\s?|\[)u[ms]\b")
# A word names the CSS colour or matplotlib's default-cycle ("tab:") shade of it.
TAB = {"red": "tab:red", "blue": "tab:blue", "green": "tab:green", "orange": "tab:orange", "grey": "tab:gray",
       "purple": "tab:purple"}
COLOUR_WORD = re.compile(r"\((red|blue|green|orange|black|grey|gray|purple)\)")


def inside(box, outer):
    return (box.x0 >= outer.x0 - TOLERANCE_PX and box.y0 >= outer.y0 - TOLERANCE_PX
            and box.x1 <= outer.x1 + TOLERANCE_PX and box.y1 <= outer.y1 + TOLERANCE_PX)


def panel_name(ax, index):
    title = ax.get_title() or ax.get_ylabel() or ax.get_xlabel()
    return f"panel {index + 1}" + (f" ({title.splitlines()[0][:50]})" if title else "")


def is_colour_bar(ax):
    return hasattr(ax, "_colorbar")


def handle_look(handle):
    """What tells a legend entry apart from another: colour, line style, marker, hatch."""
    if isinstance(handle, Line2D):
        return ("line", matplotlib.colors.to_hex(handle.get_color(), keep_alpha=False), handle.get_linestyle(),
                handle.get_marker(), handle.get_markerfacecolor() if handle.get_marker() not in ("", "None", None) else "")
    if isinstance(handle, Patch):
        return ("patch", matplotlib.colors.to_hex(handle.get_facecolor(), keep_alpha=True),
                matplotlib.colors.to_hex(handle.get_edgecolor(), keep_alpha=True), handle.get_hatch())
    if isinstance(handle, Collection):
        face, edge = handle.get_facecolor(), handle.get_edgecolor()
        sizes = handle.get_sizes()[:1] if hasattr(handle, "get_sizes") else ()
        return ("collection", type(handle).__name__, matplotlib.colors.to_hex(face[0], keep_alpha=True) if len(face) else "",
                matplotlib.colors.to_hex(edge[0], keep_alpha=True) if len(edge) else "", tuple(sizes))
    return ("other", id(handle))


def handle_colour(handle):
    if isinstance(handle, Line2D):
        return matplotlib.colors.to_rgb(handle.get_color())
    if isinstance(handle, Patch):
        return matplotlib.colors.to_rgb(handle.get_facecolor())
    return None


def covered_fraction(ax, box):
    """The fraction of the axes' data points (line vertices, scatter points, bars) drawn under
    the display box `box`."""
    points = [line.get_transform().transform(line.get_xydata()) for line in ax.get_lines()
              if line.get_transform() == ax.transData and len(line.get_xydata()) > 1]
    points += [c.get_offset_transform().transform(c.get_offsets()) for c in ax.collections
               if not isinstance(c, QuadMesh) and len(c.get_offsets()) > 1]
    bars = [p for p in ax.patches if isinstance(p, Rectangle) and p.get_data_transform() == ax.transData]
    if bars:  # a bar by the middle of its top edge and its centre
        tops = [(b.get_x() + b.get_width() / 2, b.get_y() + b.get_height()) for b in bars]
        middles = [(b.get_x() + b.get_width() / 2, b.get_y() + b.get_height() / 2) for b in bars]
        points.append(ax.transData.transform(np.array(tops + middles, float)))
    if not points:
        return 0.0
    xy = np.concatenate(points)
    xy = xy[np.all(np.isfinite(xy), axis=1)]
    window = ax.get_window_extent()
    shown = (xy[:, 0] >= window.x0) & (xy[:, 0] <= window.x1) & (xy[:, 1] >= window.y0) & (xy[:, 1] <= window.y1)
    under = shown & (xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1) & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1)
    return float(np.count_nonzero(under)) / max(1, np.count_nonzero(shown))


def legend_problems(legend, where, figure_box, renderer, ax=None):
    problems = []
    box = legend.get_window_extent(renderer)
    if ax is not None and covered_fraction(ax, box) > MAX_COVERED:
        problems.append(f"{where}: the legend hides {100 * covered_fraction(ax, box):.0f} % of the panel's data")
    if not inside(legend.get_window_extent(renderer), figure_box):
        problems.append(f"{where}: the legend reaches outside the figure")
    labels = [t.get_text() for t in legend.get_texts()]
    handles = legend.legend_handles if hasattr(legend, "legend_handles") else legend.legendHandles
    if len(labels) > MAX_ENTRIES:
        problems.append(f"{where}: a legend of {len(labels)} entries (at most {MAX_ENTRIES}: use a colour bar)")
    repeated = sorted({label for label in labels if labels.count(label) > 1})
    if repeated:
        problems.append(f"{where}: legend entries with the same label: {repeated}")
    looks = [handle_look(h) for h in handles]
    same = sorted({labels[i] for i in range(len(looks)) for j in range(len(looks))
                   if i != j and looks[i] == looks[j] and looks[i][0] != "other"})
    if same:
        problems.append(f"{where}: legend entries drawn alike (same colour and style): {same}")
    for label, handle in zip(labels, handles):
        named = COLOUR_WORD.search(label)
        colour = handle_colour(handle)
        if named and colour is not None:
            word = named.group(1).replace("gray", "grey")
            named_as = [matplotlib.colors.to_rgb(word), matplotlib.colors.to_rgb(TAB.get(word, word))]
            if min(np.linalg.norm(np.subtract(colour, rgb)) for rgb in named_as) > 0.35:
                problems.append(f"{where}: the legend says '({word})' for a curve drawn in "
                                f"{matplotlib.colors.to_hex(colour)}")
    return problems


def varies(values):
    values = np.asarray(values, float).ravel()
    values = values[np.isfinite(values)]
    return values.size > 1 and np.ptp(values) > 1e-12 * max(np.max(np.abs(values)), 1e-300)


def shows_data(ax):
    """True when the axes draws data that varies: a line along data coordinates, bars,
    points, an image; a straight rule (axhline, axvline) alone is not data."""
    for line in ax.get_lines():
        if line.get_transform() == ax.transData and varies(line.get_ydata()) and len(line.get_xdata()) > 1:
            return True
    for patch in ax.patches:
        if isinstance(patch, Rectangle) and patch.get_data_transform() == ax.transData and patch.get_height() != 0:
            return True
    for collection in ax.collections:
        if isinstance(collection, QuadMesh):
            if varies(collection.get_array()):
                return True
        elif len(collection.get_offsets()) > 1 or len(collection.get_paths()) > 0:
            return True
    return any(isinstance(image, AxesImage) for image in ax.images)


def says_why(ax):
    return any(text.get_text().strip() for text in ax.texts)


def axes_problems(ax, where, figure_box, renderer, expected_mhz):
    problems = []
    if not inside(ax.get_tightbbox(renderer), figure_box):
        problems.append(f"{where}: its labels or title are cut by the figure's edge")
    if ax.axison and not is_colour_bar(ax) and not shows_data(ax) and not says_why(ax):
        problems.append(f"{where}: an empty panel (no data that varies) that does not say why")
    for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
        offset = axis.get_offset_text().get_text()
        if scale == "linear" and offset and not is_colour_bar(ax):
            problems.append(f"{where}: an axis with the multiplier '{offset}' (choose the unit's prefix, "
                            "or say the trace is identically zero)")
    for label, limits in ((ax.get_xlabel(), ax.get_xlim()), (ax.get_ylabel(), ax.get_ylim())):
        if "MHz" in label and expected_mhz is not None and len(expected_mhz):
            low, high = min(limits), max(limits)
            outside = [f"{f:.3g}" for f in expected_mhz if not low <= f <= high]
            if outside:
                problems.append(f"{where}: expected lines at {', '.join(outside)} MHz lie outside the axis "
                                f"[{low:.3g}, {high:.3g}] MHz")
    bars = [p for p in ax.patches if isinstance(p, Rectangle) and p.get_data_transform() == ax.transData]
    if bars and ax.get_yscale() == "log":
        problems.append(f"{where}: bars on a logarithmic axis (a bar's length there depends on an arbitrary base)")
    if ax.get_legend() is not None:
        problems += legend_problems(ax.get_legend(), where, figure_box, renderer, ax)
    return problems


def texts_of(fig):
    """Every text of the figure once (the suptitle is also one of fig.texts)."""
    texts = list(fig.texts) + ([fig._suptitle] if getattr(fig, "_suptitle", None) is not None else [])
    for ax in fig.axes:
        texts += [ax.title, ax._left_title, ax._right_title, ax.xaxis.label, ax.yaxis.label] + list(ax.texts)
        if ax.get_legend() is not None:
            texts += list(ax.get_legend().get_texts())
    return list({id(t): t for t in texts}.values())


def figure_problems(fig, expected_mhz=None):
    """Every problem found in `fig` (drawn here with its own renderer); `expected_mhz`: the
    frequencies [MHz] that must lie within every MHz axis."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    figure_box = fig.bbox
    problems = []
    for index, ax in enumerate(fig.axes):
        if ax.get_visible():
            problems += axes_problems(ax, panel_name(ax, index), figure_box, renderer, expected_mhz)
    for text in texts_of(fig):
        content = text.get_text()
        if content and ASCII_MICRO.search(content):
            problems.append(f"'um' or 'us' for µm or µs in: {content.splitlines()[0][:70]!r}")
        if content and text in fig.texts + [getattr(fig, "_suptitle", None)]:
            if not inside(text.get_window_extent(renderer), figure_box):
                problems.append(f"the text {content.splitlines()[0][:50]!r} is cut by the figure's edge")
    for legend in fig.legends:
        problems += legend_problems(legend, "figure legend", figure_box, renderer)
    return problems
