#!/usr/bin/env python3
"""The figure checks themselves (scripts/figure_checks.py), on small planted figures.

A clean figure must pass; the same figure with one planted fault — a legend placed outside
the figure, a legend over the data, a flat panel that does not say why, round-off drawn with a 1e-12 multiplier,
an expected line beyond the frequency axis, a 26-entry legend, two entries with the same
label, two drawn alike, "(red)" on an orange curve, "um", bars on a log axis, a title cut
by the figure's edge — must fail, naming the fault. A flat panel that says "identically
zero" passes. Runs in a second or two (Debian's python3-matplotlib)."""
import os
import sys
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from figure_checks import figure_problems  # noqa: E402

T = np.linspace(0, 10, 200)
LINES_MHZ = [0.8, 1.2]


def clean():
    """A run-like figure: a trace with a legend and a spectrum showing both expected lines."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6, 5))
    top.plot(T, np.sin(T), color="C0", label="k = 25 N/m")
    top.plot(T, np.cos(T), color="C1", label="k = 50 N/m")
    top.set_xlabel("t [µs]")
    top.set_ylabel("x [µm]")
    top.legend(loc="upper right", fontsize=7)
    f = np.linspace(0, 2, 400)
    bottom.semilogy(f, 1e-3 / (1 + ((f - 0.8) / 0.02) ** 2) + 1e-3 / (1 + ((f - 1.2) / 0.02) ** 2) + 1e-8)
    bottom.set_xlim(0, 1.6)
    bottom.set_xlabel("f [MHz]")
    bottom.set_ylabel("amplitude [V]")
    fig.tight_layout()
    return fig, top, bottom


class FigureChecksTest(unittest.TestCase):
    def problems(self, fig):
        found = figure_problems(fig, LINES_MHZ)
        plt.close(fig)
        return found

    def assertFault(self, fig, words):
        found = self.problems(fig)
        self.assertTrue(any(words in p for p in found), f"expected a problem with {words!r}, got {found}")

    def test_clean_figure_passes(self):
        fig, _, _ = clean()
        self.assertEqual(self.problems(fig), [])

    def test_legend_outside_the_figure(self):
        fig, top, _ = clean()
        top.legend(loc="upper left", bbox_to_anchor=(1.3, 1.0))
        self.assertFault(fig, "legend reaches outside the figure")

    def test_legend_over_the_data(self):
        fig, top, _ = clean()
        top.clear()
        top.plot(T, np.full_like(T, 0.95), color="C0", label="a trace along the top")
        top.plot(T, np.zeros_like(T) + T / 100, color="C1", label="another")
        top.set_ylim(0, 1)
        top.legend(loc="upper center", fontsize=12, ncol=2, mode="expand")
        self.assertFault(fig, "the legend hides")

    def test_flat_panel_without_a_word(self):
        fig, top, _ = clean()
        top.clear()
        top.plot(T, np.zeros_like(T))
        self.assertFault(fig, "empty panel")

    def test_flat_panel_that_says_why_passes(self):
        fig, top, _ = clean()
        top.clear()
        top.axhline(0.0)
        top.text(0.5, 0.5, "V identically zero (every sample 0)", transform=top.transAxes)
        self.assertEqual(self.problems(fig), [])

    def test_round_off_drawn_as_signal(self):
        fig, top, _ = clean()
        top.clear()
        top.plot(T, 1e-12 * np.sin(7 * T))
        self.assertFault(fig, "multiplier")

    def test_expected_line_beyond_the_axis(self):
        fig, _, bottom = clean()
        bottom.set_xlim(0, 0.09)  # 4x a drift bin, as before issue 24
        self.assertFault(fig, "expected lines at 0.8, 1.2 MHz lie outside")

    def test_long_legend(self):
        fig, top, _ = clean()
        for i in range(26):
            top.plot(T, np.sin(T + i), label=f"k = {20 + i} N/m")
        top.legend(fontsize=4)
        self.assertFault(fig, "legend of 28 entries")

    def test_repeated_labels(self):
        fig, top, _ = clean()
        top.clear()
        for i in range(4):
            top.plot(T, np.sin(T + i), color=f"C{i}", label="k = 75 N/m")
        top.legend()
        self.assertFault(fig, "same label")

    def test_entries_drawn_alike(self):
        fig, top, _ = clean()
        top.clear()
        top.plot(T, np.sin(T), color="C0", label="k = 25 N/m")
        top.plot(T, np.cos(T), color="C0", label="k = 50 N/m")
        top.legend()
        self.assertFault(fig, "drawn alike")

    def test_colour_word_that_lies(self):
        fig, top, _ = clean()
        top.clear()
        top.plot(T, np.sin(T), color="C1", label="one asperity (red)")  # C1 is orange
        top.legend()
        self.assertFault(fig, "says '(red)'")

    def test_colour_word_that_holds_passes(self):
        fig, top, _ = clean()
        top.clear()
        top.plot(T, np.sin(T), color="tab:red", label="one asperity (red)")
        top.legend()
        self.assertEqual(self.problems(fig), [])

    def test_ascii_micro(self):
        fig, top, _ = clean()
        top.set_ylabel("x [um]")
        self.assertFault(fig, "'um' or 'us'")

    def test_bars_on_a_log_axis(self):
        fig, top, _ = clean()
        top.clear()
        top.bar([1, 2, 3], [0.004, 0.99, 0.004])
        top.set_yscale("log")
        self.assertFault(fig, "bars on a logarithmic axis")

    def test_title_cut_by_the_edge(self):
        fig, top, _ = clean()
        top.set_title("a title far too long for this figure " * 6)
        self.assertFault(fig, "cut by the figure's edge")


if __name__ == "__main__":
    unittest.main()
