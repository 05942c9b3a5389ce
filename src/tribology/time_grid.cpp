#include "tribology/time_grid.hpp"

#include <cmath>

#include "core/processor_features.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define STENGMC_GRID_CHECK_AVX 1
#endif

namespace stengmc {

namespace {

#ifdef STENGMC_GRID_CHECK_AVX
//! Spacings j, j+1, ... in AVX registers, four per compare, up to the last full four;
//! advances j past them. |deviation| by clearing the sign bit; a compare sets a lane to
//! all ones where it holds, never for NaN; the lanes are and-ed over the whole grid.
[[gnu::target("avx")]] bool spacings_within_avx(const double* t, std::size_t count, double step_s, double tolerance,
                                                std::size_t& j) {
  const __m256d step = _mm256_set1_pd(step_s);
  const __m256d limit = _mm256_set1_pd(tolerance);
  const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
  __m256d within = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  for (; j + 3 < count; j += 4) {
    const __m256d deviation = _mm256_sub_pd(_mm256_sub_pd(_mm256_loadu_pd(t + j), _mm256_loadu_pd(t + j - 1)), step);
    within = _mm256_and_pd(within, _mm256_cmp_pd(_mm256_and_pd(deviation, magnitude), limit, _CMP_LE_OQ));
  }
  return _mm256_movemask_pd(within) == 0xf;
}
#endif

}  // namespace

bool evenly_spaced(std::span<const double> times_s, double step_s) {
  const double tolerance = 1e-9 * step_s;
  const std::size_t count = times_s.size();
  const double* t = times_s.data();
  bool even = true;
  std::size_t j = 1;
#ifdef STENGMC_GRID_CHECK_AVX
  // Four spacings per compare where the processor has AVX (the plain loop stayed scalar:
  // ~3 us per 5000 samples, a tenth of sampling one asperity's motion).
  if (processor_has_avx()) even = spacings_within_avx(t, count, step_s, tolerance, j);
#endif
  for (; j < count; ++j) even &= std::abs(t[j] - t[j - 1] - step_s) <= tolerance;
  return even;
}

}  // namespace stengmc
