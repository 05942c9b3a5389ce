#include "inverse/friction_ratios.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {

namespace {
constexpr std::size_t TABLE_SIZE = 4096;
}  // namespace

FrictionRatios::FrictionRatios(const KnownDevice& device) : device_(device) {
  const StribeckFriction unit(device.model, 1.0);
  const double v_b = device.model.belt_velocity_m_per_s;
  reference_ = unit.force(v_b);
  if (!(reference_ > 0.0)) throw InputError(device.study_file + ": the friction at the belt velocity is not positive");
  averaged_.resize(TABLE_SIZE);
  for (std::size_t j = 0; j < TABLE_SIZE; ++j)
    averaged_[j] = averaged_by_quadrature(static_cast<double>(j) / static_cast<double>(TABLE_SIZE - 1));

  linear_damping_ = -averaged_by_quadrature(1e-4) / 1e-4;
  // The rising branch, on which the belt carries the asperity: from v_r = 0 up to where F
  // first peaks below v_r = v_b (x' = 0), found on a logarithmic scan refined by golden section.
  double top_v = v_b, top_f = reference_;
  for (double v = 1e-12 * v_b; v < v_b; v *= 1.02) {
    const double f = unit.force(v);
    if (f > top_f) top_f = f, top_v = v;
  }
  double a = top_v / 1.02, b = std::min(top_v * 1.02, v_b);
  for (int i = 0; i < 100; ++i) {
    const double m1 = a + 0.381966 * (b - a), m2 = a + 0.618034 * (b - a);
    if (unit.force(m1) > unit.force(m2)) b = m2;
    else a = m1;
  }
  const double peak_v = 0.5 * (a + b);
  largest_share_ = unit.force(peak_v) / reference_;
  creep_.resize(TABLE_SIZE);
  creep_[0] = 0.0;
  for (std::size_t j = 1; j < TABLE_SIZE; ++j) {
    const double target = largest_share_ * reference_ * static_cast<double>(j) / static_cast<double>(TABLE_SIZE - 1);
    if (j + 1 == TABLE_SIZE) {
      creep_[j] = peak_v;
      continue;
    }
    auto f = [&](double v) { return unit.force(v) - target; };
    boost::uintmax_t iterations = 200;
    const auto [lo, hi] =
        boost::math::tools::toms748_solve(f, 0.0, peak_v, boost::math::tools::eps_tolerance<double>(50), iterations);
    creep_[j] = 0.5 * (lo + hi);
  }
}

double FrictionRatios::averaged_by_quadrature(double amplitude) const {
  const StribeckFriction unit(device_.model, 1.0);
  const double v_b = device_.model.belt_velocity_m_per_s;
  auto integrand = [&](double t) {
    const double c = std::cos(t);
    return unit.force(v_b * (1.0 - amplitude * c)) * c;
  };
  return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(integrand, 0.0, PI, 15, 1e-12) / (PI * reference_);
}

double FrictionRatios::averaged(double amplitude) const {
  const double x = std::clamp(amplitude, 0.0, 1.0) * static_cast<double>(TABLE_SIZE - 1);
  const auto i = std::min(static_cast<std::size_t>(x), TABLE_SIZE - 2);
  const double f = x - static_cast<double>(i);
  return averaged_[i] + f * (averaged_[i + 1] - averaged_[i]);
}

double FrictionRatios::creep_velocity(double share) const {
  const double x = std::clamp(share / largest_share_, 0.0, 1.0) * static_cast<double>(TABLE_SIZE - 1);
  const auto i = std::min(static_cast<std::size_t>(x), TABLE_SIZE - 2);
  const double f = x - static_cast<double>(i);
  return creep_[i] + f * (creep_[i + 1] - creep_[i]);
}

}  // namespace stengmc
