#include "core/format.hpp"
#include "surface/hertz_contact.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

void validate_inputs(const std::vector<double>& heights_m, double summit_radius_m, double effective_modulus_pa) {
  if (!std::isfinite(summit_radius_m) || summit_radius_m <= 0.0)
    throw InputError("hertz contact: summit radius R_s = " + format_number(summit_radius_m) + " m must be > 0");
  if (!std::isfinite(effective_modulus_pa) || effective_modulus_pa <= 0.0)
    throw InputError("hertz contact: effective modulus E* = " + format_number(effective_modulus_pa) + " Pa must be > 0");
  for (std::size_t i = 0; i < heights_m.size(); ++i)
    if (!std::isfinite(heights_m[i]))
      throw InputError("hertz contact: height of asperity " + std::to_string(i) + " is not finite");
}

//! Neumaier's compensated sum: the load solve targets 1e-12 relative and n reaches 1e4+,
//! so the plain sum's O(n eps) drift is kept out of the verification.
class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    if (std::abs(sum_) >= std::abs(x))
      comp_ += (sum_ - t) + x;
    else
      comp_ += (x - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + comp_; }

 private:
  double sum_ = 0.0;
  double comp_ = 0.0;
};

//! Builds the state from interferences given as depth - gap_i, where depth = z_max - d
//! and gap_i = z_max - z_i. Working in the depth keeps delta_i accurate to full relative
//! precision even when the heights carry a large common offset (z ~ 1e-6 m, delta ~ 1e-10 m).
HertzContact contact_from_depth(const std::vector<double>& gaps_m, double z_max_m, double depth_m,
                                double summit_radius_m, double effective_modulus_pa) {
  HertzContact c;
  c.separation_m = z_max_m - depth_m;
  const std::size_t n = gaps_m.size();
  c.interference_m.assign(n, 0.0);
  c.load_n.assign(n, 0.0);
  c.patch_radius_m.assign(n, 0.0);
  CompensatedSum load, area;
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = depth_m - gaps_m[i];
    if (delta <= 0.0) continue;
    c.interference_m[i] = delta;
    c.load_n[i] = hertz_load(delta, summit_radius_m, effective_modulus_pa);
    c.patch_radius_m[i] = std::sqrt(summit_radius_m * delta);
    load.add(c.load_n[i]);
    area.add(PI * summit_radius_m * delta);  // pi a^2 with a^2 = R_s delta exactly
    ++c.contact_count;
  }
  c.total_load_n = load.value();
  c.real_area_m2 = area.value();
  return c;
}

//! Total load at depth u without building the state (the solver's function).
double total_load_at_depth(const std::vector<double>& gaps_m, double depth_m, double summit_radius_m,
                           double effective_modulus_pa) {
  CompensatedSum load;
  for (double g : gaps_m)
    if (depth_m > g) load.add(hertz_load(depth_m - g, summit_radius_m, effective_modulus_pa));
  return load.value();
}

}  // namespace

double hertz_load(double interference_m, double summit_radius_m, double effective_modulus_pa) {
  if (interference_m <= 0.0) return 0.0;
  return (4.0 / 3.0) * effective_modulus_pa * std::sqrt(summit_radius_m) * interference_m * std::sqrt(interference_m);
}

double hertz_interference_for_load(double load_n, double summit_radius_m, double effective_modulus_pa) {
  // In logarithms: 3 W / (4 E* sqrt(R_s)) may itself overflow or underflow where its 2/3
  // power would not.
  const double log_ratio = std::log(3.0 * load_n / 4.0) - std::log(effective_modulus_pa) - 0.5 * std::log(summit_radius_m);
  return std::exp(2.0 / 3.0 * log_ratio);
}

HertzContact hertz_contact_at_separation(const std::vector<double>& heights_m, double summit_radius_m,
                                         double effective_modulus_pa, double separation_m) {
  validate_inputs(heights_m, summit_radius_m, effective_modulus_pa);
  if (!std::isfinite(separation_m))
    throw InputError("hertz contact: separation d = " + format_number(separation_m) + " m must be finite");
  // Direct interference z_i - d: the caller chose d, so its own rounding is the reference.
  std::vector<double> gaps(heights_m.size());
  for (std::size_t i = 0; i < gaps.size(); ++i) gaps[i] = -heights_m[i];
  HertzContact c = contact_from_depth(gaps, 0.0, -separation_m, summit_radius_m, effective_modulus_pa);
  c.separation_m = separation_m;
  return c;
}

HertzContact solve_hertz_contact(const std::vector<double>& heights_m, double summit_radius_m,
                                 double effective_modulus_pa, double nominal_load_n) {
  validate_inputs(heights_m, summit_radius_m, effective_modulus_pa);
  if (!std::isfinite(nominal_load_n) || nominal_load_n <= 0.0)
    throw ModelError("hertz contact: nominal load W = " + format_number(nominal_load_n) +
                     " N cannot be carried by any separation (need a finite W > 0; the flat does not adhere)");
  if (heights_m.empty())
    throw ModelError("hertz contact: nominal load W = " + format_number(nominal_load_n) +
                     " N cannot be carried: the population has no asperities");

  const double z_max = *std::max_element(heights_m.begin(), heights_m.end());
  std::vector<double> gaps(heights_m.size());
  for (std::size_t i = 0; i < gaps.size(); ++i) gaps[i] = z_max - heights_m[i];

  // Bracket in depth u = z_max - d: at u = 0 no summit is compressed (load 0 < W); at the
  // depth where the tallest summit alone carries W, the total is >= W. So the root lies in
  // [0, u1] without any search; the loop only guards against rounding at u1.
  const double w = nominal_load_n;
  auto f = [&](double u) {
    const double r = total_load_at_depth(gaps, u, summit_radius_m, effective_modulus_pa) - w;
    // Reporting an exact zero once the target is met lets TOMS 748 stop at once
    // (it returns on f(c) == 0); the margin of 10 keeps the verified error below 1e-12.
    return std::abs(r) <= 0.1 * HERTZ_LOAD_RELATIVE_TOLERANCE * w ? 0.0 : r;
  };
  // (The power form, not hertz_interference_for_load: it is exact enough, and the numbers
  // stay those of earlier versions; surfaces are checked to keep it in range.)
  double u_hi = std::cbrt(std::pow(3.0 * w / (4.0 * effective_modulus_pa * std::sqrt(summit_radius_m)), 2.0));
  double f_hi = f(u_hi);
  for (int k = 0; f_hi < 0.0 && k < 60; ++k) f_hi = f(u_hi *= 2.0);
  // A sum of loads beyond a double (inf, or NaN from inf - inf) would make TOMS 748 fail
  // with a raw "do not bracket the root".
  if (!(f_hi >= 0.0) || !std::isfinite(f_hi) || !(u_hi > 0.0) || !std::isfinite(u_hi))
    throw ModelError("hertz contact: could not bracket the load W = " + format_number(w) + " N (E* = " +
                     format_number(effective_modulus_pa) + " Pa, R_s = " + format_number(summit_radius_m) +
                     " m): the summits' loads are beyond what a double can sum");

  double u = u_hi;
  std::uintmax_t iterations = 200;
  if (f_hi != 0.0) {
    // 2^(1-bits) relative width on u gives ~2e-15 relative load error, far inside 1e-12;
    // the zero-on-target shortcut above normally ends the search earlier.
    boost::math::tools::eps_tolerance<double> tol(std::numeric_limits<double>::digits - 2);
    const auto [a, b] = boost::math::tools::toms748_solve(f, 0.0, u_hi, -w, f_hi, tol, iterations);
    u = std::abs(f(a)) <= std::abs(f(b)) ? a : b;
  } else {
    iterations = 0;
  }

  HertzContact c = contact_from_depth(gaps, z_max, u, summit_radius_m, effective_modulus_pa);
  c.solver_iterations = static_cast<int>(iterations);
  c.load_relative_error = std::abs(c.total_load_n - w) / w;
  if (!(c.load_relative_error <= HERTZ_LOAD_RELATIVE_TOLERANCE))
    throw ModelError("hertz contact: load solve reached relative error " + format_number(c.load_relative_error) +
                     " > 1e-12 for W = " + format_number(w) + " N after " + std::to_string(iterations) + " iterations");
  return c;
}

double screening_interaction_estimate(double contact_density) {
  if (!std::isfinite(contact_density) || contact_density < 0.0)
    throw InputError("screening estimate: contact density A_r/A0 = " + format_number(contact_density) + " must be >= 0");
  return 4.0 / (3.0 * PI) * std::pow(contact_density, 1.5);
}

}  // namespace stengmc
