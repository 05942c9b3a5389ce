#pragma once
//! The nested priors' searches, run before a broadened prior's own (docs/inverse.md, "the
//! search"). A prior that frees each atom's load and onset contains simpler models as special
//! cases: the ideal device's (every asperity at the device's load, all in contact from the
//! onset range's start), loads alone free, onsets alone free. The broadened search often misses
//! the truth even where it is one of those: with a free load and onset per atom, an atom found
//! early takes a load and onset that trade a breakaway for a plateau, and weak low-load atoms
//! then patch its misfit (the held-out ideal family was counted exactly in 65 % of records
//! under the broadened prior, 100 % under the ideal one; a record of three asperities of loads
//! 0.4-1.35 x the device's, all from t = 0, got 16 atoms, and 3 under the prior of loads alone).
//! So the nested models are searched first, simplest first, each as its own prior's estimator
//! would search it, and the freer ones only while none fits the record to its noise: a simpler
//! model that explains a record to its noise is the one the evidence prefers (the freer model's
//! extra parameters buy nothing but their Occam factor), and then the broadened search itself is
//! not run. Each order a nested search refitted in full becomes a start for the broadened model's
//! fit of that order; the broadened fit of an order is replaced where a start reaches a better
//! optimum. The model and its posterior stay the broadened prior's: the nested searches choose
//! where to look, not what is believed.
#include <memory>
#include <span>
#include <vector>

#include "inverse/fit_layout.hpp"
#include "inverse/inverse_prior.hpp"
#include "inverse/line_proposals.hpp"
#include "inverse/line_search.hpp"
#include "inverse/noise_judge.hpp"
#include "inverse/load_prior.hpp"
#include "inverse/record_fit.hpp"
#include "inverse/record_model.hpp"

namespace stengmc {

//! The priors nested in `prior`, simplest first: every asperity at the device's load and in
//! contact from the onset range's start (the ideal device's, when the prior frees loads or
//! onsets), loads alone free and onsets alone free (when it frees both). The tolerance, noise
//! and offset as written. Empty for a prior that frees neither.
std::vector<InversePrior> nested_priors(const InversePrior& prior);

struct NestedFits {
  //! Of each model searched, the orders its search refitted in full (its count - 1 on) within
  //! reach of its best: starts for the broadened model's fits of those orders.
  std::vector<FitState> starts;
  //! Every order (index n: n atoms) of the first model whose best order fits the record to its
  //! noise (whitened RSS / M sigma^2 within 5 standard deviations of chi^2_M / M, i.e. at most
  //! 1 + 5 sqrt(2 / M)); empty when none does, and then the broadened search is needed. Under a
  //! prior of coloured noise the RSS is the one whitened by the noise spectrum fitted to that
  //! order's residual, against that spectrum's level, as the estimator itself will judge it.
  std::vector<FitState> fitted_orders;
};

class NestedSearch {
 public:
  NestedSearch(const RecordModel& model, const InversePrior& prior, const KnownDevice& device,
               const LineSearchOptions& options);
  ~NestedSearch();
  NestedSearch(const NestedSearch&) = delete;
  NestedSearch& operator=(const NestedSearch&) = delete;

  //! True when the prior has nested priors.
  [[nodiscard]] bool applies() const { return !levels_.empty(); }
  //! The record's onset steps, once per asperity (a step of two units twice), for the levels
  //! that free onsets: their proposals try them (LineProposals::set_step_onsets), and their
  //! search gets a start from them (LineSearch::place_at_steps) beside its own path.
  void set_step_onsets(const std::vector<double>& asperity_onsets_s);

  //! The nested models' fits of `voltage` (searched as white noise of level `sigma_v`),
  //! simplest first, as states of the broadened `layout` (a nested fit is a point of it).
  //! `whitened_level` (noise_judge.hpp) is used only when `layout` has coloured noise.
  [[nodiscard]] NestedFits search(std::span<const double> voltage, double sigma_v, const FitLayout& layout,
                                  std::size_t max_count, std::size_t min_count, const WhitenedLevel& whitened_level = {});

 private:
  struct Level;
  const RecordModel* model_;
  std::vector<std::unique_ptr<Level>> levels_;
  std::vector<double> step_asperities_s_;
  LineSearchOptions options_;
};

}  // namespace stengmc
