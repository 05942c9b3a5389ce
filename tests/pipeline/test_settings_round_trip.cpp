// Each configurable thing lists its settings beside its reader (core/setting.hpp); run
// files record that list and generated studies (the calibration prior) write it back as
// TOML. Written and read again, the list must give the parameters it came from exactly,
// value for value, in every key: a key the list forgets, misnames or rounds fails here.
#include <gtest/gtest.h>

#include "circuit/circuit_settings.hpp"
#include "core/toml_reader.hpp"
#include "tribology/model1_settings.hpp"
#include "tribology/model2_settings.hpp"

namespace stengmc {
namespace {

TomlTable table_of(TomlDocument& document) { return *document.root().table("t"); }

TEST(Settings, Model2ListWrittenAsTomlReadsBackToTheSameParameters) {
  Model2Params p;  // every value away from its default, with digits that need 17 to survive
  p.friction.static_coefficient = 0.31234567890123456;
  p.friction.kinetic_coefficient = 0.2;
  p.belt_velocity_m_per_s = 3.3333333333333335;
  p.damping_n_s_per_m = 2.5e-7;
  p.stribeck_decay_s_per_m = 0.1;
  p.atan_sharpness_s_per_m = 7e3;
  p.friction_law = find_friction_law("literal");
  p.relative_tolerance = 3e-9;
  const auto document = TomlDocument::from_string("[t]\n" + toml_lines(model2_settings(p)), "m.toml");
  TomlTable t = table_of(*document);
  const Model2Params q = read_model2_params(t);
  document->reject_unknown_keys();
  EXPECT_EQ(q.friction.static_coefficient, p.friction.static_coefficient);
  EXPECT_EQ(q.friction.kinetic_coefficient, p.friction.kinetic_coefficient);
  EXPECT_EQ(q.belt_velocity_m_per_s, p.belt_velocity_m_per_s);
  EXPECT_EQ(q.damping_n_s_per_m, p.damping_n_s_per_m);
  EXPECT_EQ(q.stribeck_decay_s_per_m, p.stribeck_decay_s_per_m);
  EXPECT_EQ(q.atan_sharpness_s_per_m, p.atan_sharpness_s_per_m);
  EXPECT_EQ(q.friction_law, p.friction_law);
  EXPECT_EQ(q.relative_tolerance, p.relative_tolerance);
}

TEST(Settings, CircuitListWrittenAsTomlReadsBackToTheSameParameters) {
  CircuitParams c;
  c.load_resistance_ohm = 4.7e5;
  c.load_capacitance_f = 1.0 / 3.0 * 1e-12;
  c.substeps = 7;
  const auto document = TomlDocument::from_string("[t]\n" + toml_lines(circuit_settings(c)), "c.toml");
  TomlTable t = table_of(*document);
  const CircuitParams d = read_circuit_params(t);
  document->reject_unknown_keys();
  EXPECT_EQ(d.load_resistance_ohm, c.load_resistance_ohm);
  EXPECT_EQ(d.load_capacitance_f, c.load_capacitance_f);
  EXPECT_EQ(d.substeps, c.substeps);
}

// Model 1 records the angular frequency the solver uses (its study key is in Hz), so its
// list is not a study table: each recorded value must still be the parameter's own.
TEST(Settings, Model1ListRecordsEachParameter) {
  Model1Params p;
  p.drive_amplitude_m = 4e-6;
  p.solver = Model1Solver::euler_cromer;
  p.euler_cromer_substeps = 9;
  const std::vector<Setting> s = model1_settings(p);
  auto value = [&](std::string_view key) {
    for (const Setting& x : s)
      if (x.key == key) return x.value;
    ADD_FAILURE() << "no setting " << key;
    return Setting{}.value;
  };
  EXPECT_EQ(std::get<double>(value("static_friction")), p.friction.static_coefficient);
  EXPECT_EQ(std::get<double>(value("drive_amplitude_m")), 4e-6);
  EXPECT_EQ(std::get<double>(value("drive_angular_frequency_rad_per_s")), p.drive_angular_frequency_rad_per_s);
  EXPECT_EQ(std::get<std::string>(value("solver")), "euler_cromer");
  EXPECT_EQ(std::get<std::int64_t>(value("euler_cromer_substeps")), 9);
}

}  // namespace
}  // namespace stengmc
