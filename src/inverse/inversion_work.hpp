#pragma once
//! What `invert` and `calibrate` will cost, estimated before they start, in run's terms
//! (pipeline/work_estimate.hpp) and checked against the same limits (docs/faults.md,
//! "Limits"). The forward runs an inversion makes — the atoms' and a calibration's records —
//! are costed by run's own estimate of the runs they are (estimate_run of the device study
//! they stand for, inverse/device_checks.hpp); the estimator, the records held and the bank
//! by the per-item costs below, measured on this code. Whoever changes what the estimator
//! keeps per sample or does per atom updates them here.
#include <cstddef>

#include "inverse/calibration_run.hpp"
#include "pipeline/study.hpp"
#include "pipeline/work_estimate.hpp"

namespace stengmc {

// ---------------------------------------------------------------- per-item costs

//! Memory of one record's estimator (one per thread) per sample [bytes]: the line
//! proposals' 8x zero-padded FFT in and out (~130), their per-bin tables, the noise and
//! naive-count spectra, the record model's and the line search's buffers. Measured: invert
//! peaks grow by ~550 bytes per sample (8 atoms, atoms built on one thread), 5001 to 80001
//! samples.
inline constexpr double ESTIMATOR_BYTES_PER_SAMPLE = 400;
//! ... and per sample and atom of the prior's largest count, plus one [bytes]: the line
//! search's Jacobian and its trial copy, the full Jacobian of the orders the posterior weighs.
inline constexpr double ESTIMATOR_BYTES_PER_SAMPLE_ATOM = 24;
//! Estimator steps per sample and atom of the prior's largest count, plus one: measured
//! 1.0-1.2 us of CPU per (sample x atom) over 2001-5001 samples and counts 1-3, 1-8 and
//! 1-16 (~11 steps of ~100 ns), doubled for records that use the whole count range.
inline constexpr double ESTIMATOR_STEPS_PER_SAMPLE_ATOM = 20;
//! Forward runs of the atoms' search for their softest valid stiffness (tribology only,
//! head-long or shorter): doublings and a bisection to 0.1 % in ln k.
inline constexpr double VALID_RANGE_RUNS = 24;
//! Memory a calibration keeps per record until its bank is written [bytes]: the record's
//! estimate (posterior, lines, naive counts) in the journal's record, its sample, its row in
//! the file being written. Measured: ~4.3 kB per record for 1-3 asperities.
inline constexpr double BANK_BYTES_PER_RECORD = 4000;
//! ... and per asperity of the prior's largest count [bytes].
inline constexpr double BANK_BYTES_PER_RECORD_ATOM = 500;
//! Memory `invert` keeps per sample of each record [bytes]: times and voltage as read, the
//! fitted model, and their copies in the output file (FILE_BYTES_PER_VALUE each).
inline constexpr double INVERT_BYTES_PER_RECORD_SAMPLE = 24 + 3 * FILE_BYTES_PER_VALUE;

// ---------------------------------------------------------------- the estimate

struct InversionWork {
  std::size_t records = 1;         //!< records inverted (invert), or simulated and inverted (calibrate)
  int threads = 1;                 //!< records in flight at once (and the atoms' forward runs)
  bool builds_atoms = true;        //!< false: a calibration bank brings them
  bool simulates_records = false;  //!< calibrate: every record is a forward run of up to count_max asperities
};

//! The estimate of inverting (or calibrating) `work.records` records of `setup`'s grid with
//! the device of `known`.
WorkEstimate estimate_inversion(const Study& known, const InverseSetup& setup, const InversionWork& work);

//! Reading a record file of `bytes` bytes, before its grid is known: a CSV row `t,V` takes at
//! least 4 bytes, and the values read take 16 bytes per row (twice that while they grow).
WorkEstimate estimate_record_reading(double bytes);

}  // namespace stengmc
