#pragma once
//! The statistics of an ensemble with 95 % confidence intervals (docs/ensembles.md):
//! every per-realisation scalar over the valid realisations, the pooled identifiability
//! ratios, the fraction of valid realisations, and which realisations broke and why.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ensemble/ensemble_runner.hpp"
#include "ensemble/realisation_record.hpp"
#include "stats/ensemble_statistics.hpp"

namespace stengmc {

struct EnsembleSummary {
  std::size_t realisations = 0;                      //!< run
  std::size_t valid = 0;                             //!< kept in the statistics
  Interval valid_fraction;                           //!< Wilson
  std::array<ScalarSummary, SCALAR_COUNT> scalars;   //!< over the valid realisations
  //! Sum of identifiable over sum of sliding asperities (a pooled ratio: realisations with
  //! more sliding asperities weigh more, unlike the mean of fft_ratio); paired bootstrap.
  Interval fft_pooled_ratio;
  Interval hr_pooled_ratio;
  std::vector<std::pair<std::uint64_t, std::string>> invalid;  //!< id and reason
};

//! Bootstrap draws come from the study's bootstrap stream, one index per statistic, so
//! the summary is a function of the records and the seed alone.
EnsembleSummary summarise_ensemble(const std::vector<RealisationRecord>& records, std::uint64_t seed);

//! The table printed at the end of a run.
std::string format_ensemble_summary(const EnsembleSummary& summary, const EnsembleRun& run);

}  // namespace stengmc
