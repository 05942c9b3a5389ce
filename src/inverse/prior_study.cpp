#include "inverse/prior_study.hpp"

#include <sstream>

#include "circuit/circuit_settings.hpp"
#include "tribology/model2_settings.hpp"

namespace stengmc {

namespace {

//! A uniform [[ensemble.draw]] of `parameter` on [min, max].
void draw(std::ostringstream& s, const std::string& parameter, double min, double max) {
  s << "\n[[ensemble.draw]]\nparameter = \"" << parameter << "\"\nkind = \"uniform\"\nmin = " << min << "\nmax = " << max << "\n";
}

//! A draw of `parameter` within +-tolerance (relative) of `value`, when there is a tolerance.
void tolerance_draw(std::ostringstream& s, const std::string& parameter, double value, double tolerance) {
  if (tolerance > 0.0) draw(s, parameter, value * (1.0 - tolerance), value * (1.0 + tolerance));
}

}  // namespace

std::string prior_study_text(const KnownDevice& device, const InversePrior& prior, std::size_t realisations,
                             std::uint64_t seed, double band_low_hz, double band_high_hz, double reference_rms_v) {
  std::ostringstream s;
  s.precision(17);
  const Model2Params& m = device.model;
  const Asperity& a = device.asperity;
  const double tolerance = prior.parameter_tolerance;
  const bool spread = prior.load_cv[1] > 0.0;
  // Keys of the random surface's [stiffness] law (distribution.hpp).
  const std::string law_first = prior.family == StiffnessFamily::lognormal ? "median" : "shape";
  const std::string law_second = prior.family == StiffnessFamily::lognormal ? "sigma_log" : "scale";
  s << "# Calibration prior of " << device.study_file << " (written by stengmc calibrate).\n"
    << "title = \"calibration prior: " << stiffness_family_name(prior.family) << " stiffnesses, " << prior.count_min
    << "-" << prior.count_max << " sliding asperities\"\n"
    << "seed = " << seed << "\n"
    << "duration_s = " << device.duration_s << "\n"
    << "sample_rate_hz = " << device.sample_rate_hz << "\n\n"
    << "[model]\nkind = \"model2\"\n"
    << toml_lines(model2_settings(m)) << "\n"
    << "[circuit]\n"
    << toml_lines(circuit_settings(device.circuit)) << "\n"
    << "[domain]\npolicy = \"flag\"   # an asperity reaching l makes its record invalid, not the run\n\n"
    << "[surface]\nkind = \"random\"\nnominal_area_m2 = 1e-6   # positions play no part under these loads\n"
    << "[surface.summits]\ncount_rule = \"fixed\"\ncount = " << prior.count_min << "   # drawn per record\n";
  if (spread)
    // Greenwood–Williamson loads need Gaussian heights; their scale plays no part (the mass
    // is fixed): 1 % of the device's height.
    s << "[surface.heights]\nkind = \"normal\"\nmean = " << a.height_m << "\nstd = " << 0.01 * a.height_m << "\n";
  else
    s << "[surface.heights]\nkind = \"fixed\"\nvalues = [" << a.height_m << "]\n";
  s << "[surface.stiffness]\nkind = \"" << stiffness_family_name(prior.family) << "\"\n"
    << law_first << " = " << prior.first[0] << "   # drawn per record\n"
    << law_second << " = " << prior.second[0] << "   # drawn per record\n";
  if (spread)
    s << "[surface.load]\nrule = \"spread\"\nmean_load_n = " << a.normal_load_n << "\nload_cv = " << prior.load_cv[0]
      << "   # drawn per record\n";
  else
    s << "[surface.load]\nrule = \"fixed\"\nnormal_load_n = " << a.normal_load_n << "\n";
  if (prior.onset_s[1] > 0.0)
    s << "[surface.onset]\nkind = \"uniform\"\nmin = " << prior.onset_s[0] << "\nmax = " << prior.onset_s[1] << "\n";
  s << "[surface.element]\ngeometry = \"fixed\"\n"
    << "length_m = " << a.element.length_m << "\nwidth_m = " << a.element.width_m << "\n"
    << "charge_density_c_per_m2 = " << a.element.charge_density_c_per_m2 << "\n"
    << "effective_thickness_m = " << a.element.effective_thickness_m << "\n"
    << "[surface.mass]\nrule = \"fixed\"\nmass_kg = " << a.mass_kg << "\n\n"
    << "[spectrum]   # the naive FFT count, on the band of the prior's lines\n"
    << "window = \"hann\"\nelement_currents = false\nhigh_resolution = false\n"
    << "min_frequency_hz = " << band_low_hz << "\nmax_frequency_hz = " << band_high_hz << "\n"
    << "floor_window_hz = " << 0.5 * (band_high_hz - band_low_hz) << "\n\n"
    << "[noise]\nsnr_db = " << prior.snr_db[0] << "   # drawn per record\n"
    << "reference_rms_v = " << reference_rms_v << "   # the noise of a record where nothing slides\n\n"
    << "[ensemble]\nrealisations = " << realisations << "\ntrace_realisations = []\n\n"
    << "[[ensemble.draw]]\nparameter = \"surface.summits.count\"\nkind = \"integer\"\nmin = " << prior.count_min
    << "\nmax = " << prior.count_max << "\n";
  draw(s, "surface.stiffness." + law_first, prior.first[0], prior.first[1]);
  draw(s, "surface.stiffness." + law_second, prior.second[0], prior.second[1]);
  draw(s, "noise.snr_db", prior.snr_db[0], prior.snr_db[1]);
  if (spread) draw(s, "surface.load.load_cv", prior.load_cv[0], prior.load_cv[1]);
  // The device known within a tolerance: one draw per record, shared by its asperities.
  tolerance_draw(s, "model.static_friction", m.friction.static_coefficient, tolerance);
  tolerance_draw(s, "model.kinetic_friction", m.friction.kinetic_coefficient, tolerance);
  tolerance_draw(s, "model.damping_n_s_per_m", m.damping_n_s_per_m, tolerance);
  tolerance_draw(s, spread ? "surface.load.mean_load_n" : "surface.load.normal_load_n", a.normal_load_n, tolerance);
  tolerance_draw(s, "surface.element.charge_density_c_per_m2", a.element.charge_density_c_per_m2, tolerance);
  tolerance_draw(s, "surface.element.effective_thickness_m", a.element.effective_thickness_m, tolerance);
  if (prior.noise == NoiseColour::coloured) {
    draw(s, "noise.coloured_share", 0.0, 1.0);
    draw(s, "noise.coloured_exponent", COLOURED_EXPONENT_RANGE[0], COLOURED_EXPONENT_RANGE[1]);
  }
  // An offset of up to one asperity's belt-carried voltage either way (any other size is
  // the same to an estimator that fits it).
  if (prior.offset) draw(s, "noise.offset_v", -device.voltage_scale_v(), device.voltage_scale_v());
  return s.str();
}

}  // namespace stengmc
