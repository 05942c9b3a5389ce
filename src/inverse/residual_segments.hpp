#pragma once
//! Whether a residual is noise throughout the record, not only on the whole (docs/inverse.md,
//! "the search"). Noise is stationary; a misfit of the physics is not. An atom with the wrong
//! load or onset misses its breakaway, so its error sits in the first microseconds, where a
//! global chi^2 dilutes it over the whole record: on held-out loads record 2 an order of 12
//! atoms (11 asperities, one load at 0.28 x its truth) fitted at chi^2 / M 1.068 whitened,
//! under the bound of 1.071, while its first tenth held 1.94 x the noise (21 standard
//! deviations); the truth's first tenth held 0.88 x.
//!
//! The residual is cut into equal consecutive segments; a segment of L samples of white noise
//! of level sigma sums to sum r_t^2 / sigma^2 ~ chi^2_L, whose upper tail is Q(L/2, x/2), the
//! regularised incomplete gamma function (Boost.Math). The worst segment is reported.
#include <cstddef>
#include <span>

namespace stengmc {

//! Ten segments: 10 us of a 100 us record, the scale of a breakaway and of the onsets' range.
inline constexpr std::size_t RESIDUAL_SEGMENTS = 10;

struct WorstSegment {
  std::size_t first_sample = 0, last_sample = 0;  //!< the segment furthest out
  double p_value = 1.0;
  std::size_t segments = 0;  //!< how many were tested
};

//! The segment of `residual`, from sample `first` on (a whitening filter's start-up left out),
//! whose power stands furthest above white noise of standard deviation `level_v`.
WorstSegment worst_residual_segment(std::span<const double> residual, double level_v, std::size_t first = 0,
                                    std::size_t segments = RESIDUAL_SEGMENTS);

//! The p-value below which one of `tests` is more than `sigmas` standard deviations of a normal
//! variable out (one-sided), after Bonferroni's correction for their number.
double bonferroni_p_bound(double sigmas, std::size_t tests);

}  // namespace stengmc
