#pragma once
//! The two statistics the inversion reports of a set of stiffnesses (identified or true).
#include <vector>

namespace stengmc {

//! Median (mean of the middle two for an even count; 0 for none) [N/m].
double sample_median(std::vector<double> values);
//! Sample standard deviation of ln k (n - 1 denominator; 0 below two values) [-].
double sample_sd_log(const std::vector<double>& values);

}  // namespace stengmc
