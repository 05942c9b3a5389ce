#include "inverse/inversion_work.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/format.hpp"
#include "inverse/atom_table.hpp"
#include "inverse/device_checks.hpp"

namespace stengmc {

namespace {

std::string count(double n) { return format_number(std::round(n)); }

//! run's estimate of one forward run of the device: `asperities` asperities of stiffness k
//! on `grid` (its memory without the program's own, which the whole estimate counts once).
WorkEstimate forward_run(const Study& known, const InverseSetup& setup, double k, std::size_t asperities,
                         const RecordGrid& grid) {
  const std::vector<double> stiffness(asperities, k);
  WorkEstimate e = estimate_run(device_study_at(known, setup.device, stiffness, grid), -1.0, false);
  e.memory_bytes -= BASE_BYTES;
  return e;
}

void add_atoms(const Study& known, const InverseSetup& setup, const InversionWork& work, WorkEstimate& e) {
  // The stiffest asperity is the fastest run (the most periods); the table costs at most as
  // much as if every run were of it.
  const auto [softest, stiffest] = simulated_stiffness_range(setup.prior);
  const RecordGrid& grid = setup.grid;
  const AtomTableRuns runs = atom_table_runs(setup.device, grid, softest, stiffest);
  const WorkEstimate full = forward_run(known, setup, stiffest, 1, grid);
  const WorkEstimate head =
      forward_run(known, setup, stiffest, 1, RecordGrid{grid.start_s, grid.step_s, std::max<std::size_t>(runs.head_samples, 2)});
  const double short_runs = static_cast<double>(runs.heads) + VALID_RANGE_RUNS;
  e.add_steps("atoms: " + count(static_cast<double>(runs.full)) + " forward runs of " + count(static_cast<double>(grid.samples)) +
                  " samples and " + count(short_runs) + " of " + count(static_cast<double>(runs.head_samples)),
              static_cast<double>(runs.full) * full.steps + short_runs * head.steps);
  // The table's forward runs take every thread OpenMP gives, whatever -j says.
  const double parallel = std::min<double>(std::max(work.threads, omp_get_max_threads()), static_cast<double>(runs.full));
  e.add_memory("atoms: " + count(parallel) + " forward runs at once of " + count(static_cast<double>(grid.samples)) + " samples",
               parallel * full.memory_bytes);
  e.add_memory("atoms: " + count(static_cast<double>(runs.heads)) + " heads of " + count(static_cast<double>(runs.head_samples)) +
                   " samples, and the envelope",
               16.0 * static_cast<double>(runs.heads * runs.head_samples) + 16.0 * static_cast<double>(grid.samples));
}

}  // namespace

WorkEstimate estimate_inversion(const Study& known, const InverseSetup& setup, const InversionWork& work) {
  WorkEstimate e;
  const double samples = static_cast<double>(setup.grid.samples);
  const double records = static_cast<double>(work.records);
  const double atoms = static_cast<double>(setup.prior.count_max) + 1.0;
  const double threads = std::min<double>(std::max(work.threads, 1), std::max(records, 1.0));
  e.samples = samples;
  e.asperities = static_cast<double>(setup.prior.count_max);
  e.add_memory("program", BASE_BYTES);
  if (work.builds_atoms) add_atoms(known, setup, work, e);
  e.add_memory("estimators: " + count(threads) + " at once x " + count(samples) + " samples x " + count(atoms) + " atoms",
               threads * samples * (ESTIMATOR_BYTES_PER_SAMPLE + ESTIMATOR_BYTES_PER_SAMPLE_ATOM * atoms));
  e.add_steps("estimation: " + count(records) + " records x " + count(samples) + " samples x " + count(atoms) + " atoms",
              records * samples * atoms * ESTIMATOR_STEPS_PER_SAMPLE_ATOM);
  if (!work.simulates_records) {
    e.add_memory(count(records) + " records x " + count(samples) + " samples", records * samples * INVERT_BYTES_PER_RECORD_SAMPLE);
    return e;
  }
  // A calibration's record: a forward run of up to count_max asperities (the stiffest, the
  // dearest), its traces kept for the estimator, then its estimate kept in the bank.
  const double stiffest = simulated_stiffness_range(setup.prior).second;
  const WorkEstimate record = forward_run(known, setup, stiffest, setup.prior.count_max, setup.grid);
  e.add_steps("simulation: " + count(records) + " records of up to " + count(e.asperities) + " asperities", records * record.steps);
  e.add_memory("simulation: " + count(threads) + " records at once of up to " + count(e.asperities) + " asperities",
               threads * (record.memory_bytes + 4.0 * 8.0 * samples));
  e.add_memory("bank: " + count(records) + " records of up to " + count(e.asperities) + " asperities",
               records * (BANK_BYTES_PER_RECORD + BANK_BYTES_PER_RECORD_ATOM * e.asperities));
  return e;
}

WorkEstimate estimate_record_reading(double bytes) {
  WorkEstimate e;
  const double rows = bytes / 4.0;
  e.samples = rows;
  e.add_memory("program", BASE_BYTES);
  e.add_memory("up to " + count(rows) + " samples read", rows * 32.0);
  return e;
}

}  // namespace stengmc
