#include "inverse/prior_study.hpp"

#include <sstream>

#include "circuit/circuit_settings.hpp"
#include "tribology/model2_settings.hpp"

namespace stengmc {

std::string prior_study_text(const KnownDevice& device, const InversePrior& prior, std::size_t realisations,
                             std::uint64_t seed, double band_low_hz, double band_high_hz) {
  std::ostringstream s;
  s.precision(17);
  const Model2Params& m = device.model;
  const Asperity& a = device.asperity;
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
    << "[surface]\nkind = \"random\"\nnominal_area_m2 = 1e-6   # positions play no part under a fixed load\n"
    << "[surface.summits]\ncount_rule = \"fixed\"\ncount = " << prior.count_min << "   # drawn per record\n"
    << "[surface.heights]\nkind = \"fixed\"\nvalues = [" << a.height_m << "]\n"
    << "[surface.stiffness]\nkind = \"" << stiffness_family_name(prior.family) << "\"\n"
    << law_first << " = " << prior.first[0] << "   # drawn per record\n"
    << law_second << " = " << prior.second[0] << "   # drawn per record\n"
    << "[surface.load]\nrule = \"fixed\"\nnormal_load_n = " << a.normal_load_n << "\n"
    << "[surface.element]\ngeometry = \"fixed\"\n"
    << "length_m = " << a.element.length_m << "\nwidth_m = " << a.element.width_m << "\n"
    << "charge_density_c_per_m2 = " << a.element.charge_density_c_per_m2 << "\n"
    << "effective_thickness_m = " << a.element.effective_thickness_m << "\n"
    << "[surface.mass]\nrule = \"fixed\"\nmass_kg = " << a.mass_kg << "\n\n"
    << "[spectrum]   # the naive FFT count, on the band of the prior's lines\n"
    << "window = \"hann\"\nelement_currents = false\nhigh_resolution = false\n"
    << "min_frequency_hz = " << band_low_hz << "\nmax_frequency_hz = " << band_high_hz << "\n"
    << "floor_window_hz = " << 0.5 * (band_high_hz - band_low_hz) << "\n\n"
    << "[noise]\nsnr_db = " << prior.snr_db[0] << "   # drawn per record\n\n"
    << "[ensemble]\nrealisations = " << realisations << "\ntrace_realisations = []\n\n"
    << "[[ensemble.draw]]\nparameter = \"surface.summits.count\"\nkind = \"integer\"\nmin = " << prior.count_min
    << "\nmax = " << prior.count_max << "\n\n"
    << "[[ensemble.draw]]\nparameter = \"surface.stiffness." << law_first << "\"\nkind = \"uniform\"\nmin = "
    << prior.first[0] << "\nmax = " << prior.first[1] << "\n\n"
    << "[[ensemble.draw]]\nparameter = \"surface.stiffness." << law_second << "\"\nkind = \"uniform\"\nmin = "
    << prior.second[0] << "\nmax = " << prior.second[1] << "\n\n"
    << "[[ensemble.draw]]\nparameter = \"noise.snr_db\"\nkind = \"uniform\"\nmin = " << prior.snr_db[0]
    << "\nmax = " << prior.snr_db[1] << "\n";
  return s.str();
}

}  // namespace stengmc
