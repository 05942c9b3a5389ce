#pragma once
//! What the gamma and Weibull families share: parameters shape and scale (both > 0),
//! support [0, inf), and partial moments through the regularised incomplete gamma function.
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"

namespace stengmc {

inline void check_shape_and_scale(const char* family, double shape, double scale) {
  if (!(shape > 0.0)) throw InputError(std::string(family) + " distribution: shape = " + format_number(shape) + " must be > 0");
  if (!(scale > 0.0)) throw InputError(std::string(family) + " distribution: scale = " + format_number(scale) + " must be > 0");
}

}  // namespace stengmc
