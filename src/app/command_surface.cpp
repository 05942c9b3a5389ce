#include <cmath>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "app/limit_options.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "io/output_path.hpp"
#include "io/run_file.hpp"
#include "pipeline/study.hpp"
#include "io/surface_file.hpp"
#include "core/toml_reader.hpp"
#include "pipeline/surface_examination.hpp"

namespace stengmc::app {

namespace {

// Seeds and realisation ids are stored as int64 attributes and datasets.
constexpr std::uint64_t MAX_REALISATION_ID = std::numeric_limits<std::int64_t>::max();

struct SurfaceOptions {
  std::string surface_file;
  std::uint64_t realisations = 100;
  std::uint64_t seed = 0;
  std::uint64_t first = 0;
  std::string study_file;
  std::string out;
  bool figures = false;
  FigureOptions figure;
  LimitOptions limits;
};

std::string default_output(const std::string& surface_file) {
  return (std::filesystem::path("results") / std::filesystem::path(surface_file).stem()).string() + "_surface.h5";
}

void run(const SurfaceOptions& options) {
  auto document = TomlDocument::from_file(options.surface_file);
  TomlTable root = document->root();
  if (root.has("duration_s") || root.has("model"))
    throw InputError(options.surface_file + " is a study file, not a surface file: give the surface file it names in "
                     "[surface] file = ..., and the study with --study");
  const Surface surface = Surface::from_toml(root, std::filesystem::path(options.surface_file).parent_path());
  document->reject_unknown_keys();
  // The validity checks need the tribology parameters: the study's, else the defaults (Table 1).
  ModelParameters models;
  ModelScope scope;  // without a study: both models, at their defaults
  if (!options.study_file.empty()) {
    models = read_model_parameters(options.study_file);
    scope = {models.kind == ModelKind::model1, models.kind == ModelKind::model2};
  }
  if (options.first > MAX_REALISATION_ID - (options.realisations - 1))
    throw InputError("--first " + std::to_string(options.first) + " with --realisations " +
                     std::to_string(options.realisations) + " passes the largest realisation id, " +
                     std::to_string(MAX_REALISATION_ID));
  // Every realisation's summits stay in memory until the file is written.
  if (const RandomSurface* random = surface.random_surface())
    check_work(estimate_surface(*random, static_cast<double>(options.realisations)), options.limits.limits(),
               options.surface_file + ": --realisations " + std::to_string(options.realisations) +
                   " (draw fewer and continue with --first)");
  const std::string out = options.out.empty() ? default_output(options.surface_file) : options.out;
  std::vector<NamedInput> inputs{{options.surface_file, "the surface file"}, {options.study_file, "the study"}};
  for (const std::string& file : surface.auxiliary_input_files()) inputs.push_back({file, "a histogram file the surface reads"});
  check_output_path(out, inputs);
  std::printf("stengmc surface %s: realisations %llu..%llu, seed %llu; validity against %s\n", options.surface_file.c_str(),
              static_cast<unsigned long long>(options.first),
              static_cast<unsigned long long>(options.first + options.realisations - 1),
              static_cast<unsigned long long>(options.seed),
              options.study_file.empty() ? "the default Model 1 and Model 2 parameters (Table 1)" : options.study_file.c_str());
  SurfaceExamination examination;
  {
    Progress progress("sampling", options.realisations);
    examination = examine_surface(surface, options.seed, options.first, options.realisations, models.model1,
                                  models.model2, &progress, scope);
  }
  Provenance provenance;
  provenance.file_type = "stengmc-surface";
  provenance.input_file = options.surface_file;
  provenance.input_text = document->text();
  provenance.seed = options.seed;
  provenance.auxiliary_inputs = surface.auxiliary_inputs();
  write_surface_file(out, provenance, examination);
  std::printf("%s", format_surface_summary(examination).c_str());
  std::printf("wrote %s\n", out.c_str());
  if (options.figures && render_figures(out, options.figure) != 0)
    throw std::runtime_error("figure rendering failed (see the messages above); the HDF5 output is complete");
}

}  // namespace

void add_surface_command(CLI::App& app) {
  auto options = std::make_shared<SurfaceOptions>();
  CLI::App* command = app.add_subcommand(
      "surface", "Sample realisations of a surface file: population statistics, validity report, HDF5 of the populations");
  command->add_option("surface", options->surface_file, "Surface file (TOML; see surfaces/ and docs/study-files.md)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-k,--realisations", options->realisations, "Number of realisations to draw")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100'000'000}));
  command->add_option("-s,--seed", options->seed, "Master seed (realisation r depends on seed and r only)")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{0}, MAX_REALISATION_ID));
  command->add_option("--first", options->first, "First realisation id (draw realisations first .. first+K-1)")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{0}, MAX_REALISATION_ID));
  command->add_option("--study", options->study_file,
                      "Take the Model 1 / Model 2 parameters of the validity checks from this study file")
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (default: results/<surface>_surface.h5)")
      ->check(non_empty_path());
  CLI::Option* figures = command->add_flag("-f,--figures", options->figures,
                                           "Also render figures beside the output (needs python3-h5py, matplotlib)");
  add_figure_options(command, figures, options->figure);
  add_limit_options(command, options->limits);
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
