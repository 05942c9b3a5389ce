#include "ensemble/shard.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>

#include "core/build_info.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "ensemble/ensemble_runner.hpp"

namespace stengmc {

namespace {

constexpr std::string_view SHARD_MAGIC = "stengmc-shard";

bool parse_whole(std::string_view text, std::uint64_t& value) {
  if (text.empty()) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

std::string describe(const StudyFile& base, const ShardSpec& spec) {
  std::ostringstream out;
  out << SHARD_MAGIC << "\nindex = " << spec.index << "\ncount = " << spec.count << "\nstudy_identity = "
      << ensemble_identity_hash(base) << "\nstudy = " << base.file << "\nprogram = stengmc " << program_version()
      << " (git " << git_revision() << ")";
  return out.str();
}

//! The value of `key = value` in a shard description, or "" when absent.
std::string field(const std::string& description, const std::string& key) {
  std::istringstream in(description);
  std::string line;
  const std::string prefix = key + " = ";
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  return "";
}

std::string listing(const std::vector<const ShardFile*>& files) {
  std::string out;
  for (const ShardFile* f : files) out += (out.empty() ? "" : ", ") + f->path;
  return out;
}

}  // namespace

ShardSpec parse_shard_spec(std::string_view text) {
  const std::string given = "--shard " + std::string(text) + ": ";
  const auto slash = text.find('/');
  ShardSpec spec;
  if (slash == std::string_view::npos || !parse_whole(text.substr(0, slash), spec.index) ||
      !parse_whole(text.substr(slash + 1), spec.count))
    throw InputError(given + "expected i/n, two whole numbers with 0 <= i < n (shard i of n, e.g. 0/8)");
  if (spec.count == 0) throw InputError(given + "the number of shards n must be at least 1");
  if (spec.index >= spec.count)
    throw InputError(given + "the shard index must be below the number of shards (0.." + std::to_string(spec.count - 1) +
                     "; shards are numbered from 0)");
  return spec;
}

JournalIdentity shard_identity(const StudyFile& base, const ShardSpec& spec) {
  const std::string description = describe(base, spec);
  return {fnv1a64(description), description};
}

void write_shard_file(const std::string& path, const StudyFile& base, const ShardSpec& spec,
                      const std::vector<GridPoint>& grid) {
  const std::uint64_t realisations = base.ensemble->realisations;
  std::vector<RealisationRecord> records;
  for (std::size_t g = 0; g < grid.size(); ++g)
    for (const RealisationRecord& r : grid[g].run.records) {
      records.push_back(r);
      records.back().realisation = g * realisations + r.realisation;
    }
  write_journal_file(path, shard_identity(base, spec), records);
}

ShardFile read_shard_file(const std::string& path) {
  const std::string not_a_shard = path + ": not a finished shard file (";
  check_input_file(path, "a shard file");  // a FIFO would block the read below for ever
  {
    std::ifstream in(path, std::ios::binary);
    std::string magic(8, '\0');
    if (!in.read(magic.data(), 8) || magic != "STENGMCJ")
      throw InputError(not_a_shard + "stengmc run STUDY --shard i/n writes those)");
  }
  // A shard file is made by one command, and made again by the same command; `merge` has no
  // --restart to offer.
  JournalContents contents =
      read_journal_file(path, "a shard file", "Make the shard again with stengmc run STUDY --shard i/n.");
  if (contents.description.rfind(SHARD_MAGIC, 0) != 0)
    throw InputError(not_a_shard + "it is a journal of a run that has not finished: run that shard again with "
                                   "`stengmc run STUDY --shard i/n`, which resumes it)");
  if (contents.study_hash != fnv1a64(contents.description))
    throw InputError(not_a_shard + "its header does not match its checksum)");
  ShardFile shard;
  shard.path = path;
  shard.study_file = field(contents.description, "study");
  if (!parse_whole(field(contents.description, "index"), shard.spec.index) ||
      !parse_whole(field(contents.description, "count"), shard.spec.count) ||
      !parse_whole(field(contents.description, "study_identity"), shard.study_identity) || shard.spec.count == 0 ||
      shard.spec.index >= shard.spec.count)
    throw InputError(not_a_shard + "its header lacks the shard's index, count or study identity)");
  shard.records = std::move(contents.records);
  return shard;
}

void check_shard_set(const std::vector<ShardFile>& shards) {
  if (shards.empty()) throw InputError("merge: no shard files given");
  const ShardFile& first = shards.front();
  for (const ShardFile& s : shards) {
    if (s.study_identity != first.study_identity)
      throw InputError(s.path + " is a shard of another computation than " + first.path + " (" + s.study_file +
                       " against " + first.study_file +
                       ": the study, its surface or the program differ); merge only the shards of one run");
    if (s.spec.count != first.spec.count)
      throw InputError(s.path + " is shard " + s.spec.text() + " but " + first.path + " is shard " + first.spec.text() +
                       ": all shards of a merge must come from the same --shard i/n with one n");
  }
  std::map<std::uint64_t, std::vector<const ShardFile*>> by_index;
  for (const ShardFile& s : shards) by_index[s.spec.index].push_back(&s);
  for (const auto& [index, files] : by_index)
    if (files.size() > 1)
      throw InputError("shard " + files.front()->spec.text() + " is given " + std::to_string(files.size()) +
                       " times: " + listing(files) + "; give each shard once");
  std::string missing;
  std::size_t missing_count = 0;
  for (std::uint64_t i = 0; i < first.spec.count; ++i)
    if (!by_index.count(i)) {
      if (++missing_count <= 20) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    }
  if (missing_count > 0)
    throw InputError(std::to_string(missing_count) + " of the " + std::to_string(first.spec.count) +
                     " shards are missing (index " + missing + (missing_count > 20 ? ", ..." : "") + " of " +
                     std::to_string(first.spec.count) + "; given: " + std::to_string(shards.size()) +
                     " files): run them with --shard i/" + std::to_string(first.spec.count) + " and merge all");
}

void merge_shard_records(const std::vector<ShardFile>& shards, std::vector<GridPoint>& grid) {
  const std::uint64_t realisations = grid.front().study.ensemble->realisations;
  std::vector<std::map<std::uint64_t, const RealisationRecord*>> points(grid.size());
  for (const ShardFile& s : shards)
    for (const RealisationRecord& r : s.records) {
      const std::uint64_t g = r.realisation / realisations, id = r.realisation % realisations;
      if (g >= grid.size() || !s.spec.contains(id) || !points[g].emplace(id, &r).second)
        throw InputError(s.path + ": holds a record (key " + std::to_string(r.realisation) +
                         ") that does not belong to shard " + s.spec.text() + " of this study, or holds it twice");
    }
  for (std::size_t g = 0; g < grid.size(); ++g) {
    for (const ShardFile& s : shards)
      for (std::uint64_t id = s.spec.index; id < realisations; id += s.spec.count)
        if (!points[g].count(id))
          throw InputError(s.path + ": lacks realisation " + std::to_string(id) + " of grid point " + std::to_string(g + 1) +
                           ": the file is not the shard a finished run wrote; run shard " + s.spec.text() + " again");
    EnsembleRun& run = grid[g].run;
    run = EnsembleRun{};
    run.requested = realisations;
    for (const auto& [id, record] : points[g]) run.records.push_back(*record);
    for (RealisationRecord& r : run.records) r.realisation %= realisations;
  }
}

}  // namespace stengmc
