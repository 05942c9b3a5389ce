#pragma once
//! Whether a fit explains a record to its noise (docs/inverse.md, "the search"): the one
//! judgement behind the search's re-seating (LineSearch re-seats only the orders that do not)
//! and the nested searches' stop (the first model whose best order does ends the search).
//!
//! A fit of M samples fits to its noise when its chi^2, RSS / sigma^2, lies within
//! FITS_SIGMAS standard deviations (sqrt(2 M)) of chi^2_M's mean M. Under white noise RSS and
//! sigma are the fit's own. Under a prior of coloured noise they are not: the white level,
//! taken above the lines, leaves the 1/f part out, so no fit of a coloured record would ever
//! fit, and every order would be re-seated, every nested model searched (the held-out noise
//! family took 9 s a record instead of 1.6 s). There the residual's noise spectrum is fitted,
//! and the RSS whitened by it is judged against the level that whitener leaves, as the
//! estimator judges its final fits.
//!
//! A chi^2 within its bound is not enough: the residual must also be noise throughout the
//! record (residual_segments.hpp), no tenth of it above the noise by more than FITS_SIGMAS
//! after Bonferroni's correction. A misfit confined to the breakaway (a wrong load or onset)
//! passes a global chi^2 that the rest of the record dilutes; it does not pass this.
#include <cmath>
#include <cstddef>
#include <functional>

#include "inverse/noise_whitening.hpp"
#include "inverse/record_fit.hpp"
#include "inverse/residual_segments.hpp"

namespace stengmc {

inline constexpr double FITS_SIGMAS = 5.0;
//! The bound on chi^2: (1 + 5 sqrt(2 / M)) M, 1.07 M at M = 10^4 (the held-out ideal family's
//! true orders under the ideal model: 0.97-1.05 M).
inline double fitting_chi2(std::size_t samples) {
  const auto m = static_cast<double>(samples);
  return (1.0 + FITS_SIGMAS * std::sqrt(2.0 / m)) * m;
}

//! The level [V] of the noise a whitener leaves on a record, the model's own floor included
//! (RecordEstimator's rule).
using WhitenedLevel = std::function<double(const Whitener&)>;

class NoiseJudge {
 public:
  //! White noise: judged at the fit's own level.
  NoiseJudge() = default;
  //! Coloured noise: judged whitened by the spectrum of each fit's residual, at `level`'s.
  explicit NoiseJudge(WhitenedLevel level) : level_(std::move(level)) {}

  struct Judgement {
    double chi2 = NAN;  //!< under the judged noise
    WorstSegment worst;  //!< its segment furthest out, tested only where chi2 is within its bound
                         //!< (else segments = 0)
    bool fits = false;  //!< chi2 within its bound and no segment out
  };
  //! `order` (a fit made by `fit`) under the judged noise. `fit`'s noise model is left as it was.
  [[nodiscard]] Judgement judge(RecordFit& fit, const OrderFit& order) const;
  [[nodiscard]] double chi2(RecordFit& fit, const OrderFit& order) const { return judge(fit, order).chi2; }
  [[nodiscard]] bool fits(RecordFit& fit, const OrderFit& order) const { return judge(fit, order).fits; }
  [[nodiscard]] bool coloured() const { return static_cast<bool>(level_); }

 private:
  WhitenedLevel level_;
  // The last judgement (the re-seating asks again of a fit it did not change).
  mutable double judged_rss_v2_ = NAN, judged_sigma_v_ = NAN;
  mutable std::size_t judged_atoms_ = 0;
  mutable Judgement judged_;
};

}  // namespace stengmc
