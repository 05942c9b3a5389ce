#pragma once
//! When an asperity counts as sliding: Model 1, x' != 0; Model 2, |v_b - x'| > 1/s (the
//! atan regularisation's width: below it the belt holds the asperity, MODEL.md §1).
#include <cmath>
#include <cstddef>
#include <span>

#include "pipeline/study.hpp"

namespace stengmc {

struct SlidingRule {
  bool model1 = true;                  //!< Model 1: any nonzero velocity slides
  double belt_velocity_m_per_s = 0.0;  //!< Model 2: v_b
  double sharpness_s_per_m = 1.0;      //!< Model 2: s

  static SlidingRule of(const Study& study) {
    return {study.model == ModelKind::model1, study.model2.belt_velocity_m_per_s, study.model2.atan_sharpness_s_per_m};
  }
  [[nodiscard]] bool slides(double v) const {
    return model1 ? v != 0.0 : std::abs(belt_velocity_m_per_s - v) > 1.0 / sharpness_s_per_m;
  }
};

//! Fraction of the velocity samples in which the asperity slides.
inline double slip_fraction(const SlidingRule& rule, std::span<const double> velocity_m_per_s) {
  if (velocity_m_per_s.empty()) return 0.0;
  std::size_t sliding = 0;
  for (double v : velocity_m_per_s) sliding += rule.slides(v) ? 1 : 0;
  return static_cast<double>(sliding) / static_cast<double>(velocity_m_per_s.size());
}

inline double slip_fraction(const Study& study, std::span<const double> velocity_m_per_s) {
  return slip_fraction(SlidingRule::of(study), velocity_m_per_s);
}

}  // namespace stengmc
