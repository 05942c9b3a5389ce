#include "circuit/circuit_solver.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

// Radau IIA, s = 3 (Hairer & Wanner, Solving ODEs II, Table 5.6).
const double SQRT6 = std::sqrt(6.0);
const Eigen::Vector3d RADAU_C{(4.0 - SQRT6) / 10.0, (4.0 + SQRT6) / 10.0, 1.0};
const Eigen::Matrix3d RADAU_A = (Eigen::Matrix3d() <<
    (88.0 - 7.0 * SQRT6) / 360.0, (296.0 - 169.0 * SQRT6) / 1800.0, (-2.0 + 3.0 * SQRT6) / 225.0,
    (296.0 + 169.0 * SQRT6) / 1800.0, (88.0 + 7.0 * SQRT6) / 360.0, (-2.0 - 3.0 * SQRT6) / 225.0,
    (16.0 - SQRT6) / 36.0, (16.0 + SQRT6) / 36.0, 1.0 / 9.0).finished();

//! The equation at one instant in the form dV/dt = alpha V + beta, with what the
//! element currents need.
struct Coefficients {
  double alpha = 0.0;  // [1/s]
  double beta = 0.0;   // [V/s]
};

class ParallelElements {
 public:
  ParallelElements(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                   const CircuitParams& params)
      : elements_(elements), motions_(motions), params_(params), states_(elements.size()) {}

  //! Evaluates every motion at t and returns the V equation's coefficients there.
  Coefficients at(double t, Side side) {
    double capacitance = params_.load_capacitance_f;  // sum C_i + C_L [F]
    double source = 0.0;                              // sum sigma_i w_i x_i' [A]
    double conductance = 0.0;                         // sum eps0 w_i x_i' / d0_i [S]
    for (std::size_t i = 0; i < elements_.size(); ++i) {
      const StengElement& e = elements_[i];
      states_[i] = motions_[i]->at(t, side);
      const PhasePoint& p = states_[i];
      capacitance += EPSILON_0 * e.width_m * (e.length_m - p.x_m) / e.effective_thickness_m;
      source += e.charge_density_c_per_m2 * e.width_m * p.v_m_per_s;
      conductance += EPSILON_0 * e.width_m * p.v_m_per_s / e.effective_thickness_m;
    }
    return {(conductance - 1.0 / params_.load_resistance_ohm) / capacitance, source / capacitance};
  }

  //! Element currents i_i = sigma w x' + (eps0 w x'/d0) V - C_i dV/dt at the state last evaluated.
  void currents(double voltage, double dv_dt, std::vector<std::vector<double>>& out, std::size_t sample) const {
    for (std::size_t i = 0; i < elements_.size(); ++i) {
      const StengElement& e = elements_[i];
      const PhasePoint& p = states_[i];
      const double c_i = EPSILON_0 * e.width_m * (e.length_m - p.x_m) / e.effective_thickness_m;
      out[i][sample] = e.charge_density_c_per_m2 * e.width_m * p.v_m_per_s +
                       EPSILON_0 * e.width_m * p.v_m_per_s / e.effective_thickness_m * voltage - c_i * dv_dt;
    }
  }

 private:
  std::span<const StengElement> elements_;
  std::span<const Motion* const> motions_;
  const CircuitParams& params_;
  std::vector<PhasePoint> states_;
};

//! One Radau IIA step of dV/dt = alpha(t) V + beta(t) from (t, V) over h; returns the
//! new V and adds the step's charge integral of V/R to `charge`.
double radau_step(ParallelElements& circuit, double t, double h, double voltage, double load_resistance,
                  double& charge) {
  Eigen::Matrix3d system;
  Eigen::Vector3d rhs;
  Eigen::Vector3d alpha;
  Eigen::Vector3d beta;
  for (int j = 0; j < 3; ++j) {
    // The last node is the step's right end: take the left limit there, so a velocity
    // step at a breakpoint belongs to the next step.
    const Coefficients c = circuit.at(t + RADAU_C[j] * h, j == 2 ? Side::left : Side::right);
    alpha[j] = c.alpha;
    beta[j] = c.beta;
  }
  // Stages: V_i = V_n + h sum_j a_ij (alpha_j V_j + beta_j)  =>  (I - h A diag(alpha)) V = V_n + h A beta
  system = Eigen::Matrix3d::Identity() - h * RADAU_A * alpha.asDiagonal();
  rhs = Eigen::Vector3d::Constant(voltage) + h * RADAU_A * beta;
  const Eigen::Vector3d stages = system.partialPivLu().solve(rhs);
  charge += h * RADAU_A.row(2).dot(stages) / load_resistance;  // b = last row of A (stiffly accurate)
  return stages[2];
}

void check(std::span<const StengElement> elements, std::span<const Motion* const> motions,
           std::span<const double> times, const CircuitParams& params) {
  if (elements.size() != motions.size()) throw Error("circuit: one motion per element is needed");
  if (!(params.load_resistance_ohm > 0.0) || !std::isfinite(params.load_resistance_ohm))
    throw InputError("circuit: load resistance must be a positive finite number of ohms");
  if (!(params.load_capacitance_f >= 0.0) || !std::isfinite(params.load_capacitance_f))
    throw InputError("circuit: load capacitance must be >= 0 F");
  if (params.substeps == 0) throw InputError("circuit: substeps must be >= 1");
  for (std::size_t j = 1; j < times.size(); ++j)
    if (!(times[j] > times[j - 1])) throw InputError("circuit: times must be strictly increasing");
}

}  // namespace

CircuitResult solve_circuit(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                            std::span<const double> times, const CircuitParams& params) {
  check(elements, motions, times, params);
  const std::size_t count = times.size();
  CircuitResult result;
  result.voltage_v.assign(count, 0.0);
  result.charge_c.assign(count, 0.0);
  result.current_a.assign(elements.size(), std::vector<double>(count, 0.0));
  if (count == 0) return result;

  // Every breakpoint of every motion, merged, so no step straddles a kink of any x_i.
  std::vector<double> breakpoints;
  for (const Motion* m : motions) breakpoints.insert(breakpoints.end(), m->breakpoints().begin(), m->breakpoints().end());
  std::sort(breakpoints.begin(), breakpoints.end());

  ParallelElements circuit(elements, motions, params);
  const double r = params.load_resistance_ohm;
  double voltage = 0.0;
  double charge = 0.0;
  {
    const Coefficients c = circuit.at(times[0], Side::right);
    circuit.currents(voltage, c.alpha * voltage + c.beta, result.current_a, 0);
  }
  auto next_breakpoint = std::upper_bound(breakpoints.begin(), breakpoints.end(), times[0]);
  for (std::size_t j = 1; j < count; ++j) {
    double t = times[j - 1];
    const double t_end = times[j];
    while (t < t_end) {
      // Piece: up to the next breakpoint inside the interval, else the interval's end.
      while (next_breakpoint != breakpoints.end() && *next_breakpoint <= t) ++next_breakpoint;
      const double piece_end =
          (next_breakpoint != breakpoints.end() && *next_breakpoint < t_end) ? *next_breakpoint : t_end;
      const double h = (piece_end - t) / static_cast<double>(params.substeps);
      for (std::size_t s = 0; s < params.substeps; ++s) {
        const double t_step = t + static_cast<double>(s) * h;
        const double step = (s + 1 == params.substeps) ? piece_end - t_step : h;
        voltage = radau_step(circuit, t_step, step, voltage, r, charge);
      }
      t = piece_end;
    }
    // dV/dt from the equation itself at the output point (left limit: the interval just solved).
    const Coefficients c = circuit.at(t_end, Side::left);
    result.voltage_v[j] = voltage;
    result.charge_c[j] = charge;
    circuit.currents(voltage, c.alpha * voltage + c.beta, result.current_a, j);
  }
  return result;
}

}  // namespace stengmc
