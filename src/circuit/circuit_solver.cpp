#include "circuit/circuit_solver.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/constants.hpp"
#include "circuit/circuit_errors.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"

namespace stengmc {

namespace {

// Radau IIA, s = 3 (Hairer & Wanner, Solving ODEs II, Table 5.6). Stiffly accurate:
// the weights b are the last row of A and c_3 = 1.
constexpr int STAGES = 3;
const double SQRT6 = std::sqrt(6.0);
const Eigen::Vector3d RADAU_C{(4.0 - SQRT6) / 10.0, (4.0 + SQRT6) / 10.0, 1.0};
const Eigen::Matrix3d RADAU_A = (Eigen::Matrix3d() <<
    (88.0 - 7.0 * SQRT6) / 360.0, (296.0 - 169.0 * SQRT6) / 1800.0, (-2.0 + 3.0 * SQRT6) / 225.0,
    (296.0 + 169.0 * SQRT6) / 1800.0, (88.0 + 7.0 * SQRT6) / 360.0, (-2.0 - 3.0 * SQRT6) / 225.0,
    (16.0 - SQRT6) / 36.0, (16.0 + SQRT6) / 36.0, 1.0 / 9.0).finished();
const Eigen::Vector3d RADAU_B = RADAU_A.row(2).transpose();

// Progress is reported in batches: one call per sample would cost more than a sample on
// small circuits.
constexpr std::size_t PROGRESS_BATCH = 256;

//! The equation at one instant in the form dV/dt = alpha V + beta.
struct Coefficients {
  double alpha = 0.0;  // [1/s]
  double beta = 0.0;   // [V/s]
};

//! One element at one instant, in the form its current takes (MODEL.md §2):
//! i_i = source + conductance V - capacitance dV/dt.
struct ElementTerms {
  double source = 0.0;       // sigma w x' [A]
  double conductance = 0.0;  // eps0 w x' / d0 = -dC_i/dt [S]
  double capacitance = 0.0;  // C_i = eps0 w (l - x) / d0 [F]

  [[nodiscard]] double current(double voltage, double dv_dt) const {
    return source + conductance * voltage - capacitance * dv_dt;
  }
};

//! Per-element constants, so the terms cost three multiplications per motion evaluation.
struct ElementConstants {
  double charge_per_m = 0.0;       // sigma w [C/m]
  double capacitance_per_m = 0.0;  // eps0 w / d0 [F/m]
  double length_m = 0.0;           // l [m]
};

class ParallelElements {
 public:
  ParallelElements(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                   const CircuitParams& params)
      : motions_(motions), load_capacitance_(params.load_capacitance_f), load_conductance_(1.0 / params.load_resistance_ohm),
        constants_(elements.size()), terms_(STAGES * elements.size()) {
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const StengElement& e = elements[i];
      constants_[i] = {e.charge_density_c_per_m2 * e.width_m, EPSILON_0 * e.width_m / e.effective_thickness_m,
                       e.length_m};
    }
  }

  [[nodiscard]] std::size_t size() const { return constants_.size(); }

  //! Evaluates every motion at t, keeps each element's terms in slot `stage` (0..2) for
  //! the currents, and returns the V equation's coefficients there.
  Coefficients at(double t, Side side, int stage) {
    ElementTerms* terms = terms_.data() + static_cast<std::size_t>(stage) * constants_.size();
    double capacitance = load_capacitance_;  // sum C_i + C_L [F]
    double source = 0.0;                     // sum sigma_i w_i x_i' [A]
    double conductance = 0.0;                // sum eps0 w_i x_i' / d0_i [S]
    for (std::size_t i = 0; i < constants_.size(); ++i) {
      const ElementConstants& k = constants_[i];
      const PhasePoint p = motions_[i]->at(t, side);
      terms[i] = {k.charge_per_m * p.v_m_per_s, k.capacitance_per_m * p.v_m_per_s,
                  k.capacitance_per_m * (k.length_m - p.x_m)};
      capacitance += terms[i].capacitance;
      source += terms[i].source;
      conductance += terms[i].conductance;
    }
    // A NaN capacitance passes here and surfaces as a non-finite voltage at the output time.
    if (capacitance <= 0.0) throw_capacitance_not_positive(t, capacitance);
    return {(conductance - load_conductance_) / capacitance, source / capacitance};
  }

  //! The terms of every element stored for `stage` by the last at(t, side, stage).
  [[nodiscard]] const ElementTerms* stage_terms(int stage) const {
    return terms_.data() + static_cast<std::size_t>(stage) * constants_.size();
  }

 private:
  std::span<const Motion* const> motions_;
  double load_capacitance_;  // C_L [F]
  double load_conductance_;  // 1/R [S]
  std::vector<ElementConstants> constants_;
  std::vector<ElementTerms> terms_;  // [stage][element]
};

//! The solution at a step's right end.
struct StepEnd {
  double voltage = 0.0;  // V [V]
  double dv_dt = 0.0;    // dV/dt, left limit [V/s]
};

//! One Radau IIA step of dV/dt = alpha(t) V + beta(t) from (t, V) to t_end. Adds the
//! step's quadrature of V/R to `charge` and of each i_i to `element_charge`; afterwards
//! the circuit's stage-2 slot holds the element terms at t_end (left limit).
StepEnd radau_step(ParallelElements& circuit, double t, double t_end, double voltage, double load_resistance,
                   double& charge, std::vector<double>& element_charge) {
  const double h = t_end - t;
  Eigen::Vector3d alpha;
  Eigen::Vector3d beta;
  for (int j = 0; j < STAGES; ++j) {
    // The last node is the step's right end, passed exactly rather than as t + 1.0 h, which
    // can round off the breakpoint. Take the left limit there, so a velocity step at a
    // breakpoint belongs to the next step.
    const Coefficients c = j == STAGES - 1 ? circuit.at(t_end, Side::left, j)
                                           : circuit.at(t + RADAU_C[j] * h, Side::right, j);
    alpha[j] = c.alpha;
    beta[j] = c.beta;
  }
  // Stages: V_i = V_n + h sum_j a_ij (alpha_j V_j + beta_j)  =>  (I - h A diag(alpha)) V = V_n + h A beta
  const Eigen::Matrix3d system = Eigen::Matrix3d::Identity() - h * RADAU_A * alpha.asDiagonal();
  const Eigen::Vector3d rhs = Eigen::Vector3d::Constant(voltage) + h * RADAU_A * beta;
  const Eigen::Vector3d stages = system.partialPivLu().solve(rhs);
  const Eigen::Vector3d dv_dt = alpha.cwiseProduct(stages) + beta;
  charge += h * RADAU_B.dot(stages) / load_resistance;
  // Element charges with the same quadrature. Radau IIA is collocation (Hairer & Wanner
  // II, Thm IV.5.2): dV/dt at the stages is the collocation polynomial's own derivative,
  // so the sum over elements of these increments equals the charge increment through R
  // plus C_L (V_end - V_n) exactly, and each one integrates -(C_i u)' (u the collocation
  // polynomial) exactly where C_i is linear in t, so it differs from the change of
  // sigma w x - C_i V by an O(h^6) quadrature error on smooth steps, more only on a step
  // that carries a start-up jump of V against a curved C_i (tests/circuit: < 1e-10).
  for (std::size_t i = 0; i < circuit.size(); ++i) {
    double integral = 0.0;
    for (int j = 0; j < STAGES; ++j) integral += RADAU_B[j] * circuit.stage_terms(j)[i].current(stages[j], dv_dt[j]);
    element_charge[i] += h * integral;
  }
  return {stages[2], dv_dt[2]};
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

//! Element terms at one output time into the result, with the non-finite check.
void write_sample(const ParallelElements& circuit, const StepEnd& end, double charge,
                  const std::vector<double>& element_charge, double t, std::size_t sample, CircuitResult& result) {
  if (!std::isfinite(end.voltage)) throw_non_finite("voltage", t);
  if (!std::isfinite(charge)) throw_non_finite("delivered charge", t);
  result.voltage_v[sample] = end.voltage;
  result.charge_c[sample] = charge;
  const ElementTerms* terms = circuit.stage_terms(STAGES - 1);
  for (std::size_t i = 0; i < circuit.size(); ++i) {
    const double current = terms[i].current(end.voltage, end.dv_dt);
    if (!std::isfinite(current) || !std::isfinite(element_charge[i]))
      throw_non_finite("current or charge of element " + std::to_string(i + 1), t);
    result.current_a[i][sample] = current;
    result.element_charge_c[i][sample] = element_charge[i];
  }
}

}  // namespace

CircuitResult solve_circuit(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                            std::span<const double> times, const CircuitParams& params, Progress* progress) {
  check(elements, motions, times, params);
  const std::size_t count = times.size();
  CircuitResult result;
  result.voltage_v.assign(count, 0.0);
  result.charge_c.assign(count, 0.0);
  result.current_a.assign(elements.size(), std::vector<double>(count, 0.0));
  result.element_charge_c.assign(elements.size(), std::vector<double>(count, 0.0));
  if (count == 0) return result;

  // Every breakpoint of every motion, merged, so no step straddles a kink of any x_i.
  std::vector<double> breakpoints;
  for (const Motion* m : motions) breakpoints.insert(breakpoints.end(), m->breakpoints().begin(), m->breakpoints().end());
  std::sort(breakpoints.begin(), breakpoints.end());

  ParallelElements circuit(elements, motions, params);
  const double r = params.load_resistance_ohm;
  const auto substeps = static_cast<double>(params.substeps);
  double charge = 0.0;
  std::vector<double> element_charge(elements.size(), 0.0);
  StepEnd end;  // V(t0) = 0
  {
    // The first sample: right limit, the motion the first interval sees. Stored in the
    // last stage's slot, where write_sample reads the element terms.
    const Coefficients c = circuit.at(times[0], Side::right, STAGES - 1);
    end.dv_dt = c.beta;
    write_sample(circuit, end, charge, element_charge, times[0], 0, result);
  }
  std::size_t unreported = 1;  // samples done but not yet passed to progress
  auto next_breakpoint = std::upper_bound(breakpoints.begin(), breakpoints.end(), times[0]);
  for (std::size_t j = 1; j < count; ++j) {
    double t = times[j - 1];
    const double t_end = times[j];
    while (t < t_end) {
      // Piece: up to the next breakpoint inside the interval, else the interval's end.
      while (next_breakpoint != breakpoints.end() && *next_breakpoint <= t) ++next_breakpoint;
      const double piece_end =
          (next_breakpoint != breakpoints.end() && *next_breakpoint < t_end) ? *next_breakpoint : t_end;
      // Substep ends t + span k / substeps, and the last one is piece_end itself, so the
      // final node is the breakpoint (or output time) bit for bit.
      const double span = piece_end - t;
      double t_step = t;
      for (std::size_t s = 1; s <= params.substeps; ++s) {
        const double t_next = s == params.substeps ? piece_end : t + span * (static_cast<double>(s) / substeps);
        end = radau_step(circuit, t_step, t_next, end.voltage, r, charge, element_charge);
        t_step = t_next;
      }
      t = piece_end;
    }
    // The last stage was evaluated at exactly t_end (left limit: the interval just solved),
    // so the currents there need no further motion evaluation.
    write_sample(circuit, end, charge, element_charge, t_end, j, result);
    if (progress != nullptr && ++unreported == PROGRESS_BATCH) {
      progress->advance(unreported);
      unreported = 0;
    }
  }
  if (progress != nullptr) progress->advance(unreported);
  return result;
}

}  // namespace stengmc
