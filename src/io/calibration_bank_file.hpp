#pragma once
//! The calibration bank file (docs/inverse.md, "calibration bank"),
//! file_type "stengmc-calibration-bank":
//!   root attributes  provenance (the device study's file and text, calibration seed, program
//!                    version, git revision, date); identity_hash (hex) and what it hashes:
//!                    identity_device, identity_prior, identity_grid, identity_estimator;
//!                    prior_study_text (the ensemble study the records came from);
//!                    records_requested, records_valid, seconds, atom_seconds, threads
//!   /atoms/          the atoms' shape family (AtomShapeData): pi_nodes, zeta_nodes; the
//!                    onset-aligned rows (onset_nodes: which nodes; onset_values, onset_slopes)
//!                    and the breakaway-aligned ones (breakaway_nodes, _values, _slopes,
//!                    breakaway_share); tail_log_amplitude, tail_phase per node; attributes the
//!                    range (min/max_pi, min/max_zeta), sample counts, check_error and settings
//!   /maps/           naive_thresholds; attributes count_min, count_max, misfit_ratio and line_se_bound
//!                    (the fit classes' boundaries), naive_threshold, records and the bank's own figures
//!   /maps/fits/, /maps/misfits/  each fit class's maps (inverse/calibration_maps.hpp):
//!                    confusion (counts x counts, row n-hat, column true n), median_score_quantile,
//!                    sd_score_quantile (per bin of 4 counts of n-hat); attributes
//!                    line_error_scale, records (of the class), pooled (1: learnt from all records)
//!   /records/        one entry per simulated record: truth, raw estimate, naive counts;
//!                    flat k lists with offsets (true_stiffness / true_offset, stiffness,
//!                    log_stiffness_se / estimate_offset)
//! bank_format_version 5 (4 without line_se_bound and 3 with one set of maps are refused): every table carries its checksum, and so do the numeric
//! attributes of /atoms and /maps (io/checksummed_tables.hpp); every reader verifies them
//! all, so a damaged bank is refused naming the table, never used. Format 1 (the old atom
//! table, no checksums) and format 2 (the old atom table with checksums) are refused with
//! the advice to make the bank again.
#include <string>

#include "inverse/calibration_run.hpp"

namespace stengmc {

void write_calibration_bank(const std::string& path, const CalibrationBank& bank);

//! What `invert` needs of a bank: its identity, atoms and maps (records are not read).
struct StoredBank {
  std::string path;
  BankIdentity identity;
  std::string git_revision;
  std::string created_utc;
  AtomShapeData atoms;
  CalibrationMaps maps;
};

//! Reads a bank (in a child process only: io/guarded_read.hpp), verifying every checksum.
//! @throws InputError naming the file when it is not a regular file, not a stengmc
//! calibration bank of this format, or damaged (naming the table whose checksum fails).
StoredBank read_calibration_bank(const std::string& path);

//! What a bank was made from (its identity alone).
BankIdentity bank_identity_of(const std::string& path);

//! The whole bank back, records included, for refitting its maps without simulating again
//! (`stengmc calibrate --refit`): `setup` must be the one the bank was made for.
CalibrationBank read_calibration_bank_records(const std::string& path, const InverseSetup& setup);

}  // namespace stengmc
