#pragma once
//! What a calibration bank was made from, and its hash: a bank is valid only for the same
//! known device, prior, record grid and estimator (docs/inverse.md, "banks").
#include <cstdint>
#include <string>

#include "inverse/inverse_prior.hpp"
#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! Bumped whenever the estimator's results change for the same inputs: banks made by another
//! estimator version are refused (their calibration describes another estimator).
//! 2: a broadened prior's search also starts from its nested models' fits (the ideal device,
//! loads alone, onsets alone: nested_search.hpp).
//! 3: the coloured noise's spectrum fitted with weights from its model (noise_whitening.cpp);
//! nested models judged against that noise; atoms re-seated in every order that does not fit
//! to the noise (fitting_chi2, noise_judge.hpp), not only above 1.5 M sigma^2.
//! 4: under a prior of coloured noise the search's re-seating also judges its fits whitened
//! (NoiseJudge), as the nested searches already did; narrow splits (LineSearch::split).
//! 5: a fit fits to its noise only if no tenth of its residual holds more than the noise
//! allows (residual_segments.hpp), not only its chi^2.
//! 6: re-seating also crosses close atoms' onsets and loads with their k's free, and merges
//! close atoms to free one for a missing line (LineSearch::cross, LineSearch::merge).
//! 7: re-seating first solves every atom's tail jointly for its breakaway (LineSearch::tail_solve)
//! and trades onsets within clusters with the breakaways held (LineSearch::trade_onsets).
//! 8: contact onsets read off the record as steps (onset_steps.hpp) are tried as every atom's
//! placement, and a start with one atom at each is searched beside the greedy path
//! (LineSearch::place_at_steps).
//! 9: the broadened model's start from the steps only where no nested model fits the record to
//! its noise (lines move by <= 1e-6 relative on the staggered-onset family, counts do not).
//! 10: the broadened model's greedy additions and re-seats no longer try the onset steps; the
//! nested models' and the start from the steps still do.
inline constexpr int ESTIMATOR_VERSION = 10;

struct BankIdentity {
  std::string device;     //!< KnownDevice::describe()
  std::string prior;      //!< InversePrior::describe()
  std::string grid;       //!< "start_s = ..., step_s = ..., samples = ..."
  std::string estimator;  //!< program version and estimator version
  std::uint64_t hash = 0; //!< FNV-1a over the four

  //! What differs from `other`, in words ("" when nothing does).
  [[nodiscard]] std::string differences(const BankIdentity& other) const;
};

BankIdentity bank_identity(const KnownDevice& device, const InversePrior& prior, const RecordGrid& grid);

//! The device study's record grid (t = 0 .. duration_s at sample_rate_hz).
RecordGrid device_grid(const KnownDevice& device);

}  // namespace stengmc
