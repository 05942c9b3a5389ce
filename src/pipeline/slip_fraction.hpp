#pragma once
//! When an asperity counts as sliding: Model 1, x' != 0; Model 2, |v_b - x'| > 1/s (the
//! atan regularisation's width: below it the belt holds the asperity, MODEL.md §1).
#include <cmath>
#include <cstddef>
#include <span>

#include "io/study.hpp"

namespace stengmc {

//! Fraction of the velocity samples in which the asperity slides.
inline double slip_fraction(const Study& study, std::span<const double> velocity_m_per_s) {
  if (velocity_m_per_s.empty()) return 0.0;
  std::size_t sliding = 0;
  for (double v : velocity_m_per_s) {
    const bool slides = study.model == ModelKind::model1
        ? v != 0.0
        : std::abs(study.model2.belt_velocity_m_per_s - v) > 1.0 / study.model2.atan_sharpness_s_per_m;
    sliding += slides ? 1 : 0;
  }
  return static_cast<double>(sliding) / static_cast<double>(velocity_m_per_s.size());
}

}  // namespace stengmc
