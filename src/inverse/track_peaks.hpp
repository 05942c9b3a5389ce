#pragma once
//! The lines of one tracking window in the excited regime (docs/tracking.md, line detection):
//! peaks of the window's Hann periodogram. A driven asperity's line is a random narrow-band
//! process, not the deterministic damped sinusoid ESPRIT models: ESPRIT splits it into a main
//! line and satellites and wanders with them, while the periodogram's peak of a window a few
//! coherence times long finds it where it is (seen on simulated records: the 95 N/m line of the
//! excited example at SNR 100-290 where ESPRIT missed it).
#include <span>

#include "inverse/known_device.hpp"
#include "inverse/track_lines.hpp"

namespace stengmc {

class PeakLineDetector {
 public:
  //! `settings` as LineDetector's: band, white noise, sample rate, threshold and grey margin,
  //! cluster_hz (0: two Hann main-lobe half-widths, 2/T) and dynamic_range.
  PeakLineDetector(const KnownDevice& device, LineDetectorSettings settings);

  //! The window's mean and its lines: local maxima of the Hann amplitude spectrum (zero-padded
  //! 4x, the peak refined by a parabola through the log amplitudes) in the band, judged against
  //! the window's floor (the larger of the white noise and the band's median level: a driven
  //! asperity's off-resonance response raises it). Each line's
  //!  - snr: z = A sqrt(N / 2) / sigma_floor, as LineDetector's for a line of constant envelope;
  //!  - frequency_se_hz: how far a window's peak of the random line falls from its centre, the
  //!    line's half-width as the window resolves it, (gamma + 1.5 / T) / 2 pi, with the noise's
  //!    Cramer-Rao term sqrt(6) / (2 pi z T) added in quadrature;
  //!  - damping_per_s: ln(A_first / A_second) / (T / 2) from the amplitudes at the line of the
  //!    window's two halves: gamma for a free ring-down (a released asperity), scattered
  //!    either way for a driven line.
  [[nodiscard]] WindowLines detect(std::span<const double> window) const;
  [[nodiscard]] const LineDetectorSettings& settings() const { return settings_; }

 private:
  const KnownDevice& device_;
  LineDetectorSettings settings_;
};

}  // namespace stengmc
