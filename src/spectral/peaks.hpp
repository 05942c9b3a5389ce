#pragma once
//! Spectral lines found in an amplitude spectrum (MODEL.md §3: a local maximum whose
//! prominence exceeds a threshold set relative to a robust noise-floor estimate).
#include <cstddef>
#include <map>
#include <span>
#include <vector>

#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

struct PeakOptions {
  double prominence_over_floor = 10.0;  //!< a peak's prominence must exceed this x the noise floor
  double min_separation_hz = 0.0;       //!< of two peaks closer than this, the weaker is dropped
  double min_frequency_hz = 0.0;        //!< ignore peaks below (DC, drift)
  double max_frequency_hz = 0.0;        //!< ignore peaks above (0: up to Nyquist), e.g. above a device's highest line
  //! > 0: the floor is local, the running median over this width (local_noise_floor.hpp)
  //! instead of one median over 0 .. Nyquist [Hz]
  double floor_window_hz = 0.0;
  std::size_t max_peaks = 64;           //!< keep at most this many, strongest first
  //! drop a peak not above this x the summed side-lobe leakage the stronger kept peaks' lines
  //! put at its frequency (window response incl. negative-frequency images); 0 disables.
  //! Without it a noise-free or zero-padded spectrum reports side lobes as lines.
  double leakage_margin = 2.0;
  //! > 0: candidates whose bin lies more than this many dB (plus a 12 dB allowance for the
  //! refinement's gain over the bin) below the strongest candidate's are not refined or
  //! returned: a later cut at this dynamic range would drop them anyway, and a noise-free
  //! spectrum has hundreds. 0 (default): all are returned.
  double skip_below_db = 0.0;
};

struct Peak {
  double frequency_hz = 0.0;  //!< refined frequency [Hz]
  double amplitude = 0.0;     //!< refined amplitude, signal unit
  double prominence = 0.0;    //!< height above the higher of the two flanking minima, signal unit
  std::size_t bin = 0;        //!< index of the local maximum in the spectrum
};

//! Robust noise floor: the rms amplitude a white-noise spectrum would have, estimated from
//! the median of A_k (Rayleigh: rms = median / sqrt(ln 2)), so lines do not raise it.
double noise_floor(const AmplitudeSpectrum& spectrum);

//! Peaks of `spectrum`, sorted by frequency, with frequency and amplitude refined on the
//! windowed DTFT of `signal` (the samples the spectrum was computed from).
//! `shared`, when given, carries what does not depend on the options' thresholds between
//! searches of the same spectrum and signal (PeakSearchShared).
struct PeakSearchShared;
std::vector<Peak> find_peaks(const AmplitudeSpectrum& spectrum, const SpectrumAnalyzer& analyzer,
                             std::span<const double> signal, double sample_rate_hz, const PeakOptions& options,
                             PeakSearchShared* shared = nullptr);

//! What several find_peaks calls on one spectrum and signal (a sweep of thresholds) can
//! share: a peak's refinement depends only on its bin and prominence, the local floor only
//! on its window, so each is computed once. Results are bitwise those of separate calls.
//! Use one per spectrum: it does not check that the spectrum or signal stayed the same.
struct PeakSearchShared {
  double floor_window_hz = -1.0;        //!< the window `floor` was computed for (-1: none yet)
  std::vector<double> floor;            //!< the noise floor per bin
  std::map<std::size_t, Peak> refined;  //!< refined peaks by bin
};

}  // namespace stengmc
