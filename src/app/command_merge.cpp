// `stengmc merge`: the shards of an ensemble (run --shard i/n) into the one output file a
// single run writes (docs/ensembles.md; docs/cluster.md).
#include <cstdio>
#include <map>
#include <memory>

#include "app/commands.hpp"
#include "app/inputs.hpp"
#include "app/limit_options.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/ensemble_summary.hpp"
#include "ensemble/partial_results.hpp"
#include "ensemble/shard.hpp"
#include "ensemble/sweep.hpp"
#include "io/ensemble_file.hpp"

namespace stengmc::app {

namespace {

struct MergeOptions {
  std::vector<std::string> shards;
  std::string out;
  std::string study;  //!< the study file, if not where the shards' runs read it
  bool partial = false;  //!< write what the shards and journals hold, however much is missing
  LimitOptions limits;
};

//! Each shard is checked (a regular file: a FIFO would block the merge for ever) and read
//! whole into memory, so together they must fit the memory limit.
void check_reading(const MergeOptions& options) {
  WorkEstimate reading;
  for (const std::string& path : options.shards)
    reading.add_memory("the shard file " + path, static_cast<double>(check_input_file(path, "a shard file")));
  check_work(reading, options.limits.limits(), "merge: reading the shards");
}

//! --partial: the finished realisations of any shards and journals of one study, each grid
//! point's in id order (a realisation in two files, such as a shard and its journal, once:
//! it is the same record), as an ordinary ensemble file marked partial.
void merge_partial(const MergeOptions& options) {
  check_reading(options);
  std::vector<PartialSource> sources;
  for (const std::string& path : options.shards) sources.push_back(read_partial_source(path));
  const SourceStudy read = read_source_study(sources.front(), options.study, options.limits.limits());
  const StudyFile& study = read.study;
  std::vector<GridPoint> grid = read.grid;
  std::vector<std::map<std::uint64_t, const RealisationRecord*>> points(grid.size());
  for (const PartialSource& source : sources) {
    if (source.shard && source.identity != ensemble_identity_hash(study))
      throw InputError(source.path + " is a shard of another computation than " + sources.front().path + " (" +
                       source.study_file + " against " + study.file + "); merge only the files of one run");
    for (const auto& [g, finished] : finished_by_point(source, grid)) points[g].insert(finished.begin(), finished.end());
  }
  const std::uint64_t realisations = study.ensemble->realisations;
  // A grid point without one finished realisation has no row and no statistic to write, and
  // NaN in their place would read as a result: refuse, naming every such point, so the
  // researcher knows which journals or shards to add (or to wait for).
  std::vector<std::size_t> empty;
  for (std::size_t g = 0; g < grid.size(); ++g)
    if (points[g].empty()) empty.push_back(g);
  if (!empty.empty()) {
    std::string named;
    for (std::size_t k = 0; k < empty.size() && k < 10; ++k)
      named += std::string(k ? "; " : "") + std::to_string(empty[k] + 1) +
               (grid.size() > 1 ? " (" + describe_grid_point(grid[empty[k]], true) + ")" : std::string());
    if (empty.size() > 10) named += "; ... (" + std::to_string(empty.size() - 10) + " more)";
    throw InputError("merge --partial: no file given holds a finished realisation of grid point" +
                     std::string(empty.size() > 1 ? "s " : " ") + named + " of " + std::to_string(grid.size()) + " in " +
                     study.file + ": an ensemble file has every grid point of its study, each with at least one "
                     "realisation. Add the journals (OUT.point<g>.journal) or shard files that hold them, or wait "
                     "until the run has finished one at each point; nothing was written");
  }
  std::size_t present = 0;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    EnsembleRun& run = grid[g].run;
    run = EnsembleRun{};
    run.requested = realisations;
    run.partial = points[g].size() < realisations;
    for (const auto& [id, record] : points[g]) run.records.push_back(*record);
    for (RealisationRecord& r : run.records) r.realisation = r.realisation % realisations;
    present += run.records.size();
    grid[g].summary = summarise_ensemble(run.records, study.seed);
  }
  const std::string out = options.out.empty() ? study.output.file : options.out;
  std::vector<NamedInput> inputs = study_inputs(study);
  for (const PartialSource& s : sources) inputs.push_back({s.path, "a shard or journal file"});
  check_output_path(out, inputs, output_option(options.out, study));
  write_ensemble_file(out, study, grid);
  const std::size_t expected = realisations * grid.size();
  std::printf("stengmc merge --partial: %zu files of %s (seed %llu)\n", sources.size(), study.file.c_str(),
              static_cast<unsigned long long>(study.seed));
  print_ensemble_results(study, grid, false);
  if (present < expected)
    std::printf("PARTIAL: %zu of the %zu realisations are in this file (root attribute partial = 1); statistics are "
                "over these alone\n",
                present, expected);
  else
    std::printf("complete: all %zu realisations were there, so the file is the one a merge of every shard writes\n",
                expected);
  std::printf("wrote %s\n", out.c_str());
}

void merge(const MergeOptions& options) {
  if (options.partial) return merge_partial(options);
  check_reading(options);
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
      "merge", "Merge the shard files of an ensemble (run --shard i/n, i = 0..n-1) into the output file one run writes "
      "(--partial: what unfinished shards and journals hold)");
  command->add_option("shards", options->shards, "The shard files, all n of them, each once (with --partial: any shard files and journals of one run)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file (default: the study's [output] file)")
      ->check(non_empty_path());
  command->add_option("--study", options->study,
                      "The study file, if it is no longer where the shard runs read it (it must be the same text)")
      ->check(CLI::ExistingFile);
  command->add_flag("--partial", options->partial,
                    "Write what the given shard files and journals (OUT.journal, OUT.point<g>.journal) hold, however "
                    "many shards or realisations are missing: an ordinary ensemble file whose statistics are over the "
                    "finished realisations, marked with the root attribute partial = 1");
  add_limit_options(command, options->limits);
  command->callback([options] { merge(*options); });
}

}  // namespace stengmc::app
