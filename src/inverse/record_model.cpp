#include "inverse/record_model.hpp"

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

RecordModel::RecordModel(const AtomTable& atoms) : atoms_(&atoms) {
  const StengElement& e = atoms.device().asperity.element;
  gamma_per_v_ = EPSILON_0 / (e.charge_density_c_per_m2 * e.effective_thickness_m);
}

void AtomSums::reset(std::size_t samples) {
  for (auto* v : {&value, &squares, &slope, &weighted_slope, &capacitance}) v->assign(samples, 0.0);
}

void RecordModel::add(double k, AtomSums& sums, std::span<double> d_dlnk) const {
  const std::size_t m_count = samples();
  atom_.resize(m_count);
  slope_.resize(m_count);
  atoms_->evaluate(k, atom_, d_dlnk, slope_);
  const KnownDevice& device = atoms_->device();
  // The element's displacement, roughly: carried by the belt (after a constant-force
  // pick-up at F/m) until it reaches its mean displacement F/k, then oscillating about it.
  const double v_b = device.model.belt_velocity_m_per_s;
  const double acceleration = device.sliding_friction_n() / device.asperity.mass_kg;
  const double pick_up_s = v_b / acceleration;
  const double mean_x = atoms_->equilibrium_displacement(k);
  const double mean_c = device.element_capacitance_f(mean_x);
  const RecordGrid& grid = atoms_->grid();
  // Samples before the asperity reaches its mean displacement (a few hundred at most) have
  // their own capacitance; the rest share the mean one.
  const double carried_until_s = mean_x / v_b + pick_up_s;
  std::size_t m = 0;
  for (; m < m_count && grid.at(m) < carried_until_s; ++m) {
    const double t = grid.at(m);
    const double x = t < pick_up_s ? 0.5 * acceleration * t * t : v_b * (t - 0.5 * pick_up_s);
    const double c = device.element_capacitance_f(std::min(x, mean_x));
    sums.weighted_slope[m] += c * slope_[m];
    sums.capacitance[m] += c;
  }
  for (; m < m_count; ++m) {
    sums.weighted_slope[m] += mean_c * slope_[m];
    sums.capacitance[m] += mean_c;
  }
  double* value = sums.value.data();
  double* squares = sums.squares.data();
  double* slope = sums.slope.data();
  const double* atom = atom_.data();
  const double* atom_slope = slope_.data();
  for (std::size_t j = 0; j < m_count; ++j) {
    value[j] += atom[j];
    squares[j] += atom[j] * atom[j];
    slope[j] += atom_slope[j];
  }
}

void RecordModel::voltage(const AtomSums& sums, std::span<double> out) const {
  const double r = atoms_->device().circuit.load_resistance_ohm;
  // With one atom the terms cancel (to rounding): it is exact as it stands.
  for (std::size_t m = 0; m < out.size(); ++m)
    out[m] = sums.value[m] - r * sums.capacitance[m] * sums.slope[m] + r * sums.weighted_slope[m] +
             gamma_per_v_ * (sums.value[m] * sums.value[m] - sums.squares[m]);
}

void RecordModel::evaluate(std::span<const double> k, std::span<double> voltage_out, Eigen::MatrixXd* jacobian) const {
  const std::size_t m_count = samples();
  if (voltage_out.size() != m_count) throw Error("RecordModel::evaluate: one voltage per sample expected");
  if (jacobian) jacobian->resize(static_cast<Eigen::Index>(m_count), static_cast<Eigen::Index>(k.size()));
  AtomSums sums;
  sums.reset(m_count);
  for (std::size_t i = 0; i < k.size(); ++i) {
    std::span<double> column;
    if (jacobian) column = std::span<double>(jacobian->col(static_cast<Eigen::Index>(i)).data(), m_count);
    add(k[i], sums, column);
  }
  voltage(sums, voltage_out);
}

}  // namespace stengmc
