#pragma once
//! Samples of one sliding-propagator piece (PieceKind::oscillator) on a uniform time grid:
//! the free oscillator walked by its flow from sample to sample, the polynomial part by
//! Estrin's scheme, several samples side by side in the lanes of a SIMD register.
#include <cstddef>

#include "model/motion_knot.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {

//! One piece's share of a uniform grid: samples [first, end) of `times_s`.
struct OscillatorSamplingTask {
  const MotionKnot* start = nullptr;   //!< the piece's start knot
  const MotionPiece* piece = nullptr;  //!< kind oscillator
  double w0_rad_per_s = 0.0;           //!< the piece's time scale (Model2Integration)
  double step_s = 0.0;                 //!< the grid spacing
  const double* times_s = nullptr;     //!< the grid
  std::size_t first = 0;
  std::size_t end = 0;
  double* x_m = nullptr;               //!< x out, indexed like times_s
  double* v_m_per_s = nullptr;         //!< x' out, likewise
  //! The state half a spacing after samples [first, mid_end) (mid_end <= end), into these
  //! two (nullptr: none wanted).
  double* mid_x_m = nullptr;
  double* mid_v_m_per_s = nullptr;
  std::size_t mid_end = 0;
};

//! How many samples go side by side. Every width computes each sample by the same
//! operations in the same order (no fused multiply-add anywhere), so all give the same
//! bits: the width changes the speed only.
enum class SamplingLanes { two, four };

//! The widest width this processor runs (four needs AVX2 on x86-64; two is the baseline).
SamplingLanes widest_sampling_lanes();

//! Fills the task's outputs. The free oscillator x_h is walked in four interleaved walks:
//! every 128 samples (fewer where x_h is much larger than the motion, see the .cpp) it is
//! anchored in closed form at the block's first sample, the next three are one, two and
//! three spacings on from it, and every later sample is the flow over four spacings
//! applied to the sample four before; x = centre + x_h + x_p with x_p by Estrin's scheme.
//! A midpoint is the flow over half a spacing from its sample. `four` where the processor
//! lacks AVX2 runs as `two` (the same bits).
void sample_oscillator_piece(const OscillatorSamplingTask& task, SamplingLanes lanes);

}  // namespace stengmc
