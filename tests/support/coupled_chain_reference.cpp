#include "support/coupled_chain_reference.hpp"

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <utility>

namespace stengmc::test {
namespace {

namespace odeint = boost::numeric::odeint;
using Vector = boost::numeric::ublas::vector<double>;
using Matrix = boost::numeric::ublas::matrix<double>;

// Units of the state, so every component is O(1..100) and one absolute tolerance fits all:
// t in us, x in um, x' in m/s (= um/us), V in mV, Q in fC.
constexpr double US = 1e-6;
constexpr double UM = 1e-6;
constexpr double MV = 1e-3;
constexpr double FC = 1e-15;
constexpr double EPS0 = 8.8541878128e-12;  // F/m, CODATA 2018 (MODEL.md §2)
constexpr double PI = 3.14159265358979323846;

struct Chain {
  const std::vector<ChainAsperity>& a;
  const ChainParameters& p;

  // MODEL.md §1, consistent form: F = N [mu_k + (mu_s - mu_k) exp(-c_s |v_r|)] (2/pi) atan(s v_r).
  double friction(double load, double vr) const {
    const double stribeck = p.kinetic_friction + (p.static_friction - p.kinetic_friction) *
                                                     std::exp(-p.stribeck_decay_s_per_m * std::abs(vr));
    return load * stribeck * (2.0 / PI) * std::atan(p.atan_sharpness_s_per_m * vr);
  }
  double friction_slope(double load, double vr) const {
    const double mu_d = p.static_friction - p.kinetic_friction;
    const double decay = std::exp(-p.stribeck_decay_s_per_m * std::abs(vr));
    const double s = p.atan_sharpness_s_per_m;
    const double sign = (2.0 / PI) * std::atan(s * vr);
    const double sign_slope = (2.0 / PI) * s / (1.0 + s * s * vr * vr);
    const double decay_slope = -p.stribeck_decay_s_per_m * (vr < 0.0 ? -1.0 : 1.0) * mu_d * decay;
    return load * (decay_slope * sign + (p.kinetic_friction + mu_d * decay) * sign_slope);
  }
  // MODEL.md §2: (sum C_i + C_L) dV/dt = sum sigma w x' + V sum eps0 w x'/d0 - V/R.
  void sums(const Vector& y, double& source, double& conductance, double& capacitance) const {
    source = 0.0;
    conductance = 0.0;
    capacitance = p.load_capacitance_f;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double g = EPS0 * a[i].width_m / a[i].effective_thickness_m;
      source += a[i].charge_density_c_per_m2 * a[i].width_m * y[2 * i + 1];
      conductance += g * y[2 * i + 1];
      capacitance += g * (a[i].length_m - y[2 * i] * UM);
    }
  }

  void operator()(const Vector& y, Vector& dy, double) const {
    const std::size_t n = a.size();
    const double volts = y[2 * n] * MV;
    for (std::size_t i = 0; i < n; ++i) {
      const double v = y[2 * i + 1];
      const double f = friction(a[i].normal_load_n, p.belt_velocity_m_per_s - v);
      dy[2 * i] = v;
      dy[2 * i + 1] = (f - p.damping_n_s_per_m * v - a[i].stiffness_n_per_m * y[2 * i] * UM) / a[i].mass_kg * US;
    }
    double source, conductance, capacitance;
    sums(y, source, conductance, capacitance);
    const double r = p.load_resistance_ohm;
    dy[2 * n] = (source + volts * conductance - volts / r) / capacitance * US / MV;
    dy[2 * n + 1] = volts / r * US / FC;
  }
};

struct Jacobian {
  Chain chain;

  void operator()(const Vector& y, Matrix& jac, double, Vector& dfdt) const {
    const std::vector<ChainAsperity>& a = chain.a;
    const ChainParameters& p = chain.p;
    const std::size_t n = a.size();
    jac.clear();
    dfdt.clear();  // autonomous
    const double volts = y[2 * n] * MV;
    const double r = p.load_resistance_ohm;
    double source, conductance, capacitance;
    chain.sums(y, source, conductance, capacitance);
    const double numerator = source + volts * conductance - volts / r;
    for (std::size_t i = 0; i < n; ++i) {
      const double v = y[2 * i + 1];
      const double slope = chain.friction_slope(a[i].normal_load_n, p.belt_velocity_m_per_s - v);
      jac(2 * i, 2 * i + 1) = 1.0;
      jac(2 * i + 1, 2 * i) = -a[i].stiffness_n_per_m * UM / a[i].mass_kg * US;
      jac(2 * i + 1, 2 * i + 1) = (-slope - p.damping_n_s_per_m) / a[i].mass_kg * US;
      const double g = EPS0 * a[i].width_m / a[i].effective_thickness_m;
      // C_i = g (l - x) falls as x grows, so dV/dt = N / C rises by N g / C^2 per unit x.
      jac(2 * n, 2 * i) = numerator * g / (capacitance * capacitance) * UM * US / MV;
      jac(2 * n, 2 * i + 1) = (a[i].charge_density_c_per_m2 * a[i].width_m + volts * g) / capacitance * US / MV;
    }
    jac(2 * n, 2 * n) = (conductance - 1.0 / r) / capacitance * US;
    jac(2 * n + 1, 2 * n) = MV / r * US / FC;
  }
};

}  // namespace

ChainSolution coupled_chain_reference(const std::vector<ChainAsperity>& asperities, const ChainParameters& params,
                                      const std::vector<double>& times_s, double tolerance) {
  const std::size_t n = asperities.size();
  Vector y(2 * n + 2);
  for (std::size_t i = 0; i < n; ++i) {
    y[2 * i] = asperities[i].initial_displacement_m / UM;
    y[2 * i + 1] = asperities[i].initial_velocity_m_per_s;
  }
  y[2 * n] = 0.0;
  y[2 * n + 1] = 0.0;
  std::vector<double> times_us(times_s.size());
  for (std::size_t j = 0; j < times_s.size(); ++j) times_us[j] = times_s[j] / US;
  ChainSolution out;
  const Chain chain{asperities, params};
  odeint::integrate_times(odeint::make_dense_output(tolerance, tolerance, odeint::rosenbrock4<double>()),
                          std::make_pair(chain, Jacobian{chain}), y, times_us.begin(), times_us.end(), 1e-6,
                          [&](const Vector& s, double) {
                            out.voltage_v.push_back(s[2 * n] * MV);
                            out.charge_c.push_back(s[2 * n + 1] * FC);
                          });
  return out;
}

}  // namespace stengmc::test
