// `stengmc surface` and random surfaces in studies, run as a user would (README: surface
// files, output files): a realisation drawn alone equals the same realisation inside a
// batch, bit for bit, across commands (`surface --first`, `run --realisation`); every
// file records its inputs; bad surfaces exit 2 (input) or 3 (an unloadable realisation)
// with a message naming file and key, and leave no output behind.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

const std::string GW = std::string(STENGMC_SOURCE_DIR) + "/surfaces/pet_on_steel_gw.toml";

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

//! Realisation j's slice [offset[j], offset[j+1]) of a flat per-summit or per-asperity array.
std::vector<double> slice(const Hdf5Reader& file, const std::string& array, const std::string& offsets, std::size_t j) {
  const std::vector<double> all = file.vector(array);
  const std::vector<double> offset = file.vector(offsets);
  return {all.begin() + static_cast<long>(offset[j]), all.begin() + static_cast<long>(offset[j + 1])};
}

//! Bitwise equality (EXPECT_EQ on doubles would also accept -0 == 0).
void expect_bitwise_equal(const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << what;
}

const char* SUMMIT_ARRAYS[] = {"height_m", "x_m", "y_m", "normal_load_n", "sampled_stiffness_n_per_m", "patch_radius_m",
                               "extra_displacement_m"};
const char* ASPERITY_ARRAYS[] = {"stiffness_n_per_m", "mass_kg", "normal_load_n", "static_deflection_over_length"};

TEST(SurfaceCommand, RealisationAloneEqualsRealisationInBatchAcrossCommands) {
  ScratchDir scratch("surface-alone");
  const auto batch = run_cli("surface " + GW + " --realisations 5 --seed 7 -o " + scratch.file("batch.h5"), scratch);
  ASSERT_EQ(batch.exit_code, 0) << batch.output;
  const auto alone = run_cli("surface " + GW + " --realisations 1 --first 3 --seed 7 -o " + scratch.file("alone.h5"), scratch);
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  const Hdf5Reader b(scratch.file("batch.h5")), a(scratch.file("alone.h5"));
  EXPECT_EQ(a.vector("/realisations/realisation"), std::vector<double>{3.0});
  for (const char* name : SUMMIT_ARRAYS)
    expect_bitwise_equal(slice(b, std::string("/summits/") + name, "/realisations/summit_offset", 3),
                         slice(a, std::string("/summits/") + name, "/realisations/summit_offset", 0), name);
  for (const char* name : ASPERITY_ARRAYS)
    expect_bitwise_equal(slice(b, std::string("/asperities/") + name, "/realisations/asperity_offset", 3),
                         slice(a, std::string("/asperities/") + name, "/realisations/asperity_offset", 0), name);
  // Realisations differ from each other (the slices are not trivially equal).
  EXPECT_NE(slice(b, "/summits/height_m", "/realisations/summit_offset", 2),
            slice(b, "/summits/height_m", "/realisations/summit_offset", 3));

  // A study drawing realisation 3 of the same surface with the same seed runs exactly it.
  const std::string study = scratch.write("study.toml", "seed = 7\nduration_s = 2e-6\nsample_rate_hz = 100e6\n"
                                                        "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
                                                        "[surface]\nfile = \"" + GW + "\"\n[domain]\npolicy = \"flag\"\n");
  const auto run = run_cli("run " + study + " --realisation 3 -o " + scratch.file("run.h5"), scratch);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Hdf5Reader r(scratch.file("run.h5"));
  for (const char* name : SUMMIT_ARRAYS)
    expect_bitwise_equal(slice(b, std::string("/summits/") + name, "/realisations/summit_offset", 3),
                         r.vector(std::string("/surface/summits/") + name), std::string("run: ") + name);
  expect_bitwise_equal(slice(b, "/asperities/stiffness_n_per_m", "/realisations/asperity_offset", 3), r.vector("/asperity/k"),
                       "run: the simulated stiffnesses");
  EXPECT_EQ(r.integer_attribute("/", "realisation"), 3);
}

TEST(SurfaceCommand, FilesRecordTheirInputs) {
  ScratchDir scratch("surface-provenance");
  const auto result = run_cli("surface " + GW + " -k 2 --seed 11 -o " + scratch.file("s.h5"), scratch);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const Hdf5Reader s(scratch.file("s.h5"));
  EXPECT_EQ(s.string_attribute("/", "file_type"), "stengmc-surface");
  EXPECT_EQ(s.string_attribute("/", "input_text"), file_text(GW));
  EXPECT_EQ(s.integer_attribute("/", "seed"), 11);
  EXPECT_FALSE(s.string_attribute("/", "program_version").empty());
  EXPECT_FALSE(s.string_attribute("/", "git_revision").empty());
  EXPECT_EQ(s.integer_attribute("/", "realisation_count"), 2);
  // The run file of a study that references a surface file keeps that file's text too.
  const std::string study = scratch.write("study.toml", "duration_s = 1e-6\nsample_rate_hz = 100e6\n"
                                                        "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
                                                        "[surface]\nfile = \"" + GW + "\"\n[domain]\npolicy = \"flag\"\n");
  ASSERT_EQ(run_cli("run " + study + " -o " + scratch.file("r.h5"), scratch).exit_code, 0);
  const Hdf5Reader r(scratch.file("r.h5"));
  EXPECT_EQ(r.string_attribute("/", "surface_text"), file_text(GW));
  EXPECT_EQ(r.string_attribute("/", "input_text"), file_text(study));
}

TEST(SurfaceCommand, FiguresAreRendered) {
  // --figures renders <out stem>.png with scripts/plot_surface.py (README: stengmc surface).
  ScratchDir scratch("surface-figures");
  const auto result = run_cli("surface " + GW + " -k 3 -o " + scratch.file("gw.h5") + " --figures", scratch);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  ASSERT_TRUE(std::filesystem::exists(scratch.file("gw.png"))) << result.output;
  EXPECT_GT(std::filesystem::file_size(scratch.file("gw.png")), 10'000u);
}

TEST(SurfaceCommand, RealisationsWithoutSummitsAreCountedBySurfaceAndRefusedByRun) {
  // Poisson mean 2e-7 summits: every realisation is empty. `surface` counts them and goes
  // on (one empty realisation must not stop an examination); `run` has nothing to
  // simulate and exits 3 (model error) naming the realisation.
  ScratchDir scratch("surface-empty");
  std::string text = file_text(GW);
  text.replace(text.find("density_per_m2 = 2e9 "), 21, "density_per_m2 = 1 ");
  const std::string surface = scratch.write("empty.toml", text);
  const auto examined = run_cli("surface " + surface + " -k 3 -o " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(examined.exit_code, 0) << examined.output;
  EXPECT_NE(examined.output.find("no summits to carry W"), std::string::npos) << examined.output;
  EXPECT_NE(examined.output.find("3 of 3"), std::string::npos) << examined.output;
  const Hdf5Reader s(scratch.file("s.h5"));
  EXPECT_EQ(s.vector("/realisations/load_carried"), (std::vector<double>{0.0, 0.0, 0.0}));
  const std::string study = scratch.write("study.toml", "duration_s = 1e-6\nsample_rate_hz = 100e6\n"
                                                        "[model]\nkind = \"model2\"\n[surface]\nfile = \"empty.toml\"\n");
  const auto run = run_cli("run " + study + " --realisation 2 -o " + scratch.file("r.h5"), scratch);
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_NE(run.output.find("realisation 2 drew no summits"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("no separation can carry"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("r.h5")));
}

struct BadSurface {
  const char* name;
  const char* from;  // text of the GW surface to replace
  const char* to;
  int exit_code;
  std::vector<const char*> message;  // substrings the error must contain
};

TEST(SurfaceCommand, BadSurfacesExitWithNamedErrorsAndNoOutput) {
  const std::vector<BadSurface> cases = {
      {"hertz without materials", "[materials]", "[unused_materials]", 2, {"bad.toml", "[load] rule", "needs a [materials] table"}},
      {"zero load", "nominal_load_n = 0.02", "nominal_load_n = 0", 2, {"bad.toml:", "nominal_load_n", "no separation can carry"}},
      {"zero std", "std = 0.25e-6", "std = 0", 2, {"bad.toml:", "[heights] std", "must be > 0"}},
      {"negative scale", "sigma_log = 0.5", "sigma_log = -0.5", 2, {"bad.toml:", "sigma_log", "must be > 0"}},
      {"empty truncation", "min = 20 ", "min = 1e6 ", 2, {"bad.toml:", "[stiffness]", "widen it"}},
      {"missing histogram", "kind = \"normal\"", "kind = \"empirical\"\nfile = \"nowhere.csv\"", 2,
       {"bad.toml:", "[heights] file", "nowhere.csv", "cannot open"}},
  };
  for (const BadSurface& c : cases) {
    ScratchDir scratch("surface-bad");
    std::string text = file_text(GW);
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.name;
    text.replace(at, std::strlen(c.from), c.to);
    if (std::string(c.name) == "empty truncation") text.replace(text.find("max = 200"), 9, "max = 2e6");
    const std::string surface = scratch.write("bad.toml", text);
    const std::string out = scratch.file("out.h5");
    const auto result = run_cli("surface " + surface + " -k 2 -o " + out, scratch);
    EXPECT_EQ(result.exit_code, c.exit_code) << c.name << "\n" << result.output;
    for (const char* part : c.message) EXPECT_NE(result.output.find(part), std::string::npos) << c.name << ": " << part << "\n" << result.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
    for (const auto& entry : std::filesystem::directory_iterator(scratch.file("")))
      EXPECT_EQ(entry.path().extension().string() == ".tmp", false) << c.name << ": left " << entry.path();
  }
}

}  // namespace
}  // namespace stengmc
