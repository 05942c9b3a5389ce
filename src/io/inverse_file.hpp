#pragma once
//! The output of `stengmc invert` (docs/inverse.md, output), file_type
//! "stengmc-inverse". S records, C counts of the prior, L identified lines in all:
//!   root attributes   provenance (the --known study's file and text), bank (path, "" without),
//!                     bank_identity_hash, bank_git_revision, calibrated (0/1), records (S)
//!   /inverse/records/name (S), noise_sigma_v, residual_sigma_v, signal_to_noise_db,
//!                     band_power_ratio, lines_outside_prior, seconds, verdict, warnings (S)
//!   /inverse/count/   counts (C), estimate, interval_low, interval_high, naive_fft (S),
//!                     probability, raw_probability (S x C)
//!   /inverse/lines/   record (L: which record), stiffness_n_per_m, stiffness_low,
//!                     stiffness_high, log_stiffness_se, frequency_hz, amplitude_v,
//!                     nearest_separation_hz (L); offset (S + 1)
//!   /inverse/stiffness/ median, median_low, median_high, sd_log, sd_log_low, sd_log_high,
//!                     intervals_calibrated (S); laws/ (3 S rows, best AIC first per record):
//!                     record, family, first, first_low, first_high, second, second_low,
//!                     second_high, aic, delta_aic, median, sd_log, fitted
//!   /inverse/pooled/laws/  the same for all records' lines together (3 rows)
//!   /inverse/traces/record_<i>/{time, voltage, model}  the first 16 records (figures)
#include <string>
#include <vector>

#include "inverse/inversion.hpp"

namespace stengmc {

struct InverseFileContext {
  std::string known_file, known_text;
  std::string bank_path;                 //!< "" without a bank
  std::uint64_t bank_identity_hash = 0;
  std::string bank_git_revision;
  std::vector<std::vector<double>> times;  //!< each record's times (for the kept traces)
  std::vector<std::vector<double>> voltages;
};

void write_inverse_file(const std::string& path, const InverseFileContext& context, const std::vector<Inversion>& inversions,
                        const std::vector<LawFit>& pooled);

}  // namespace stengmc
