#include "inverse/record_model.hpp"

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

RecordModel::RecordModel(const AtomTable& atoms) : atoms_(&atoms) {
  const StengElement& e = atoms.device().asperity.element;
  gamma_per_v_ = EPSILON_0 / (e.charge_density_c_per_m2 * e.effective_thickness_m);
}

void RecordModel::evaluate(std::span<const double> k, std::span<double> voltage, Eigen::MatrixXd* jacobian) const {
  const std::size_t m_count = samples();
  if (voltage.size() != m_count) throw Error("RecordModel::evaluate: one voltage per sample expected");
  if (jacobian) jacobian->resize(static_cast<Eigen::Index>(m_count), static_cast<Eigen::Index>(k.size()));
  std::fill(voltage.begin(), voltage.end(), 0.0);
  std::vector<double> atom(m_count), derivative(jacobian ? m_count : 0), slope(k.size() > 1 ? m_count : 0);
  std::vector<double> sum_slope(slope.size(), 0.0), weighted_slope(slope.size(), 0.0), squares(m_count, 0.0);
  std::vector<double> capacitance_sum(slope.size(), 0.0);
  const KnownDevice& device = atoms_->device();
  const double r = device.circuit.load_resistance_ohm;
  // The element's displacement, roughly: carried by the belt (after a constant-force
  // pick-up at F/m) until it reaches its mean displacement F/k, then oscillating about it.
  const double v_b = device.model.belt_velocity_m_per_s;
  const double acceleration = device.sliding_friction_n() / device.asperity.mass_kg;
  const double pick_up_s = v_b / acceleration;
  const RecordGrid& grid = atoms_->grid();
  for (std::size_t i = 0; i < k.size(); ++i) {
    atoms_->evaluate(k[i], atom, derivative, slope);
    for (std::size_t m = 0; m < m_count; ++m) {
      voltage[m] += atom[m];
      squares[m] += atom[m] * atom[m];
    }
    const double mean_x = atoms_->equilibrium_displacement(k[i]);
    const double mean_c = device.element_capacitance_f(mean_x);
    for (std::size_t m = 0; m < slope.size(); ++m) {
      const double t = grid.at(m);
      double c_i = mean_c;
      if (t < mean_x / v_b + pick_up_s) {
        const double x = t < pick_up_s ? 0.5 * acceleration * t * t : v_b * (t - 0.5 * pick_up_s);
        c_i = device.element_capacitance_f(std::min(x, mean_x));
      }
      capacitance_sum[m] += c_i;
      sum_slope[m] += slope[m];
      weighted_slope[m] += c_i * slope[m];
    }
    if (jacobian)
      for (std::size_t m = 0; m < m_count; ++m) (*jacobian)(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(i)) = derivative[m];
  }
  if (k.size() < 2) return;  // one atom is exact as it stands
  for (std::size_t m = 0; m < m_count; ++m)
    voltage[m] += -r * capacitance_sum[m] * sum_slope[m] + r * weighted_slope[m] +
                  gamma_per_v_ * (voltage[m] * voltage[m] - squares[m]);
}

}  // namespace stengmc
