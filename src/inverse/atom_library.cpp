#include "inverse/atom_library.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {
// Below this Pi the asperity never nears the belt's velocity and its shape scales with Pi
// (atom_shapes.hpp): no node is needed there.
constexpr double SMALLEST_PI_NODE = 0.2;
// Loads below this share of the device's carry atoms too weak to matter; their envelopes
// are those of this load (the friction's share of their damping is negligible anyway).
constexpr double SMALLEST_ENVELOPE_LOAD = 1e-3;
// The shapes and envelopes reach this far beyond what the fits' bounds need.
constexpr double MARGIN = 1.05;
}  // namespace

AtomCoverage atom_coverage(double k_low, double k_high, const FitLayout& layout) {
  AtomCoverage c;
  c.min_stiffness_n_per_m = k_low;
  c.max_stiffness_n_per_m = k_high;
  if (layout.load_per_atom || layout.load_shared) {
    c.min_load_ratio = std::exp(layout.min_log_load);
    c.max_load_ratio = std::exp(layout.max_log_load);
  }
  c.min_damping_rate = layout.min_damping_rate;
  c.max_damping_rate = layout.max_damping_rate;
  return c;
}

AtomShapeRange atom_shape_range(const KnownDevice& device, double f_ref, const AtomCoverage& coverage) {
  const double m = device.asperity.mass_kg, v_b = device.model.belt_velocity_m_per_s;
  const double load = device.asperity.normal_load_n;
  const double omega_low = std::sqrt(coverage.min_stiffness_n_per_m / m), omega_high = std::sqrt(coverage.max_stiffness_n_per_m / m);
  AtomShapeRange r;
  r.max_pi = coverage.max_load_ratio * load * f_ref / (m * omega_low * v_b) * MARGIN;
  r.min_pi = std::min(std::max(SMALLEST_PI_NODE, coverage.min_load_ratio * load * f_ref / (m * omega_high * v_b) / MARGIN),
                      r.max_pi / 1.5);
  // zeta = d / omega0, each end from the damping's and the stiffness's; a device without
  // damping has zeta = 0, kept just above it.
  r.min_zeta = std::max(1e-12, coverage.min_damping_rate / omega_high / MARGIN);
  r.max_zeta = std::max(r.min_zeta, coverage.max_damping_rate / omega_low * MARGIN);
  return r;
}

AtomShapeWork atom_shape_work(const AtomShapeRange& range, const AtomShapeSettings& settings) {
  const std::size_t pis =
      std::max<std::size_t>(4, static_cast<std::size_t>(std::ceil(std::log(range.max_pi / range.min_pi) / settings.log_pi_step)) + 1);
  const std::size_t zetas = range.max_zeta > range.min_zeta ? std::max<std::size_t>(2, settings.zeta_nodes) : 1;
  return {pis * zetas + 8, range.max_pi + settings.after_breakaway + settings.tail_fit_span + 2.0 * PI};
}

AtomLibrary::AtomLibrary(const KnownDevice& device, const RecordGrid& grid, const AtomCoverage& coverage)
    : device_(device), grid_(grid), coverage_(coverage), ratios_(std::make_unique<FrictionRatios>(device_)) {
  shapes_ = std::make_unique<AtomShapes>(device_, *ratios_, atom_shape_range(device_, ratios_->reference(), coverage_));
  build_envelopes();
}

AtomLibrary::AtomLibrary(const KnownDevice& device, const RecordGrid& grid, const AtomCoverage& coverage, AtomShapeData shapes)
    : device_(device), grid_(grid), coverage_(coverage), ratios_(std::make_unique<FrictionRatios>(device_)) {
  shapes_ = std::make_unique<AtomShapes>(device_, *ratios_, std::move(shapes));
  build_envelopes();
}

void AtomLibrary::build_envelopes() {
  const double m = device_.asperity.mass_kg, v_b = device_.model.belt_velocity_m_per_s;
  const double beta_per_ratio = device_.asperity.normal_load_n * ratios_->reference() / (m * v_b);
  EnvelopeFamilyRange range;
  range.min_beta_per_s = beta_per_ratio * std::max(coverage_.min_load_ratio, SMALLEST_ENVELOPE_LOAD) / MARGIN;
  range.max_beta_per_s = beta_per_ratio * coverage_.max_load_ratio * MARGIN;
  range.min_damping_rate_per_s = coverage_.min_damping_rate;
  range.max_damping_rate_per_s = coverage_.max_damping_rate;
  range.step_s = grid_.step_s;
  range.span_s = grid_.at(grid_.samples - 1) + 10e-6;  // beyond it L goes on linearly
  envelopes_ = std::make_unique<EnvelopeFamily>(*ratios_, range);
  model_ = std::make_unique<AtomModel>(device_, grid_, *shapes_, *envelopes_);
}

}  // namespace stengmc
