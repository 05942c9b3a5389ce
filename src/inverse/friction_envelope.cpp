#include "inverse/friction_envelope.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "tribology/model2_integrator.hpp"

namespace stengmc {

namespace {
constexpr std::size_t FRICTION_TABLE_SIZE = 4096;
}  // namespace

FrictionEnvelope::FrictionEnvelope(const KnownDevice& device, double span_s, double step_s)
    : device_(device), step_s_(step_s) {
  if (!(step_s > 0.0) || !(span_s > 0.0)) throw Error("FrictionEnvelope: span and step must be > 0");
  // G only depends on A: tabulate it once; the table's resolution (v_b / 4096) matters only
  // in the first cycles after breakaway, which the atoms take from the forward model.
  friction_table_.resize(FRICTION_TABLE_SIZE);
  for (std::size_t j = 0; j < FRICTION_TABLE_SIZE; ++j)
    friction_table_[j] = averaged_friction(device.model.belt_velocity_m_per_s * static_cast<double>(j) /
                                           static_cast<double>(FRICTION_TABLE_SIZE - 1));

  const double m = device.asperity.mass_kg;
  const double rate = device.damping_rate_per_s();
  using State = std::array<double, 1>;
  auto rhs = [&](const State& a, State& da, double /*s*/) { da[0] = -rate * a[0] + tabulated_friction(a[0]) / m; };
  const auto count = static_cast<std::size_t>(std::ceil(span_s / step_s)) + 1;
  values_.resize(count);
  slopes_.resize(count);
  // Dormand–Prince 5(4) with dense output (Boost.Odeint), error-controlled far below the
  // atoms' own accuracy; sampled on the uniform table.
  State a{device.model.belt_velocity_m_per_s};
  auto stepper = boost::numeric::odeint::make_dense_output(1e-12, 1e-12, boost::numeric::odeint::runge_kutta_dopri5<State>());
  std::vector<double> times(count);
  for (std::size_t j = 0; j < count; ++j) times[j] = step_s * static_cast<double>(j);
  std::size_t j = 0;
  boost::numeric::odeint::integrate_times(stepper, rhs, a, times.begin(), times.end(), step_s * 0.5,
                                          [&](const State& state, double) { values_[j++] = state[0]; });
  for (std::size_t i = 0; i < count; ++i) {
    State da{};
    rhs(State{values_[i]}, da, 0.0);
    slopes_[i] = da[0];
  }
}

double FrictionEnvelope::averaged_friction(double amplitude_m_per_s) const {
  const StribeckFriction friction(device_.model, device_.asperity.normal_load_n);
  const double v_b = device_.model.belt_velocity_m_per_s;
  // The integrand is even in theta: (1 / pi) integral over [0, pi].
  auto integrand = [&](double theta) {
    const double c = std::cos(theta);
    return friction.force(v_b - amplitude_m_per_s * c) * c;
  };
  return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(integrand, 0.0, PI, 15, 1e-12) / PI;
}

double FrictionEnvelope::tabulated_friction(double a) const {
  const double x = std::clamp(a / device_.model.belt_velocity_m_per_s, 0.0, 1.0) * static_cast<double>(FRICTION_TABLE_SIZE - 1);
  const auto i = std::min(static_cast<std::size_t>(x), FRICTION_TABLE_SIZE - 2);
  const double f = x - static_cast<double>(i);
  return friction_table_[i] + f * (friction_table_[i + 1] - friction_table_[i]);
}

double FrictionEnvelope::at(double s) const {
  const double x = std::clamp(s / step_s_, 0.0, static_cast<double>(values_.size() - 1));
  const auto i = std::min(static_cast<std::size_t>(x), values_.size() - 2);
  const double f = x - static_cast<double>(i);
  return values_[i] + f * (values_[i + 1] - values_[i]);
}

double FrictionEnvelope::slope(double s) const {
  const double x = std::clamp(s / step_s_, 0.0, static_cast<double>(values_.size() - 1));
  const auto i = std::min(static_cast<std::size_t>(x), values_.size() - 2);
  const double f = x - static_cast<double>(i);
  return slopes_[i] + f * (slopes_[i + 1] - slopes_[i]);
}

}  // namespace stengmc
