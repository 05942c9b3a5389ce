#include "inverse/forward_atom.hpp"

#include <algorithm>
#include <cmath>

#include "circuit/circuit_solver.hpp"
#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "tribology/domain_check.hpp"
#include "tribology/model2.hpp"
#include "tribology/time_grid.hpp"

namespace stengmc {

ForwardAtom simulate_forward_atom(const KnownDevice& device, double stiffness_n_per_m, std::span<const double> times_s) {
  if (times_s.empty()) return {};
  Asperity asperity = device.asperity;
  asperity.stiffness_n_per_m = stiffness_n_per_m;
  // The tribology samples on a uniform grid from t = 0; the record's times lie on such a
  // grid (checked by the caller), possibly starting later.
  const double step_s = times_s.size() > 1 ? times_s[1] - times_s[0] : 1.0;
  const auto first = static_cast<std::size_t>(std::llround(times_s.front() / step_s));
  const TimeGrid grid{step_s, first + times_s.size()};
  const Trajectory trajectory = solve_model2(asperity, device.model, grid);
  std::vector<double> grid_times = grid.times();
  if (const auto exit = first_domain_exit(*trajectory.motion, grid_times, trajectory.x_m, asperity.element.length_m))
    throw ModelError("an asperity of stiffness " + format_number(stiffness_n_per_m) + " N/m reaches l = " +
                     format_number(asperity.element.length_m) + " m at t = " + format_number(*exit) +
                     " s: outside the device's valid range (MODEL.md §2)");
  const Motion* motion = trajectory.motion.get();
  const CircuitResult circuit = solve_circuit(std::span<const StengElement>(&asperity.element, 1),
                                              std::span<const Motion* const>(&motion, 1), grid_times, device.circuit);
  ForwardAtom atom;
  atom.voltage_v.assign(circuit.voltage_v.begin() + static_cast<std::ptrdiff_t>(first), circuit.voltage_v.end());
  atom.displacement_m.assign(trajectory.x_m.begin() + static_cast<std::ptrdiff_t>(first), trajectory.x_m.end());
  // dV/dt from the circuit equation itself (MODEL.md §2), exact at the samples where a
  // difference quotient is not (the belt's pick-up is a corner within one sample).
  const StengElement& e = asperity.element;
  const double r = device.circuit.load_resistance_ohm;
  atom.slope_v_per_s.resize(atom.voltage_v.size());
  for (std::size_t m = 0; m < atom.voltage_v.size(); ++m) {
    const double x = trajectory.x_m[first + m], v = trajectory.v_m_per_s[first + m], voltage = atom.voltage_v[m];
    const double capacitance = device.element_capacitance_f(x) + device.circuit.load_capacitance_f;
    atom.slope_v_per_s[m] = (e.charge_density_c_per_m2 * e.width_m * v +
                             voltage * EPSILON_0 * e.width_m * v / e.effective_thickness_m - voltage / r) /
                            capacitance;
  }
  return atom;
}

}  // namespace stengmc

namespace stengmc {

bool stays_below_length(const KnownDevice& device, double stiffness_n_per_m, const TimeGrid& grid) {
  Asperity asperity = device.asperity;
  asperity.stiffness_n_per_m = stiffness_n_per_m;
  const Trajectory trajectory = solve_model2(asperity, device.model, grid);
  return !first_domain_exit(*trajectory.motion, grid.times(), trajectory.x_m, asperity.element.length_m);
}

double smallest_valid_stiffness(const KnownDevice& device, double duration_s, double step_s, double lowest_n_per_m,
                                double highest_n_per_m) {
  // Only the tribology decides: a failure of the solvers themselves (a circuit that gives a
  // non-finite voltage, an integrator out of steps) is the device's error, not "too soft",
  // and propagates instead of sending the search to ever stiffer asperities.
  auto valid = [&](double k) {
    // The largest excursion comes in the first cycles after breakaway: 2 periods past it.
    const double breakaway = device.sliding_friction_n() / (k * device.model.belt_velocity_m_per_s);
    const double omega = device.angular_frequency(k);
    const double span = std::min(duration_s, breakaway * 1.5 + (omega > 0.0 ? 4.0 * PI / omega : duration_s));
    return stays_below_length(device, k, TimeGrid{step_s, static_cast<std::size_t>(std::ceil(span / step_s)) + 1});
  };
  if (valid(lowest_n_per_m)) return 0.0;
  // mu_s N / k < l at the upper end: breakaway before l (the oscillation adds ~v_b / omega).
  double high = std::max(lowest_n_per_m * 2.0, 4.0 * device.model.friction.static_coefficient *
                                                   device.asperity.normal_load_n / device.asperity.element.length_m);
  while (!valid(high)) {
    if (high >= highest_n_per_m) return INFINITY;
    high *= 2.0;
  }
  double low = lowest_n_per_m;
  while (high / low > 1.001) {
    const double mid = std::sqrt(low * high);
    (valid(mid) ? high : low) = mid;
  }
  return high * 1.02;
}

}  // namespace stengmc
