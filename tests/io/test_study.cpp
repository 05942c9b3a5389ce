// The study reader: the paper's defaults (MODEL.md §1, Tables 1-2) where a study is
// silent, surface files, and the errors the README's table does not already cover.
#include <gtest/gtest.h>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"

namespace stengmc {
namespace {

const std::string MINIMAL = R"(duration_s = 1e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
[surface]
[[surface.asperity]]
stiffness_n_per_m = 25
)";

std::string error_of(const std::string& text) {
  try {
    parse_study(text, "s.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Study, DefaultsAreThePapersValues) {
  const Study s = parse_study(MINIMAL, "studies/x.toml");
  const Asperity& a = s.asperities.at(0);
  EXPECT_EQ(a.mass_kg, 1e-12);
  EXPECT_EQ(a.normal_load_n, 1e-3);
  EXPECT_EQ(a.element.charge_density_c_per_m2, 80e-6);
  EXPECT_EQ(a.element.effective_thickness_m, 50e-6);
  EXPECT_EQ(a.element.width_m, 10e-6);
  EXPECT_EQ(a.element.length_m, 10e-6);
  EXPECT_EQ(s.model2.friction.static_coefficient, 0.28);
  EXPECT_EQ(s.model2.friction.kinetic_coefficient, 0.22);
  EXPECT_EQ(s.model2.damping_n_s_per_m, 1e-7);
  EXPECT_EQ(s.model2.stribeck_decay_s_per_m, 1e-7);
  EXPECT_EQ(s.model2.atan_sharpness_s_per_m, 1e3);
  EXPECT_EQ(s.circuit.load_resistance_ohm, 1e6);
  EXPECT_EQ(s.domain_policy, DomainPolicy::error);
  EXPECT_EQ(s.output.file, "results/x.h5");
  EXPECT_EQ(s.grid().count, 101u);
  EXPECT_EQ(s.text, MINIMAL);
}

TEST(Study, Model1DefaultsAndDriveFrequencyInHertz) {
  std::string text = MINIMAL;
  text.replace(text.find("\"model2\""), 8, "\"model1\"\ndrive_frequency_hz = 2e4");
  const Study s = parse_study(text, "s.toml");
  EXPECT_EQ(s.model, ModelKind::model1);
  EXPECT_EQ(s.model1.drive_amplitude_m, 9e-6);
  EXPECT_DOUBLE_EQ(s.model1.drive_angular_frequency_rad_per_s, 2 * PI * 2e4);
  EXPECT_EQ(s.model1.solver, Model1Solver::exact);
}

TEST(Study, DefaultsApplyToEveryAsperityAndCountReplicates) {
  const Study s = parse_study(R"(duration_s = 1e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
[surface.defaults]
length_m = 50e-6
[[surface.asperity]]
stiffness_n_per_m = 75
count = 3
[[surface.asperity]]
stiffness_n_per_m = 25
length_m = 20e-6
)", "s.toml");
  ASSERT_EQ(s.asperities.size(), 4u);
  EXPECT_EQ(s.asperities[2].stiffness_n_per_m, 75);
  EXPECT_EQ(s.asperities[2].element.length_m, 50e-6);
  EXPECT_EQ(s.asperities[3].element.length_m, 20e-6);
}

TEST(Study, SurfaceFileIsResolvedFromTheStudyFolder) {
  const Study s = parse_study(R"(duration_s = 1e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
[surface]
file = "../surfaces/paper_four_stiffnesses.toml"
)", std::string(STENGMC_SOURCE_DIR) + "/studies/virtual.toml");
  ASSERT_EQ(s.asperities.size(), 4u);
  EXPECT_EQ(s.asperities[3].stiffness_n_per_m, 155);
}

TEST(Study, RejectsMissingSurfaceFileWithItsPath) {
  std::string text = MINIMAL;
  const std::string inline_list = "[[surface.asperity]]\nstiffness_n_per_m = 25";
  text.replace(text.find(inline_list), inline_list.size(), "file = \"nowhere.toml\"");
  EXPECT_NE(error_of(text).find("s.toml:6: [surface] file = \"nowhere.toml\": no such file"), std::string::npos) << error_of(text);
}

TEST(Study, RejectsStaticBelowKineticFriction) {
  std::string text = MINIMAL;
  text.replace(text.find("kind = \"model2\""), 15, "kind = \"model2\"\nstatic_friction = 0.2\nkinetic_friction = 0.3");
  EXPECT_NE(error_of(text).find("static_friction = 0.2 must be >= kinetic_friction = 0.3"), std::string::npos) << error_of(text);
}

TEST(Study, RejectsUnknownModelAndSyntaxErrorsWithLocation) {
  std::string text = MINIMAL;
  text.replace(text.find("\"model2\""), 8, "\"model3\"");
  EXPECT_NE(error_of(text).find("s.toml:4: [model] kind = \"model3\" is not one of \"model1\", \"model2\""), std::string::npos)
      << error_of(text);
  EXPECT_NE(error_of("duration_s = = 1\n").find("s.toml:1:"), std::string::npos);
}

TEST(Study, RejectsModel1KeysInAModel2Study) {
  std::string text = MINIMAL;
  text.replace(text.find("kind = \"model2\""), 15, "kind = \"model2\"\ndrive_amplitude_m = 9e-6");
  EXPECT_NE(error_of(text).find("unknown key 'model.drive_amplitude_m'"), std::string::npos) << error_of(text);
}

TEST(Study, RejectsImposedInputOutsideModel1) {
  const std::string text = MINIMAL + "[circuit]\ninput = \"imposed\"\n";
  EXPECT_NE(error_of(text).find("needs [model] kind = \"model1\""), std::string::npos) << error_of(text);
}

TEST(Study, RejectsInitialDisplacementAtOrBeyondL) {
  std::string text = MINIMAL + "initial_displacement_m = 10e-6\n";
  EXPECT_NE(error_of(text).find("initial_displacement_m must be < length_m"), std::string::npos) << error_of(text);
}

TEST(Study, RejectsRunsTooLargeForMemory) {
  std::string text = MINIMAL;
  text.replace(text.find("duration_s = 1e-6"), 17, "duration_s = 1.0");  // 1e8 samples
  // Read fine; the run refuses before it allocates anything (pipeline/work_estimate).
  try {
    (void)run_study(parse_study(text, "big.toml"), RunOptions{.show_progress = false});
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x the limit of 8 GB"), std::string::npos) << e.what();
  }
  const std::string many = MINIMAL + "count = 100000000000\n";
  EXPECT_NE(error_of(many).find("count = 100000000000 brings the list above"), std::string::npos) << error_of(many);
}

TEST(Study, RejectsDurationThatIsNotAWholeNumberOfSamples) {
  std::string text = MINIMAL;
  text.replace(text.find("duration_s = 1e-6"), 17, "duration_s = 1.006e-6");
  EXPECT_NE(error_of(text).find("is not a whole number of sample intervals"), std::string::npos) << error_of(text);
}

TEST(Study, RejectsUnknownOutputTrace) {
  const std::string text = MINIMAL + "[output]\ntraces = [\"x\", \"velocity\"]\n";
  EXPECT_NE(error_of(text).find("[output] traces [1] = \"velocity\" is not one of"), std::string::npos) << error_of(text);
}

// The friction laws are a registry (tribology/friction_law.hpp): the reader takes a law by
// its registered name and lists every registered name when the study gives another.
TEST(Study, FrictionFormNamesARegisteredLaw) {
  EXPECT_EQ(parse_study(MINIMAL, "s.toml").model2.friction_law->name, "consistent");
  std::string literal = MINIMAL;
  literal.replace(literal.find("kind = \"model2\""), 15, "kind = \"model2\"\nfriction_form = \"literal\"");
  EXPECT_EQ(parse_study(literal, "s.toml").model2.friction_law->name, "literal");
  std::string unknown = MINIMAL;
  unknown.replace(unknown.find("kind = \"model2\""), 15, "kind = \"model2\"\nfriction_form = \"coulomb\"");
  const std::string error = error_of(unknown);
  EXPECT_NE(error.find("[model] friction_form"), std::string::npos) << error;
  EXPECT_NE(error.find("\"coulomb\""), std::string::npos) << error;
  EXPECT_NE(error.find("consistent"), std::string::npos) << error;
  EXPECT_NE(error.find("literal"), std::string::npos) << error;
}

TEST(Study, RejectsMissingModelKind) {
  std::string text = MINIMAL;
  text.replace(text.find("kind = \"model2\""), 15, "");
  EXPECT_NE(error_of(text).find("[model] kind is missing"), std::string::npos) << error_of(text);
}

}  // namespace
}  // namespace stengmc
