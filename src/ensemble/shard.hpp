#pragma once
//! Shards: an ensemble cut into n slices that run anywhere, at any time (Slurm job arrays,
//! several machines), and are merged into the file one run would have written (README:
//! ensembles; docs/cluster.md).
//!
//! Shard i of n runs the realisations r with r ≡ i (mod n) of every grid point. Round robin
//! rather than contiguous blocks: realisation costs drift with the id only by chance, and
//! a sweep's expensive points are shared by every shard alike, so the slices take about
//! the same time; resuming a killed shard with another n is also safe, since the
//! realisations of a journal are valid whatever slice they belong to.
//!
//! A shard file is a journal file (ensemble/journal.hpp) written in one go when the shard
//! has finished, so it exists only complete. Its header's description says what it is
//! (the study's identity hash, the study file, i and n) and its hash is the FNV-1a of that
//! description; grid point g's realisation r is stored under the id g × realisations + r.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ensemble/journal.hpp"
#include "ensemble/shard_spec.hpp"
#include "ensemble/sweep.hpp"
#include "ensemble/study_file.hpp"

namespace stengmc {

//! A shard file as read back.
struct ShardFile {
  std::string path;
  ShardSpec spec;
  std::uint64_t study_identity = 0;  //!< ensemble_identity_hash of the study as written
  std::string study_file;            //!< the study's path as the shard run was given it
  std::vector<RealisationRecord> records;
};

//! The identity a shard file is written under.
JournalIdentity shard_identity(const StudyFile& base, const ShardSpec& spec);

//! Writes shard `spec` of `base` from its finished grid (records of the shard's ids only).
void write_shard_file(const std::string& path, const StudyFile& base, const ShardSpec& spec,
                      const std::vector<GridPoint>& grid);

//! Reads a shard file; InputError naming `path` when it is not a finished shard file.
ShardFile read_shard_file(const std::string& path);

//! Checks that `shards` are the slices 0..n-1 of one computation, each once; InputError
//! naming the files otherwise.
void check_shard_set(const std::vector<ShardFile>& shards);

//! Puts the records of a checked shard set into `grid` (prepare_grid of the study the
//! shards ran, whose identity the caller compared), each point's in id order, as a single
//! run would hold them; InputError naming the file of any record that does not belong.
void merge_shard_records(const std::vector<ShardFile>& shards, std::vector<GridPoint>& grid);

}  // namespace stengmc
