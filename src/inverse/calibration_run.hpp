#pragma once
//! A calibration: the prior's records simulated with the ensemble runner (reproducible by
//! seed, journalled, OpenMP, bitwise identical for any thread count), the estimator applied
//! to each noisy record as it finishes, the maps fitted (docs/inverse.md,
//! `stengmc calibrate`).
#include <string>
#include <vector>

#include "inverse/atom_table.hpp"
#include "inverse/bank_identity.hpp"
#include "inverse/calibration_maps.hpp"
#include "inverse/calibration_sample.hpp"
#include "pipeline/study.hpp"
#include "pipeline/work_estimate.hpp"

namespace stengmc {

//! Everything the inversion of a device needs before it sees a record: the device, its
//! prior, the grid, the atoms (and, from a calibration, the maps).
struct InverseSetup {
  KnownDevice device;
  InversePrior prior;
  RecordGrid grid;
  BankIdentity identity;
};

//! The known device and prior of a `--known` study, for records on `grid` (the study's own
//! grid when nullopt). Checks that the sample rate resolves the prior's highest line.
//! @throws InputError naming the study for a missing known parameter or a bad [inverse].
InverseSetup inverse_setup(const Study& study, std::optional<RecordGrid> grid = std::nullopt);

//! The stiffness range the atoms cover: the prior's 1e-4 .. 1 - 1e-4 quantiles widened by
//! 1.25 each way, cut below where an asperity would reach its element's length [N/m].
std::pair<double, double> atom_range(const InverseSetup& setup);

//! The rms voltage of one sliding asperity of the prior's central stiffness (the geometric
//! mean of its 1e-4 and 1 - 1e-4 quantiles) over the record [V]: the scale a record of no
//! sliding asperity takes its noise level from, and the amplitude checks compare with.
double one_asperity_rms_v(const AtomTable& atoms, const InversePrior& prior);

struct CalibrationBank {
  InverseSetup setup;
  std::string device_study_file, device_study_text;
  std::string prior_study_text;             //!< the ensemble study the records came from
  AtomTableData atoms;
  CalibrationMaps maps;
  std::vector<CalibrationSample> samples;   //!< every record, valid or not, by id
  std::size_t resumed = 0;                  //!< records recovered from an interrupted run
  double seconds = 0.0, atom_seconds = 0.0; //!< wall time in all, of which building the atoms
  double cpu_seconds = 0.0;                 //!< CPU time of the records (all threads; without the atoms)
  double estimation_cpu_seconds = 0.0;      //!< of which the estimator's (the rest: forward simulation)
  int threads = 1;
  //! An MPI rank other than 0 (ensemble/process_world.hpp): it computed records for rank 0
  //! and holds none; only rank 0's bank is complete and written.
  bool worker = false;
};

struct CalibrationOptions {
  int threads = 0;               //!< 0: OpenMP's default
  bool restart = false;          //!< discard an interrupted run's journal
  bool show_progress = true;
  std::optional<std::size_t> records;        //!< override [inverse] calibration_records
  std::optional<std::uint64_t> seed;         //!< override [inverse] seed
  //! The whole calibration's estimate (inverse/inversion_work.hpp) is refused over these
  //! before anything runs, and each record's run is held to them as an ensemble's is.
  WorkLimits limits{};
  LimitNames limit_names{};                  //!< how the caller raises them (messages)
};

//! Runs the calibration of `device_study`; finished records go to `journal_path` (the caller
//! removes it once the bank is written).
CalibrationBank run_calibration(const Study& device_study, const std::string& journal_path, const CalibrationOptions& options);

}  // namespace stengmc
