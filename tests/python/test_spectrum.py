"""stengmc.spectrum on a numpy array against numpy's own FFT (the independent reference):
the single-sided amplitude spectrum of MODEL.md 3, A_k = 2 |sum w_n y_n e^(-2 pi i k n/M)| /
sum w_n after the mean is removed, and the lines it finds where the signal has them; and
the same analysis as `stengmc spectrum` of the record written as a CSV."""
import h5py
import numpy as np
import pytest

from conftest import run_cli

RATE_HZ = 100e6
N = 5000


def two_tones():
    t = np.arange(N) / RATE_HZ
    # Whole numbers of cycles in the record: each tone falls on a bin, no leakage.
    return t, 0.25 + 1.5 * np.sin(2 * np.pi * 1.2e6 * t) + 0.4 * np.cos(2 * np.pi * 2.6e6 * t)


def test_the_amplitude_spectrum_is_numpys(stengmc):
    _, v = two_tones()
    s = stengmc.spectrum(v, RATE_HZ, window="rectangular", high_resolution=False)
    reference = 2 * np.abs(np.fft.rfft(v - v.mean())) / N
    assert np.allclose(s["frequency_hz"], np.fft.rfftfreq(N, 1 / RATE_HZ), rtol=1e-12, atol=0)
    assert np.allclose(s["voltage_v"][1:], reference[1:], rtol=1e-9, atol=1e-12)
    assert s["mean_v"] == pytest.approx(0.25, rel=1e-12)
    # Peaks are refined between bins (20 kHz apart here): each tone within a tenth of a bin.
    bin_hz = RATE_HZ / N
    for tone_hz, amplitude_v in ((1.2e6, 1.5), (2.6e6, 0.4)):
        nearest = np.argmin(np.abs(s["peaks"]["frequency_hz"] - tone_hz))
        assert abs(s["peaks"]["frequency_hz"][nearest] - tone_hz) < 0.1 * bin_hz, tone_hz
        assert s["peaks"]["amplitude_v"][nearest] == pytest.approx(amplitude_v, rel=1e-4), tone_hz


def test_the_hann_window_is_the_periodic_one(stengmc):
    _, v = two_tones()
    w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(N) / N)  # DFT-even Hann (window.hpp)
    reference = 2 * np.abs(np.fft.rfft(w * (v - v.mean()))) / w.sum()
    s = stengmc.spectrum(v, RATE_HZ, high_resolution=False)
    assert np.allclose(s["voltage_v"][1:], reference[1:], rtol=1e-9, atol=1e-12)


def test_it_is_the_command_lines_analysis_of_the_same_record(stengmc, tmp_path):
    t, v = two_tones()
    csv = tmp_path / "record.csv"
    csv.write_text("t,V\n" + "".join(f"{a!r},{b!r}\n" for a, b in zip(t.tolist(), v.tolist())))
    out = tmp_path / "spectrum.h5"
    run_cli("spectrum", csv, "--out", out)
    ours = stengmc.spectrum(v, RATE_HZ)
    with h5py.File(out, "r") as f:
        assert np.array_equal(ours["frequency_hz"], f["spectrum/frequency"][()])
        assert np.allclose(ours["voltage_v"], f["spectrum/voltage"][()], rtol=1e-12, atol=1e-15)
        assert np.allclose(ours["lines"]["frequency_hz"], f["spectrum/lines/frequency"][()], rtol=1e-9)


def test_bad_arguments_are_named(stengmc):
    _, v = two_tones()
    with pytest.raises(ValueError, match="sample_rate_hz = -1 must be a finite number > 0"):
        stengmc.spectrum(v, -1.0)
    with pytest.raises(ValueError, match="window"):
        stengmc.spectrum(v, RATE_HZ, window="triangle")
    with pytest.raises(ValueError, match="windw"):
        stengmc.spectrum(v, RATE_HZ, windw="hann")
    with pytest.raises(ValueError, match="voltage_v: expected a one-dimensional array"):
        stengmc.spectrum(np.zeros((2, 10)), RATE_HZ)
