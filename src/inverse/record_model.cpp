#include "inverse/record_model.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

void AtomSums::reset(std::size_t samples) {
  for (auto* v : {&value, &slope, &displacement}) v->assign(samples, 0.0);
  onsets.clear();
  atoms = 0;
}

RecordModel::RecordModel(const AtomLibrary& atoms) : atoms_(&atoms) {
  const KnownDevice& device = atoms.device();
  const StengElement& e = device.asperity.element;
  volts_per_unit_ = device.voltage_scale_v();
  gamma_per_v_ = EPSILON_0 / (e.charge_density_c_per_m2 * e.effective_thickness_m);
  capacitance_per_length_ = EPSILON_0 * e.width_m / e.effective_thickness_m;
}

void RecordModel::add(const AtomParameters& a, double d, AtomSums& sums, AtomValues* values, bool derivatives) const {
  thread_local AtomValues scratch;
  AtomValues& v = values ? *values : scratch;
  const AtomModel& model = atoms_->model();
  model.evaluate(a, d, v, derivatives);
  const RecordGrid& grid = atoms_->grid();
  double* value = sums.value.data() + v.first;
  double* slope = sums.slope.data() + v.first;
  const double scale = volts_per_unit_;
  const double v_b = model.device().model.belt_velocity_m_per_s;
  for (std::size_t j = 0; j < v.u.size(); ++j) {
    value[j] += scale * v.u[j];
    slope[j] += scale * v.slope[j];
  }
  // The element's displacement, the atom's velocity integrated (trapezoids; u rises from 0 at
  // the onset): its oscillation about the mean included, for the cost of the mean alone
  // (which left 1.0e-4 relative L2 at n = 6 against the shared circuit where this leaves 0.95e-4).
  const double h = grid.step_s;
  double x = v.u.empty() ? 0.0 : 0.5 * v_b * v.u[0] * (grid.at(v.first) - a.onset_s);
  double* displacement = sums.displacement.data() + v.first;
  for (std::size_t j = 0; j < v.u.size(); ++j) {
    if (j > 0) x += 0.5 * h * v_b * (v.u[j - 1] + v.u[j]);
    displacement[j] += x;
  }
  for (std::size_t m = v.end(); m < grid.samples; ++m) sums.displacement[m] += x;
  if (!v.u.empty()) sums.onsets.push_back({v.first, grid.at(v.first) - a.onset_s, scale * v.slope[0]});
  ++sums.atoms;
}

void RecordModel::unit_voltage(const AtomSums& sums, std::span<double> out) const {
  if (out.size() != samples()) throw Error("RecordModel: one voltage per sample expected");
  const KnownDevice& device = atoms_->device();
  const double r = device.circuit.load_resistance_ohm;
  const double fixed = static_cast<double>(sums.atoms) * capacitance_per_length_ * device.asperity.element.length_m +
                       device.circuit.load_capacitance_f;
  for (std::size_t m = 0; m < out.size(); ++m) {
    const double u = sums.value[m];
    const double capacitance = fixed - capacitance_per_length_ * sums.displacement[m];
    // D = 1 - gamma U: V D = U - tau V' gives V = U/D - tau U'/D^3 to first order in tau, all
    // orders in gamma U (up to ~0.3 at n = 16 while the belt carries every asperity: its
    // square is not negligible). D stays far from 0 for any U an atom sum reaches; the floor
    // only keeps a wild trial step of a fit finite.
    const double d = std::max(1.0 - gamma_per_v_ * u, 0.05);
    out[m] = u / d - r * capacitance * sums.slope[m] / (d * d * d);
  }
  // The lag at each onset: the slope's jump there, tau e^{-(t - t_on)/tau} of it not yet
  // followed (beyond 40 tau, nothing).
  for (const AtomSums::Onset& o : sums.onsets) {
    const std::size_t m = o.sample;
    const double tau = r * (fixed - capacitance_per_length_ * sums.displacement[m]);
    if (!(tau > 0.0) || o.since_s > 40.0 * tau) continue;
    const double d = std::max(1.0 - gamma_per_v_ * sums.value[m], 0.05);
    out[m] += tau * o.slope * std::exp(-o.since_s / tau) / (d * d * d);
  }
}

void RecordModel::voltage(const FitState& state, std::span<double> out) const {
  AtomSums sums;
  sums.reset(samples());
  for (const AtomParameters& a : state.atoms) add(a, state.damping_rate_per_s, sums);
  unit_voltage(sums, out);
  for (double& v : out) v = state.amplitude * v + state.offset_v;
}

}  // namespace stengmc
