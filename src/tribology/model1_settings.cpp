#include "tribology/model1_settings.hpp"

#include "core/constants.hpp"
#include "tribology/friction_settings.hpp"

namespace stengmc {

Model1Params read_model1_params(TomlTable& model) {
  Model1Params p;
  p.friction = read_friction_coefficients(model);
  p.drive_amplitude_m = model.non_negative("drive_amplitude_m", p.drive_amplitude_m);
  p.drive_angular_frequency_rad_per_s =
      2.0 * PI * model.positive("drive_frequency_hz", p.drive_angular_frequency_rad_per_s / (2.0 * PI));
  p.solver = model.enumeration("solver", p.solver, MODEL1_SOLVER_NAMES);
  // Read whatever the solver, so switching `solver` back and forth never makes it "unknown".
  p.euler_cromer_substeps = static_cast<std::size_t>(model.integer("euler_cromer_substeps", 1, 1));
  if (p.euler_cromer_substeps > 1'000'000) model.fail("euler_cromer_substeps", "must be <= 1000000");
  return p;
}

std::vector<Setting> model1_settings(const Model1Params& p) {
  std::vector<Setting> settings = friction_settings(p.friction);
  settings.insert(settings.end(), {{"drive_amplitude_m", p.drive_amplitude_m},
                                   {"drive_angular_frequency_rad_per_s", p.drive_angular_frequency_rad_per_s},
                                   {"solver", std::string(MODEL1_SOLVER_NAMES.name(p.solver))},
                                   {"euler_cromer_substeps", static_cast<std::int64_t>(p.euler_cromer_substeps)}});
  return settings;
}

}  // namespace stengmc
