#include "ensemble/partial_results.hpp"

#include "core/error.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/journal.hpp"
#include "ensemble/shard.hpp"
#include "ensemble/study_file.hpp"

namespace stengmc {

namespace {

constexpr std::string_view SHARD_DESCRIPTION_START = "stengmc-shard";

}  // namespace

PartialSource read_partial_source(const std::string& path) {
  // The journal reader decides what the file is (and refuses what is not a journal); a
  // shard file is then read again by the shard reader, with every check merge makes.
  const std::string advice = "Give a journal (OUT.journal, OUT.point<g>.journal) or a shard file (run --shard i/n).";
  JournalScan scan = scan_journal_file(path, "a journal or shard file", advice);
  PartialSource source;
  source.path = path;
  if (scan.contents.description.rfind(SHARD_DESCRIPTION_START, 0) == 0) {
    ShardFile shard = read_shard_file(path);
    source.complete = true;
    source.shard = shard.spec;
    source.identity = shard.study_identity;
    source.study_file = shard.study_file;
    source.records = std::move(shard.records);
    return source;
  }
  source.identity = scan.contents.study_hash;
  source.study_file = journal_study_file(scan.contents.description);
  try {
    source.journal_shard = journal_shard(scan.contents.description);
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
  source.records = std::move(scan.contents.records);
  source.skipped_bytes = scan.skipped_bytes;
  source.torn_bytes = scan.torn_bytes;
  return source;
}

std::map<std::size_t, std::map<std::uint64_t, const RealisationRecord*>> finished_by_point(
    const PartialSource& source, const std::vector<GridPoint>& grid) {
  const std::uint64_t realisations = grid.front().study.ensemble->realisations;
  std::map<std::size_t, std::map<std::uint64_t, const RealisationRecord*>> points;
  if (source.shard) {
    for (const RealisationRecord& r : source.records) {
      const std::uint64_t g = r.realisation / realisations, id = r.realisation % realisations;
      if (g >= grid.size() || !source.shard->contains(id))
        throw InputError(source.path + ": holds a record (key " + std::to_string(r.realisation) +
                         ") that does not belong to shard " + source.shard->text() + " of this study");
      points[g].emplace(id, &r);
    }
    return points;
  }
  std::optional<std::size_t> point;
  for (std::size_t g = 0; g < grid.size() && !point; ++g)
    if (ensemble_journal_identity(grid[g].study).study_hash == source.identity) point = g;
  if (!point)
    throw InputError(source.path + ": a journal of no grid point of " + grid.front().study.file +
                     " as it is now (the study, its surface or the stengmc version changed since the run, or it is "
                     "another study's journal; --study names the study it ran)");
  auto& finished = points[*point];
  for (const RealisationRecord& r : source.records)
    if (r.realisation < realisations) finished.emplace(r.realisation, &r);
  return points;
}

std::vector<std::uint64_t> expected_ids(const PartialSource& source, std::uint64_t realisations) {
  const std::optional<ShardSpec>& slice = source.shard ? source.shard : source.journal_shard;
  std::vector<std::uint64_t> ids;
  for (std::uint64_t id = 0; id < realisations; ++id)
    if (!slice || slice->contains(id)) ids.push_back(id);
  return ids;
}

SourceStudy read_source_study(const PartialSource& source, const std::string& study_path, const WorkLimits& limits) {
  const std::string file = study_path.empty() ? source.study_file : study_path;
  if (file.empty())
    throw InputError(source.path + ": its header names no study file; --study names the study it ran");
  SourceStudy result{read_study_file(file, std::nullopt), {}};
  if (!result.study.ensemble) throw InputError(file + ": the study has no [ensemble] table, so " + source.path + " is not its");
  if (source.shard && ensemble_identity_hash(result.study) != source.identity)
    throw InputError(file + " is not the study " + source.path +
                     " ran: it, its surface file or the stengmc version changed since (the shard records its identity)" +
                     (study_path.empty() ? " (--study names the study file if it moved)" : ""));
  result.grid = prepare_grid(result.study, limits);
  return result;
}

std::string id_ranges(const std::vector<std::uint64_t>& ids, std::size_t limit) {
  std::string out;
  std::size_t ranges = 0, left_out = 0;
  for (std::size_t i = 0; i < ids.size();) {
    std::size_t j = i;
    while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
    if (ranges++ < limit) {
      // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, its bug 105329) on
      // "literal" + std::string temporaries.
      if (!out.empty()) out += ", ";
      out += std::to_string(ids[i]);
      if (j > i) out.append("-").append(std::to_string(ids[j]));
    } else {
      left_out += j - i + 1;
    }
    i = j + 1;
  }
  if (left_out > 0) out += ", ... (" + std::to_string(left_out) + " more)";
  return out;
}

}  // namespace stengmc
