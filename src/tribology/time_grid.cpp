#include "tribology/time_grid.hpp"

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace stengmc {

bool evenly_spaced(std::span<const double> times_s, double step_s) {
  const double tolerance = 1e-9 * step_s;
  const std::size_t count = times_s.size();
  const double* t = times_s.data();
  bool even = true;
  std::size_t j = 1;
#if defined(__SSE2__)
  // A comparison sets a lane to all ones where it holds (never for NaN); the lanes are
  // and-ed across the whole grid.
  const __m128d step = _mm_set1_pd(step_s);
  const __m128d upper = _mm_set1_pd(tolerance);
  const __m128d lower = _mm_set1_pd(-tolerance);
  auto holds = [&](const double* later) {
    const __m128d deviation = _mm_sub_pd(_mm_sub_pd(_mm_loadu_pd(later), _mm_loadu_pd(later - 1)), step);
    return _mm_and_pd(_mm_cmple_pd(deviation, upper), _mm_cmpge_pd(deviation, lower));
  };
  // Two accumulators, four spacings per pass: the and-chain is not the limit.
  __m128d within = _mm_castsi128_pd(_mm_set1_epi64x(-1));
  __m128d within_odd = within;
  for (; j + 3 < count; j += 4) {
    within = _mm_and_pd(within, holds(t + j));
    within_odd = _mm_and_pd(within_odd, holds(t + j + 2));
  }
  for (; j + 1 < count; j += 2) within = _mm_and_pd(within, holds(t + j));
  even = _mm_movemask_pd(_mm_and_pd(within, within_odd)) == 3;
#endif
  for (; j < count; ++j) even &= std::abs(t[j] - t[j - 1] - step_s) <= tolerance;
  return even;
}

}  // namespace stengmc
