// `stengmc export-netlist STUDY [-o file.cir]`: the tribology of one realisation, then its
// elements as an ngspice / LTspice netlist (io/netlist_export.hpp; README: "ngspice netlist").
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "app/limit_options.hpp"
#include "io/netlist_export.hpp"
#include "io/output_path.hpp"
#include "pipeline/run_study.hpp"

namespace stengmc::app {

namespace {

struct ExportOptions {
  std::string study_file;
  std::string out;
  std::uint64_t realisation = 0;
  LimitOptions limits;
};

void run(const ExportOptions& options) {
  const Study study = read_study(options.study_file, options.realisation);
  const std::string out = options.out.empty()
      ? (std::filesystem::path("results") / std::filesystem::path(study.file).stem()).string() + ".cir"
      : options.out;
  check_output_path(out, study_inputs(study));
  // The netlist needs the motions only: the built-in circuit runs too (it is cheap), a
  // netlist load is not co-simulated.
  Study tribology_only = study;
  tribology_only.netlist = nullptr;
  check_work(estimate_run(tribology_only, -1.0, true, true), options.limits.limits(), study.file + ": the run");
  std::printf("stengmc export-netlist %s: %s, %zu asperities, %.4g s at %.4g Hz\n", study.file.c_str(),
              std::string(model_name(study.model)).c_str(), study.asperities.size(), study.duration_s,
              study.sample_rate_hz);
  const RunResult result =
      run_study(tribology_only, stengmc::RunOptions{.show_progress = true, .limits = options.limits.limits()});
  for (const std::string& note : result.notes) std::printf("note: %s\n", note.c_str());
  const std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  write_netlist_file(out, study, result);
  std::printf("wrote %s (S-TENG port: node steng against ground 0)\n", out.c_str());
}

}  // namespace

void add_export_netlist_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export-netlist", "Run a study's tribology and write its S-TENG elements, driven by their x(t) as PWL sources,\n"
                        "on the study's load as an ngspice / LTspice netlist (port node: steng)");
  command->add_option("study", options->study_file, "Study file (TOML)")->required();
  command->add_option("-o,--out", options->out, "Output netlist (default: results/<study>.cir)")
      ->check(non_empty_path());
  command->add_option("-r,--realisation", options->realisation, "Realisation of a random surface (default 0)")
      ->check(CLI::Range(std::uint64_t{0}, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())));
  add_limit_options(command, options->limits);
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
