// `stengmc merge`: the shards of an ensemble (run --shard i/n) into the one output file a
// single run writes (docs/ensembles.md; docs/cluster.md).
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "app/limit_options.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/ensemble_summary.hpp"
#include "ensemble/shard.hpp"
#include "ensemble/sweep.hpp"
#include "io/ensemble_file.hpp"

namespace stengmc::app {

namespace {

struct MergeOptions {
  std::vector<std::string> shards;
  std::string out;
  std::string study;  //!< the study file, if not where the shards' runs read it
  LimitOptions limits;
};

void merge(const MergeOptions& options) {
  // Each shard is checked (a regular file: a FIFO would block the merge for ever) and read
  // whole into memory, so together they must fit the memory limit.
  WorkEstimate reading;
  for (const std::string& path : options.shards)
    reading.add_memory("the shard file " + path, static_cast<double>(check_input_file(path, "a shard file")));
  check_work(reading, options.limits.limits(), "merge: reading the shards");
  std::vector<ShardFile> shards;
  for (const std::string& path : options.shards) shards.push_back(read_shard_file(path));
  check_shard_set(shards);
  const ShardFile& first = shards.front();
  const std::string study_file = options.study.empty() ? first.study_file : options.study;
  const StudyFile study = read_study_file(study_file, std::nullopt);
  if (!study.ensemble || ensemble_identity_hash(study) != first.study_identity)
    throw InputError(study_file + " is not the study " + first.path +
                     " and the other shards ran: it, its surface file or the stengmc version changed since (the "
                     "shards record its identity); merge with the study and program they ran with" +
                     (options.study.empty() ? " (--study names the study file if it moved)" : ""));
  const std::string out = options.out.empty() ? study.output.file : options.out;
  std::vector<NamedInput> inputs = study_inputs(study);
  for (const ShardFile& s : shards) inputs.push_back({s.path, "a shard file"});
  check_output_path(out, inputs, output_option(options.out, study));

  std::vector<GridPoint> grid = prepare_grid(study, options.limits.limits());
  merge_shard_records(shards, grid);
  for (GridPoint& point : grid) point.summary = summarise_ensemble(point.run.records, study.seed);
  write_ensemble_file(out, study, grid);
  std::printf("stengmc merge: %zu shards of %s (seed %llu)\n", shards.size(), study.file.c_str(),
              static_cast<unsigned long long>(study.seed));
  print_ensemble_results(study, grid, false);
  std::printf("wrote %s\n", out.c_str());
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* command = app.add_subcommand(
      "merge", "Merge the shard files of an ensemble (run --shard i/n, i = 0..n-1) into the output file one run writes");
  command->add_option("shards", options->shards, "The shard files, all n of them, each once")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (default: the study's [output] file)")
      ->check(non_empty_path());
  command->add_option("--study", options->study,
                      "The study file, if it is no longer where the shard runs read it (it must be the same text)")
      ->check(CLI::ExistingFile);
  add_limit_options(command, options->limits);
  command->callback([options] { merge(*options); });
}

}  // namespace stengmc::app
