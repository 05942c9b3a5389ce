#pragma once
//! The S-TENG element formulas hold for x < l only (MODEL.md §2, validity).
#include <optional>
#include <span>

#include "tribology/motion.hpp"

namespace stengmc {

//! First time [s] at which x reaches `length_m`, or nothing. Found from the samples
//! and then located on the dense output by bisection to ~1e-15 relative.
std::optional<double> first_domain_exit(const Motion& motion, std::span<const double> times_s,
                                        std::span<const double> x_m, double length_m);

}  // namespace stengmc
