#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "app/output_guard.hpp"
#include "core/progress.hpp"
#include "io/run_file.hpp"
#include "io/study.hpp"
#include "io/surface_file.hpp"
#include "io/toml_reader.hpp"
#include "pipeline/surface_examination.hpp"

namespace stengmc::app {

namespace {

struct SurfaceOptions {
  std::string surface_file;
  std::uint64_t realisations = 100;
  std::uint64_t seed = 0;
  std::uint64_t first = 0;
  std::string study_file;
  std::string out;
  bool figures = false;
};

std::string default_output(const std::string& surface_file) {
  return (std::filesystem::path("results") / std::filesystem::path(surface_file).stem()).string() + "_surface.h5";
}

void run(const SurfaceOptions& options) {
  auto document = TomlDocument::from_file(options.surface_file);
  TomlTable root = document->root();
  const Surface surface = Surface::from_toml(root, std::filesystem::path(options.surface_file).parent_path());
  document->reject_unknown_keys();
  // The validity checks need the tribology parameters: the study's, else the defaults (Table 1).
  Model1Params model1;
  Model2Params model2;
  if (!options.study_file.empty()) {
    const Study study = read_study(options.study_file);
    model1 = study.model1;
    model2 = study.model2;
  }
  const std::string out = options.out.empty() ? default_output(options.surface_file) : options.out;
  refuse_overwriting_input(options.surface_file, out);
  std::printf("stengmc surface %s: realisations %llu..%llu, seed %llu; validity against %s\n", options.surface_file.c_str(),
              static_cast<unsigned long long>(options.first),
              static_cast<unsigned long long>(options.first + options.realisations - 1),
              static_cast<unsigned long long>(options.seed),
              options.study_file.empty() ? "the default Model 1 and Model 2 parameters (Table 1)" : options.study_file.c_str());
  SurfaceExamination examination;
  {
    Progress progress("sampling", options.realisations);
    examination = examine_surface(surface, options.seed, options.first, options.realisations, model1, model2, &progress);
  }
  write_surface_file(out, {"stengmc-surface", options.surface_file, document->text(), options.seed, "", ""}, examination);
  std::printf("%s", format_surface_summary(examination).c_str());
  std::printf("wrote %s\n", out.c_str());
  if (options.figures && render_figures(out) != 0)
    throw std::runtime_error("figure rendering failed (see the messages above); the HDF5 output is complete");
}

}  // namespace

void add_surface_command(CLI::App& app) {
  auto options = std::make_shared<SurfaceOptions>();
  CLI::App* command = app.add_subcommand(
      "surface", "Sample realisations of a surface file: population statistics, validity report, HDF5 of the populations");
  command->add_option("surface", options->surface_file, "Surface file (TOML; see surfaces/ and the README)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-k,--realisations", options->realisations, "Number of realisations to draw")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100'000'000}));
  command->add_option("-s,--seed", options->seed, "Master seed (realisation r depends on seed and r only)")->capture_default_str();
  command->add_option("--first", options->first, "First realisation id (draw realisations first .. first+K-1)")
      ->capture_default_str();
  command->add_option("--study", options->study_file,
                      "Take the Model 1 / Model 2 parameters of the validity checks from this study file")
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (default: results/<surface>_surface.h5)");
  command->add_flag("-f,--figures", options->figures, "Also render PNG figures beside the output (needs python3-h5py, matplotlib)");
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
