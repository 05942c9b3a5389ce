#include "inverse/inversion_work.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/format.hpp"
#include "inverse/atom_library.hpp"
#include "inverse/fit_layout.hpp"
#include "inverse/load_prior.hpp"
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
  // The shapes: one short forward run per node of (Pi, zeta) the prior reaches, in a frame
  // where a radian is 100 ns; each costs at most the longest's.
  const auto [softest, stiffest] = simulated_stiffness_range(setup.prior);
  const LoadPrior loads(setup.prior);
  const AtomCoverage coverage = atom_coverage(softest, stiffest, fit_layout(setup.prior, setup.device, loads));
  const FrictionRatios ratios(setup.device);
  const AtomShapeWork shapes = atom_shape_work(atom_shape_range(setup.device, ratios.reference(), coverage));
  const double reference_k = setup.device.asperity.mass_kg * 1e14;  // omega0 = 1e7 rad/s
  const RecordGrid node_grid{0.0, setup.grid.step_s,
                             std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(shapes.longest_rad * 1e-7 / setup.grid.step_s)))};
  const WorkEstimate node = forward_run(known, setup, reference_k, 1, node_grid);
  const double runs = static_cast<double>(shapes.runs) + VALID_RANGE_RUNS;
  e.add_steps("atoms: " + count(runs) + " forward runs of up to " + count(static_cast<double>(node_grid.samples)) + " samples",
              runs * node.steps);
  // The shapes' runs take every thread OpenMP gives, whatever -j says.
  const double parallel = std::min<double>(std::max(work.threads, omp_get_max_threads()), runs);
  e.add_memory("atoms: " + count(parallel) + " forward runs at once", parallel * node.memory_bytes);
  // The shapes (two rows of ~800 values per node) and the envelopes (three dampings x ~200
  // loads x the record).
  e.add_memory("atoms: " + count(static_cast<double>(shapes.runs)) + " shapes and the envelopes of the record's " +
                   count(static_cast<double>(setup.grid.samples)) + " samples",
               16.0 * 1600.0 * static_cast<double>(shapes.runs) + 8.0 * 600.0 * static_cast<double>(setup.grid.samples));
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
