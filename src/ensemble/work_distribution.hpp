#pragma once
//! Realisations over MPI ranks (docs/ensembles.md; docs/cluster.md). Rank 0 keeps the
//! queue of realisation ids of the current batch and hands them out one at a time to
//! whichever thread asks first: its own OpenMP threads take them from the queue directly,
//! every OpenMP thread of the other ranks asks over MPI (sending its finished record with
//! the next request). This is dynamic load balancing at the grain of one realisation: a
//! rank that drew ten expensive realisations simply asks less often. The results do not
//! depend on who computed what, because a record depends on (study, seed, id) alone and
//! rank 0 orders them by id; rank 0 journals every record as it arrives, so a killed job
//! resumes with any number of ranks.
//!
//! Without MPI in the build, or in a run of one process, nothing here is used.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "ensemble/realisation_record.hpp"

namespace stengmc {

//! Computes the record of one realisation id (run, hook applied).
using ComputeRecord = std::function<RealisationRecord(std::uint64_t)>;
//! Takes finished records (journal, progress, results); called from several threads. Rank 0
//! passes the records that arrived together at once, so it journals them with one fsync.
using DeliverRecords = std::function<void(std::vector<RealisationRecord>&&)>;

//! Rank 0's side, for one ensemble (one grid point): construct it on rank 0 while every
//! other rank calls serve_realisations for the same ensemble.
class WorkDistributor {
 public:
  WorkDistributor();
  //! Stops serving; without finish() (an error unwinding) the other ranks are left waiting
  //! and the caller ends the job (abort_every_process).
  ~WorkDistributor();
  WorkDistributor(const WorkDistributor&) = delete;
  WorkDistributor& operator=(const WorkDistributor&) = delete;

  //! Runs `ids` on `threads` local threads and every remote thread; returns when every
  //! record was delivered. A failure anywhere is rethrown here (a remote one as the same
  //! kind of error, with the rank named).
  void run(const std::vector<std::uint64_t>& ids, int threads, const ComputeRecord& compute,
           const DeliverRecords& deliver);

  //! Tells every remote thread the ensemble is over (once each has asked for more work).
  void finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

//! A rank other than 0: runs the realisations rank 0 hands out on `threads` threads and
//! sends their records back, until rank 0 says the ensemble is over.
void serve_realisations(int threads, const ComputeRecord& compute);

}  // namespace stengmc
