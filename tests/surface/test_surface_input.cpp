// Reading random surfaces (MODEL.md §4; STYLE.md "Input, errors, output"): every rejected
// surface throws InputError naming the file, the line (found here independently, by
// searching the text), the key and what was expected; and a complete valid surface reads
// with every key consumed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <unistd.h>

#include "core/error.hpp"
#include "core/toml_reader.hpp"
#include "surface/random_surface.hpp"
#include "surface/surface.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

const std::string FILE_NAME = "bad_surface.toml";

//! Histogram files go to one scratch folder, removed when the test program ends.
std::filesystem::path temp_dir() {
  static const testing::ScratchDir scratch("surface-input");
  return scratch.file("");
}

const char* MATERIALS = R"(
[materials]
summit_radius_m = 50e-6
body_1 = { youngs_modulus_pa = 2.8e9, poisson_ratio = 0.4 }
body_2 = { youngs_modulus_pa = 210e9, poisson_ratio = 0.3 }
)";

// A valid surface; each case below breaks one thing in it.
const std::string HEAD = R"(kind = "random"
nominal_area_m2 = 1e-6
[summits]
count_rule = "poisson"
density_per_m2 = 1e8
)";
const std::string HEIGHTS = R"(
[heights]
kind = "gamma"
shape = 2
scale = 0.5e-6
)";
const std::string STIFFNESS = R"(
[stiffness]
kind = "lognormal"
median = 75
sigma_log = 0.3
)";
const std::string FIXED_LOAD = R"(
[load]
rule = "fixed"
normal_load_n = 1e-3
)";

// Reads `text` as the surface file FILE_NAME exactly as a run does (Surface::from_toml,
// then the unknown-key check); the InputError message, or "(no error)".
std::string error_of(const std::string& text) {
  try {
    auto doc = TomlDocument::from_string(text, FILE_NAME);
    TomlTable root = doc->root();
    Surface::from_toml(root, temp_dir());
    doc->reject_unknown_keys();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// 1-based number of the first line of `text` that contains `needle` (0 if none).
int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

// The message must start with "file:line:" (line of `located_at` in the text) and contain
// every expected fragment: the key and what was expected.
void expect_rejected(const std::string& text, const std::string& located_at, std::initializer_list<std::string> fragments) {
  const std::string message = error_of(text);
  std::printf("  %s\n", message.c_str());
  const int line = line_of(text, located_at);
  ASSERT_GT(line, 0) << "test text lacks " << located_at;
  EXPECT_EQ(message.rfind(FILE_NAME + ":" + std::to_string(line) + ": ", 0), 0u) << message;
  for (const std::string& fragment : fragments) EXPECT_NE(message.find(fragment), std::string::npos) << fragment << "\n  in: " << message;
}

void write_file(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

// ---------------------------------------------------------------- distributions

TEST(SurfaceInput, NonPositiveScaleParametersAreRejected) {
  expect_rejected(HEAD + "[heights]\nkind = \"normal\"\nmean = 1e-6\nstd = 0\n" + STIFFNESS + FIXED_LOAD, "std = 0",
                  {"[heights] std", "= 0 must be > 0"});
  expect_rejected(HEAD + "[heights]\nkind = \"lognormal\"\nmedian = 1e-6\nsigma_log = -1\n" + STIFFNESS + FIXED_LOAD,
                  "sigma_log = -1", {"[heights] sigma_log", "= -1 must be > 0"});
  expect_rejected(HEAD + HEIGHTS + "[stiffness]\nkind = \"gamma\"\nshape = 2\nscale = 0\n" + FIXED_LOAD, "scale = 0\n",
                  {"[stiffness] scale", "= 0 must be > 0"});
}

TEST(SurfaceInput, TruncationWithoutProbabilityMassIsRejected) {
  // P(50 < Z < 60) for a standard normal underflows to 0 (< the 1e-12 floor).
  expect_rejected(HEAD + "[heights]\nkind = \"normal\"\nmean = 0\nstd = 1\nmin = 50\nmax = 60\n" + STIFFNESS + FIXED_LOAD,
                  "max = 60", {"[heights] max", "truncation to [50, 60] leaves probability", "widen it"});
}

TEST(SurfaceInput, StiffnessLawThatCanDrawNonPositiveValuesIsRejected) {
  // An untruncated normal reaches -inf; the message must ask for a truncation.
  const std::string text = HEAD + HEIGHTS + "[stiffness]\nkind = \"normal\"\nmean = 75\nstd = 20\n" + FIXED_LOAD;
  expect_rejected(text, "kind = \"normal\"", {"[stiffness] kind", "stiffnesses must be > 0", "min > 0"});
  // With a truncation that still reaches 0, the message points at `min`.
  expect_rejected(HEAD + HEIGHTS + "[stiffness]\nkind = \"normal\"\nmean = 75\nstd = 20\nmin = 0\n" + FIXED_LOAD, "min = 0",
                  {"[stiffness] min", "stiffness 0 N/m", "min > 0"});
  // The same law truncated at min = 10 is accepted.
  EXPECT_EQ(error_of(HEAD + HEIGHTS + "[stiffness]\nkind = \"normal\"\nmean = 75\nstd = 20\nmin = 10\n" + FIXED_LOAD),
            "(no error)");
  // A fixed list containing 0 is rejected too.
  expect_rejected(HEAD + HEIGHTS + "[stiffness]\nkind = \"fixed\"\nvalues = [0, 50]\n" + FIXED_LOAD,
                  "kind = \"fixed\"", {"[stiffness] kind", "stiffness 0 N/m", "must be > 0"});
}

TEST(SurfaceInput, EmpiricalHistogramMissingOrMalformedNamesBothFiles) {
  const auto dir = temp_dir();
  // Missing: the surface file, the key, the resolved histogram path and the reason.
  const std::string missing = HEAD + "[heights]\nkind = \"empirical\"\nfile = \"absent.csv\"\n" + STIFFNESS + FIXED_LOAD;
  expect_rejected(missing, "file = \"absent.csv\"",
                  {"[heights] file", (dir / "absent.csv").string() + ": cannot open the histogram file"});
  // Malformed on its line 3: the histogram path with that line number.
  write_file(dir / "malformed.csv", "lower,upper,weight\n0,1e-6,1\n1e-6,oops,2\n");
  const std::string malformed =
      HEAD + "[heights]\nkind = \"empirical\"\nfile = \"malformed.csv\"\n" + STIFFNESS + FIXED_LOAD;
  expect_rejected(malformed, "file = \"malformed.csv\"",
                  {"[heights] file", (dir / "malformed.csv").string() + ":3: expected three numbers", "1e-6,oops,2"});
}

// ---------------------------------------------------------------- rules needing other tables

TEST(SurfaceInput, HertzLoadNeedsMaterials) {
  expect_rejected(HEAD + HEIGHTS + STIFFNESS + "[load]\nrule = \"hertz\"\nnominal_load_n = 0.1\n",
                  "rule = \"hertz\"", {"[load] rule", "= \"hertz\" needs a [materials] table"});
}

TEST(SurfaceInput, HertzLoadMustBePositive) {
  for (const char* w : {"0", "-2"}) {
    SCOPED_TRACE(w);
    const std::string text =
        HEAD + HEIGHTS + STIFFNESS + "[load]\nrule = \"hertz\"\nnominal_load_n = " + w + "\n" + MATERIALS;
    expect_rejected(text, std::string("nominal_load_n = ") + w,
                    {"[load] nominal_load_n", std::string("= ") + w + ": no separation can carry it", "W > 0"});
  }
}

TEST(SurfaceInput, LoadSpreadNeedsGaussianHeightsAndACvInRange) {
  const std::string normal = "[heights]\nkind = \"normal\"\nmean = 110e-6\nstd = 1e-6\n";
  const std::string spread = "[load]\nrule = \"spread\"\nmean_load_n = 1e-3\nload_cv = 0.4\n";
  EXPECT_EQ(error_of(HEAD + normal + STIFFNESS + spread), "(no error)");
  expect_rejected(HEAD + HEIGHTS + STIFFNESS + spread, "rule = \"spread\"",
                  {"[load] rule", "Gaussian heights", "kind = \"normal\""});
  expect_rejected(HEAD + "[heights]\nkind = \"normal\"\nmean = 110e-6\nstd = 1e-6\nmin = 0\n" + STIFFNESS + spread,
                  "rule = \"spread\"", {"without min or max"});
  expect_rejected(HEAD + normal + STIFFNESS + "[correlation]\nrho = 0.5\n" + spread, "rule = \"spread\"",
                  {"[correlation]"});
  expect_rejected(HEAD + normal + STIFFNESS + "[load]\nrule = \"spread\"\nmean_load_n = 1e-3\nload_cv = 1.5\n",
                  "load_cv = 1.5", {"[load] load_cv", "must lie in [0, 1.4]"});
  expect_rejected(HEAD + normal + STIFFNESS + "[load]\nrule = \"spread\"\nload_cv = 0.2\n", "[load]",
                  {"mean_load_n", "is missing"});
  expect_rejected(HEAD + normal + STIFFNESS + "[load]\nrule = \"spread\"\nmean_load_n = 1e-3\nnormal_load_n = 1e-3\n",
                  "normal_load_n = 1e-3", {"[load] normal_load_n", "mean_load_n and load_cv"});
}

TEST(SurfaceInput, MindlinStiffnessNeedsMaterials) {
  expect_rejected(HEAD + HEIGHTS + "[stiffness]\nrule = \"mindlin\"\n" + FIXED_LOAD, "rule = \"mindlin\"",
                  {"[stiffness] rule", "= \"mindlin\" needs a [materials] table"});
}

TEST(SurfaceInput, ApplyingTheInteractionNeedsHertzLoad) {
  expect_rejected(HEAD + HEIGHTS + STIFFNESS + FIXED_LOAD + MATERIALS + "[interaction]\nmode = \"apply\"\n",
                  "mode = \"apply\"", {"[interaction] mode", "= \"apply\" needs [load] rule = \"hertz\""});
}

TEST(SurfaceInput, DensityMassNeedsNonNegativeHeights) {
  // m = rho l w h: a normal height law without min can draw h < 0.
  const std::string text = HEAD + "[heights]\nkind = \"normal\"\nmean = 1e-6\nstd = 1e-6\n" + STIFFNESS + FIXED_LOAD +
                           "[mass]\nrule = \"density\"\ndensity_kg_per_m3 = 1380\n";
  expect_rejected(text, "rule = \"density\"", {"[mass] rule", "= \"density\"", "[heights] can draw", "min = 0"});
  // Truncated at min = 0, the same surface reads.
  EXPECT_EQ(error_of(HEAD + "[heights]\nkind = \"normal\"\nmean = 1e-6\nstd = 1e-6\nmin = 0\n" + STIFFNESS +
                     FIXED_LOAD + "[mass]\nrule = \"density\"\ndensity_kg_per_m3 = 1380\n"),
            "(no error)");
}

// ---------------------------------------------------------------- summits

TEST(SurfaceInput, GivenPositionsNeedMatchingLengths) {
  const std::string text = "kind = \"random\"\nnominal_area_m2 = 1e-6\n[summits]\npositions = \"given\"\n"
                           "x_m = [1e-4, 2e-4, 3e-4]\ny_m = [1e-4, 2e-4]\n" +
                           HEIGHTS + STIFFNESS + FIXED_LOAD;
  expect_rejected(text, "y_m =", {"[summits] y_m", "has 2 entries but x_m has 3"});
}

TEST(SurfaceInput, MisspelledKeysAreCaught) {
  // A misspelt required key: the reader names the key it needed, at the table's line.
  const std::string required = "kind = \"random\"\nnominal_area_m2 = 1e-6\n[summits]\ncount_rule = \"poisson\"\n"
                               "densty_per_m2 = 1e8\n" +
                               HEIGHTS + STIFFNESS + FIXED_LOAD;
  expect_rejected(required, "[summits]", {"[summits] density_per_m2", "is missing", "[1/m^2]"});
  // Where nothing else is missing, reject_unknown_keys reports the typo at its own line.
  const std::string optional = "kind = \"random\"\nnominal_area_m2 = 1e-6\n[summits]\ncount_rule = \"fixed\"\n"
                               "count = 10\ndensty_per_m2 = 1e8\n" +
                               HEIGHTS + STIFFNESS + FIXED_LOAD;
  expect_rejected(optional, "densty_per_m2", {"unknown key 'summits.densty_per_m2'", "allowed here:", "count"});
  const std::string element = HEAD + HEIGHTS + STIFFNESS + FIXED_LOAD + "[element]\nlenght_m = 2e-5\n";
  expect_rejected(element, "lenght_m", {"unknown key 'element.lenght_m'", "allowed here:", "length_m"});
}

// ---------------------------------------------------------------- valid surfaces

TEST(SurfaceInput, CompleteValidSurfacesReadAndConsumeEveryKey) {
  // Every key of the format, in two surfaces (the rules exclude each other's keys);
  // reject_unknown_keys must pass, and the values must arrive where they belong.
  const std::string random_positions = std::string(R"(kind = "random"
title = "every key, part 1"
nominal_area_m2 = 2e-6
[summits]
positions = "uniform"
count_rule = "poisson"
density_per_m2 = 5e7
[heights]
kind = "normal"
mean = 2e-6
std = 0.5e-6
min = 0
max = 5e-6
[stiffness]
rule = "sampled"
kind = "weibull"
shape = 2
scale = 80
min = 10
[correlation]
rho = 0.4
[load]
rule = "hertz"
nominal_load_n = 0.05
[interaction]
mode = "apply"
localisation_radius_m = 1e-4
localisation_spacings = 4
kernel = "hertz_pressure"
[element]
charge_density_c_per_m2 = 90e-6
effective_thickness_m = 40e-6
geometry = "patch"
[mass]
rule = "density"
density_kg_per_m3 = 1380
[drive]
phase = "uniform"
)") + MATERIALS;
  auto doc = TomlDocument::from_string(random_positions, FILE_NAME);
  TomlTable root = doc->root();
  const Surface surface = Surface::from_toml(root, temp_dir());
  EXPECT_NO_THROW(doc->reject_unknown_keys());
  ASSERT_NE(surface.random_surface(), nullptr);
  const RandomSurface& s = *surface.random_surface();
  EXPECT_EQ(s.title, "every key, part 1");
  EXPECT_EQ(s.nominal_area_m2, 2e-6);
  EXPECT_EQ(s.count_rule, CountRule::poisson);
  EXPECT_EQ(s.position_rule, PositionRule::uniform);
  EXPECT_EQ(s.summit_density_per_m2, 5e7);
  EXPECT_EQ(s.heights.kind_name(), "normal");
  EXPECT_EQ(s.heights.lower(), 0.0);
  EXPECT_EQ(s.heights.upper(), 5e-6);
  ASSERT_TRUE(s.stiffness.has_value());
  EXPECT_EQ(s.stiffness->kind_name(), "weibull");
  EXPECT_EQ(s.stiffness->lower(), 10.0);
  ASSERT_TRUE(s.correlation.has_value());
  EXPECT_EQ(s.correlation->rho(), 0.4);
  ASSERT_TRUE(s.materials.has_value());
  EXPECT_EQ(s.materials->summit_radius_m, 50e-6);
  EXPECT_EQ(s.materials->body_1.youngs_modulus_pa, 2.8e9);
  EXPECT_EQ(s.materials->body_2.poisson_ratio, 0.3);
  EXPECT_EQ(s.load_rule, LoadRule::hertz);
  EXPECT_EQ(s.nominal_load_n, 0.05);
  EXPECT_EQ(s.interaction_mode, InteractionMode::apply);
  EXPECT_EQ(s.interaction.localisation_radius_m, 1e-4);
  EXPECT_EQ(s.interaction.localisation_spacings, 4.0);
  EXPECT_EQ(s.interaction.kernel, InteractionKernel::hertz_pressure);
  EXPECT_EQ(s.element.charge_density_c_per_m2, 90e-6);
  EXPECT_EQ(s.element.effective_thickness_m, 40e-6);
  EXPECT_EQ(s.geometry_rule, GeometryRule::patch);
  EXPECT_EQ(s.mass_rule, MassRule::density);
  EXPECT_EQ(s.density_kg_per_m3, 1380.0);
  EXPECT_EQ(s.phase_rule, PhaseRule::uniform);

  const std::string given_positions = std::string(R"(kind = "random"
title = "every key, part 2"
nominal_area_m2 = 1e-6
[summits]
positions = "given"
count_rule = "fixed"
count = 3
x_m = [1e-4, 5e-4, 9e-4]
y_m = [2e-4, 6e-4, 9.5e-4]
[heights]
kind = "empirical"
file = "heights.csv"
[stiffness]
rule = "mindlin"
[load]
rule = "fixed"
normal_load_n = 2e-3
[interaction]
mode = "report"
[element]
geometry = "fixed"
length_m = 20e-6
width_m = 15e-6
[mass]
rule = "fixed"
mass_kg = 2e-12
[drive]
phase = "fixed"
phase_rad = 0.5
)") + MATERIALS;
  write_file(temp_dir() / "heights.csv", "lower,upper,weight\n1e-6,2e-6,1\n2e-6,3e-6,2\n");
  auto doc2 = TomlDocument::from_string(given_positions, FILE_NAME);
  TomlTable root2 = doc2->root();
  const Surface surface2 = Surface::from_toml(root2, temp_dir());
  EXPECT_NO_THROW(doc2->reject_unknown_keys());
  ASSERT_NE(surface2.random_surface(), nullptr);
  const RandomSurface& t = *surface2.random_surface();
  EXPECT_EQ(t.position_rule, PositionRule::given);
  EXPECT_EQ(t.count_rule, CountRule::fixed);
  EXPECT_EQ(t.summit_count, 3u);
  EXPECT_EQ(t.given_y_m.back(), 9.5e-4);
  EXPECT_EQ(t.heights.kind(), Distribution::Kind::empirical);
  EXPECT_EQ(t.heights.lower(), 1e-6);
  EXPECT_EQ(t.heights.upper(), 3e-6);
  EXPECT_EQ(t.stiffness_rule, StiffnessRule::mindlin);
  EXPECT_FALSE(t.stiffness.has_value());
  EXPECT_EQ(t.normal_load_n, 2e-3);
  EXPECT_EQ(t.interaction_mode, InteractionMode::report);
  EXPECT_EQ(t.element.length_m, 20e-6);
  EXPECT_EQ(t.element.width_m, 15e-6);
  EXPECT_EQ(t.mass_kg, 2e-12);
  EXPECT_EQ(t.phase_rule, PhaseRule::fixed);
  EXPECT_EQ(t.phase_rad, 0.5);
  // A surface that reads is a surface that samples (random_surface_input.cpp's promise).
  EXPECT_NO_THROW(surface.sample(1, 0));
  const Population p = surface2.sample(1, 0);
  EXPECT_EQ(p.asperities.size(), 3u);
  EXPECT_EQ(p.x_m[1], 5e-4);
}

}  // namespace
}  // namespace stengmc
