#pragma once
//! The windowed discrete-time Fourier transform at any frequency, with its derivatives:
//! what peak refinement maximises (MODEL.md §3's A_k between the bins).
#include <complex>
#include <span>

namespace stengmc {

//! X(x) = sum_n v_n e^{-2 pi i x n} and its first two derivatives in x.
struct Dtft {
  std::complex<double> value;   //!< X
  std::complex<double> first;   //!< dX/dx = sum_n (-2 pi i n) v_n e^{-2 pi i x n}
  std::complex<double> second;  //!< d2X/dx2 = sum_n (-4 pi^2 n^2) v_n e^{-2 pi i x n}
};

//! The DTFT of the windowed samples v_n (window times signal) at x cycles per sample, in
//! one O(n) pass; the derivatives only when asked (they cost ~1.5 passes more).
//! The phasors e^{-2 pi i x n} are recomputed exactly at every 64th sample and advanced by
//! complex rotation in between (~1e-13 relative, as accurate as a sine per sample), in
//! four interleaved lanes so the loop runs at throughput, not latency.
Dtft windowed_dtft(std::span<const double> windowed, double cycles_per_sample, bool derivatives);

}  // namespace stengmc
