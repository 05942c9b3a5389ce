#pragma once
//! The Monte Carlo runner: realisations of a study in parallel (OpenMP), each a unit of
//! work computable from the study and its id alone, kept in a crash-safe journal so a
//! killed run resumes where it stopped (docs/ensembles.md).
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ensemble/journal.hpp"
#include "ensemble/realisation_record.hpp"
#include "ensemble/shard_spec.hpp"
#include "ensemble/study_file.hpp"
#include "pipeline/work_estimate.hpp"

namespace stengmc {

//! The most threads a command or the Python module starts: far above any machine's cores
//! (extra threads only wait), far below what makes the thread library fail to start them
//! (100 000 crashed the Python module).
inline constexpr int MAX_THREADS = 1024;

struct EnsembleOptions {
  std::string progress_label = "ensemble";  //!< e.g. "point 3/14" in a sweep
  int threads = 0;                     //!< 0: OpenMP's default (OMP_NUM_THREADS or the cores)
  std::optional<std::uint64_t> only{};  //!< run this realisation alone (no journal)
  bool restart = false;                //!< discard an existing journal instead of resuming it
  bool show_progress = true;           //!< progress bar with ETA and running statistics
  WorkLimits limits{};                 //!< a realisation over them is recorded invalid (run_realisation)
  //! Run only this slice of the realisations (and keep only its records from a journal);
  //! not with a target (a slice cannot see when the whole would have stopped).
  std::optional<ShardSpec> shard{};
  //! Part of a longer job (a sweep): when it started, and the job's fraction this run covers,
  //! [job_before, job_before + job_share]: the progress then gives the whole job's ETA too.
  std::optional<std::chrono::steady_clock::time_point> job_start{};
  double job_before = 0.0, job_share = 1.0;
  //! Called as each realisation's record is delivered, one call at a time (under the runner's
  //! lock, in the delivering thread): how many this run has finished and how many it runs
  //! (resumed ones excluded; with a target it may stop short). The Python module passes a
  //! callable through it: a notebook cell does not show stderr, where show_progress draws.
  std::function<void(std::size_t done, std::size_t total)> on_record{};
};

//! A caller's own reduction of every realisation, run in the worker thread as each record
//! finishes and before it is journalled (the inverse calibration estimates from the noisy
//! trace, adds extras and drops the traces). It must depend on the record alone, so the
//! results stay independent of threads and interruptions.
struct RealisationHook {
  std::function<void(RealisationRecord&)> apply;
  bool needs_traces = false;   //!< every realisation keeps its traces for `apply` (which may drop them)
  std::string identity;        //!< what `apply` depends on besides the study (hashed into the journal identity)
};

struct EnsembleRun {
  std::vector<RealisationRecord> records;  //!< every realisation run, by id
  std::uint64_t requested = 0;             //!< [ensemble] realisations (the cap, with a target)
  bool stopped_at_target = false;          //!< the target half-width was reached before the cap
  //! With a target: the final 95 % CI half-width of the target's mean, and whether it met
  //! the goal (false also when the cap came first).
  double target_half_width_reached = 0.0;
  bool target_met = false;
  std::size_t resumed = 0;                 //!< records recovered from an interrupted run
  double seconds = 0.0;                    //!< wall time of this invocation [s]
  int threads = 1;                         //!< threads used
  std::optional<std::uint64_t> only;       //!< the one realisation run (--only), if so
  //! In a distributed run (MPI), this rank only computed realisations for rank 0: it holds
  //! no records and writes nothing.
  bool worker = false;
  //! Merged by `merge --partial` from an unfinished run: some of the requested are missing.
  bool partial = false;
};

//! Everything that determines an ensemble's results, hashed: the study and surface texts,
//! the program version and git revision. A journal written under another hash is refused.
std::uint64_t ensemble_identity_hash(const Study& study);

//! The identity of the journal of `study` (one grid point's study), as run_ensemble opens
//! it: its hash (with the hook's identity) and "stengmc VERSION (git REV), study FILE", or
//! for a `--shard i/n` run "stengmc VERSION (git REV; shard i/n), study FILE". The shard is
//! in the description only, not the hash: a resume under another slice keeps the records
//! (each is the same computation whoever ran it) and runs what its own slice still lacks.
JournalIdentity ensemble_journal_identity(const StudyFile& study, const RealisationHook& hook = {},
                                          const std::optional<ShardSpec>& shard = std::nullopt);

//! The study file named in the description of an ensemble journal, or "" when it names none.
std::string journal_study_file(const std::string& description);

//! The shard (--shard i/n) whose run wrote an ensemble journal, from its description;
//! nullopt for a whole run's journal (and for journals written before stengmc recorded
//! it). InputError saying what was expected when the description names a shard that is not i/n.
std::optional<ShardSpec> journal_shard(const std::string& description);

//! The target rule looks at no fewer valid realisations than this: a CI from a handful
//! can be narrow by chance (or zero-wide for a statistic that has not varied yet).
inline constexpr std::size_t MIN_REALISATIONS_FOR_TARGET = 30;

//! Runs `study` (read without a realisation; it must have [ensemble]). Completed
//! realisations are appended to the journal at `journal_path` as they finish; on success
//! the caller writes the output and then removes the journal. Realisations are processed
//! in batches of [ensemble] batch ids when a target is set, so the stopping point is the
//! same for any number of threads.
//!
//! In a distributed run (ensemble/process_world.hpp) every rank calls this for the same
//! study: rank 0 journals, hands the realisations out (ensemble/work_distribution.hpp) and
//! returns every record as a single process would; the other ranks return a run marked
//! `worker`, without records.
EnsembleRun run_ensemble(const StudyFile& study, const std::string& journal_path, const EnsembleOptions& options,
                         const RealisationHook& hook = {});

}  // namespace stengmc
