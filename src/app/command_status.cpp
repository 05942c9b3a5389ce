// `stengmc status`: what a journal or shard file holds of its ensemble, read without
// changing it (a running job may be appending): which study, which grid point or shard,
// how many realisations are finished of how many, which ids are missing (issue 25;
// docs/ensembles.md).
#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "ensemble/partial_results.hpp"

namespace stengmc::app {

namespace {

struct StatusOptions {
  std::string file;
  std::string study;  //!< the study file, if not where the run read it
};

std::string hex(std::uint64_t value) {
  char text[32];
  std::snprintf(text, sizeof text, "0x%016llx", static_cast<unsigned long long>(value));
  return text;
}

std::vector<std::uint64_t> present_ids(const PartialSource& source) {
  std::vector<std::uint64_t> ids;
  for (const RealisationRecord& r : source.records) ids.push_back(r.realisation);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

void print_damage(const PartialSource& source) {
  if (source.skipped_bytes > 0)
    std::printf("  damaged: %llu bytes between records skipped (the records they held are lost; a resume skips them too)\n",
                static_cast<unsigned long long>(source.skipped_bytes));
  if (source.torn_bytes > 0)
    std::printf("  torn: the last %llu bytes are an unfinished record (a run writing or killed mid-write); a resume "
                "cuts them off\n",
                static_cast<unsigned long long>(source.torn_bytes));
}

//! Finished and missing ids of each grid point the file covers, against the study's count.
void print_points(const PartialSource& source, const SourceStudy& study) {
  const std::uint64_t realisations = study.study.ensemble->realisations;
  const auto finished = finished_by_point(source, study.grid);
  const std::vector<std::uint64_t> expected = expected_ids(source, realisations);
  const std::optional<ShardSpec>& slice = source.shard ? source.shard : source.journal_shard;
  // A shard file covers every grid point; a journal its own.
  std::vector<std::size_t> points;
  if (source.shard)
    for (std::size_t g = 0; g < study.grid.size(); ++g) points.push_back(g);
  else
    points.push_back(finished.begin()->first);
  std::size_t all_finished = 0, all_expected = 0;
  for (const std::size_t g : points) {
    const auto at = finished.find(g);
    std::vector<std::uint64_t> missing;
    std::size_t done = 0;
    for (const std::uint64_t id : expected) {
      if (at != finished.end() && at->second.count(id)) ++done;
      else missing.push_back(id);
    }
    all_finished += done;
    all_expected += expected.size();
    std::printf("  grid point %zu of %zu%s: %zu of %zu realisations finished%s\n", g + 1, study.grid.size(),
                study.grid.size() > 1 ? (" (" + describe_grid_point(study.grid[g], true) + ")").c_str() : "", done,
                expected.size(), slice ? (" (shard " + slice->text() + "'s share)").c_str() : "");
    std::printf("    missing: %s\n", missing.empty() ? "none" : id_ranges(missing).c_str());
  }
  if (points.size() > 1) std::printf("  in all: %zu of %zu realisations finished\n", all_finished, all_expected);
}

void status(const StatusOptions& options) {
  const PartialSource source = read_partial_source(options.file);
  std::printf("%s: %s\n", source.path.c_str(),
              source.complete ? ("a finished shard file, shard " + source.shard->text()).c_str()
              : source.journal_shard
                  ? ("a journal of shard " + source.journal_shard->text() +
                     "'s run, in progress or interrupted (the same run command resumes it)")
                        .c_str()
                  : "a journal of a run in progress or interrupted (the same run command resumes it)");
  std::printf("  study: %s (%s identity %s)\n", source.study_file.empty() ? "(not named)" : source.study_file.c_str(),
              source.shard ? "study" : "grid point", hex(source.identity).c_str());
  std::printf("  records: %zu intact\n", source.records.size());
  print_damage(source);
  try {
    print_points(source, read_source_study(source, options.study));
  } catch (const InputError& e) {
    // The file itself is readable; only the comparison with the study is not possible.
    std::printf("  how many are expected is not known: %s\n  finished ids: %s\n", e.what(),
                id_ranges(present_ids(source)).c_str());
  }
}

}  // namespace

void add_status_command(CLI::App& app) {
  auto options = std::make_shared<StatusOptions>();
  CLI::App* command = app.add_subcommand(
      "status",
      "Show what a journal (OUT.journal, OUT.point<g>.journal) or shard file holds: study, grid point or shard, "
      "realisations finished and missing (read only)");
  command->add_option("file", options->file, "The journal or shard file")->required()->check(CLI::ExistingFile);
  command->add_option("--study", options->study,
                      "The study file, if it is no longer where the run read it (it must be the same text)")
      ->check(CLI::ExistingFile);
  command->callback([options] { status(*options); });
}

}  // namespace stengmc::app
