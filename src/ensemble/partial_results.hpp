#pragma once
//! What shard files and journals of an unfinished ensemble hold (issue 25): `stengmc
//! status` shows it, `stengmc merge --partial` writes it as an ordinary ensemble file.
//!
//! A shard file names its study (the identity hash, the file, i/n) and stores grid point
//! g's realisation r under the id g × realisations + r (ensemble/shard.hpp). A journal
//! names only the study file and the hash of its grid point's study (the identity of
//! ensemble_journal_identity), so its grid point is the one whose hash it carries.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ensemble/realisation_record.hpp"
#include "ensemble/shard_spec.hpp"
#include "ensemble/sweep.hpp"

namespace stengmc {

//! A shard file or a journal, read without changing it.
struct PartialSource {
  std::string path;
  bool complete = false;               //!< a finished shard file (else a journal in progress)
  std::optional<ShardSpec> shard;      //!< shard files only
  //! journals of a `run --shard i/n`: the slice that run owns (its header says which)
  std::optional<ShardSpec> journal_shard;
  std::uint64_t identity = 0;          //!< shard: the study's identity; journal: its grid point's
  std::string study_file;              //!< as the run was given it ("" when the header names none)
  std::vector<RealisationRecord> records;  //!< ids as stored (shards: g × realisations + r)
  std::uint64_t skipped_bytes = 0;     //!< journals: damaged bytes between intact records
  std::uint64_t torn_bytes = 0;        //!< journals: a torn last append, cut off on resume
};

//! Reads a shard file (checked as merge checks it) or a journal (every intact record, as a
//! resume keeps them); InputError naming `path` when it is neither.
PartialSource read_partial_source(const std::string& path);

//! The finished ids of each grid point of `grid` (prepare_grid of the source's study, whose
//! identity the caller compared for a shard) that `source` holds: point → id → record.
//! InputError naming the file when a journal belongs to no grid point of the study or a
//! shard holds an id outside it.
std::map<std::size_t, std::map<std::uint64_t, const RealisationRecord*>> finished_by_point(
    const PartialSource& source, const std::vector<GridPoint>& grid);

//! The ids an unfinished run of `source` is to produce at each grid point: a shard's slice
//! (a shard file's, or the journal's of a --shard run), every id for a whole run's journal.
std::vector<std::uint64_t> expected_ids(const PartialSource& source, std::uint64_t realisations);

//! The study `source` ran, read from `study_path` (or, when that is empty, the file its
//! header names), and its grid. InputError naming both files when a shard's study identity
//! differs from the study's now (it, its surface or the stengmc version changed).
struct SourceStudy {
  StudyFile study;
  std::vector<GridPoint> grid;
};
SourceStudy read_source_study(const PartialSource& source, const std::string& study_path,
                              const WorkLimits& limits = {});

//! "1-2, 4, 7-9": ascending `ids` as ranges; after `limit` ranges, ", ... (N more)".
std::string id_ranges(const std::vector<std::uint64_t>& ids, std::size_t limit = 40);

}  // namespace stengmc
