#pragma once
//! The search for the atoms of n sliding asperities, for every n near the best one
//! (docs/inverse.md, "the search").
//!
//! Each atom's amplitude and phase follow from its stiffness, load and onset and the known
//! device, so a record is fitted by choosing those alone: greedy additions (the best proposal,
//! line_proposals.hpp) each followed by a Levenberg–Marquardt fit (record_fit.hpp) of the new
//! atom and its neighbours — within 8 line widths in frequency, or breaking away within a
//! few microseconds of it. Two asperities too close to tell apart add up to twice an atom,
//! which no single atom explains: the count stays identifiable where frequency resolution is
//! lost, and the greedy step adds the second one. The orders the posterior weighs (the greedy
//! count -1 .. +extra) are then refitted in full, the device's shared parameters with them.
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "inverse/line_proposals.hpp"
#include "inverse/noise_judge.hpp"
#include "inverse/record_fit.hpp"

namespace stengmc {

//! An order this far (in chi^2: RSS / sigma^2 plus the loads' prior) above the best has a
//! posterior weight below e^{-500} of the best's: LineSearch::refit refits it with a few steps
//! only, and the nested searches do not offer it as a start (nested_search.cpp).
inline constexpr double HOPELESS_CHI2_GAP = 1000.0;

struct LineSearchOptions {
  std::size_t max_iterations = 60;   //!< per Levenberg–Marquardt refinement
  //! The greedy path stops when the best addition, jointly refitted, lowers the squared
  //! residual by less than this fraction of its atom's energy (a true atom lowers it by about
  //! its energy, one that is not there raises it by as much).
  double stop_fraction = 0.25;
  std::size_t extra_orders = 2;      //!< orders fitted past the greedy stop (for the count's posterior)
  std::size_t candidates = 4;        //!< proposals tried at each step
  std::size_t reseat_sweeps = 2;
};

//! Puts `seeded`, the fit of a start found beside a search (a nested order, the onset steps),
//! among that search's `fits` (index n: n atoms): one order past the last is appended (the
//! orders stay consecutive), an order there is replaced where the start reached a better
//! optimum (RSS / sigma_v^2 plus the loads' penalty), one further on is dropped.
void keep_better_start(std::vector<OrderFit>& fits, OrderFit seeded, double sigma_v);

class LineSearch {
 public:
  //! `judge` says which fits explain the record to its noise (those are not re-seated).
  LineSearch(RecordFit& fit, LineProposals& proposals, const LineSearchOptions& options = {}, NoiseJudge judge = {});

  //! Fits for n = 0 (no atom) along the greedy path to its stop, then `extra_orders` more,
  //! and on to `min_count` at least, never beyond `max_count`: index n holds the fit with n
  //! atoms; those from the greedy count -1 on are refitted in full (shared parameters too).
  //! `start` holds the shared parameters to begin with (its atoms are ignored).
  std::vector<OrderFit> search(const FitState& start, std::size_t max_count, std::size_t min_count = 0);

  //! The refits in full of `fits` from index `first` on (after the noise model changed).
  void refit(std::vector<OrderFit>& fits, std::size_t first);

  //! A fit of this search's layout from a start found elsewhere (the nested model's fit of an
  //! order, nested_search.hpp): refitted in full; its atoms' placements chosen again (replace)
  //! while that improves it, up to reseat_sweeps times; its atoms re-seated (reseat) as the
  //! greedy path's own orders are; and refitted in full again.
  OrderFit polish(FitState start);

  //! A start from the record's onset steps (inverse/onset_steps.hpp; `onsets_s` once per
  //! asperity, a step of two units twice): one atom per onset, added greedily as `search` adds
  //! them but each at an onset not yet taken, its k the best the map and the golden section
  //! find there, refitted with its neighbours; then polished. The greedy path's own atoms
  //! start where the tail's phase and the plateau score best, which with a crowd of lines
  //! unexplained is often a period off an onset; these start on them.
  OrderFit place_at_steps(const FitState& start, const std::vector<double>& onsets_s);

 private:
  //! Whether `fit` explains the record to its noise (noise_judge.hpp).
  [[nodiscard]] bool fits_noise(const OrderFit& fit) const { return judge_.fits(*fit_, fit); }
  //! The best addition to `fit`, refined in ln k by golden section on its exact score; with
  //! `only_at_steps`, the best placed at one of those onsets (place_at_steps).
  LineCandidate best_addition(const OrderFit& fit, const std::vector<double>* only_at_steps = nullptr);
  //! The voltage of `atom` alone at unit amplitude (the record model of it alone).
  [[nodiscard]] std::vector<double> unit_voltage(const AtomParameters& atom, double damping_rate_per_s) const;
  //! Which atoms of `state` move with the new one (the last): neighbours in frequency or in breakaway.
  std::vector<bool> neighbours(const FitState& state) const;
  //! Re-seats each atom in turn: removed, the best proposal on what it leaves, refitted with
  //! its neighbours, kept when the fit improves. A greedy path can give an atom another's
  //! onset, or its own a whole period off (the tail's phase alike, the plateau a little
  //! apart), which no local fit undoes; with the other atoms in place the proposal sees its
  //! atom alone. Up to `sweeps` passes, while one improves.
  void reseat(OrderFit& fit, std::size_t sweeps);
  //! `fit` with atom `own` taken out (`without`, whose linear parameters are solved) gets the
  //! first of `candidates` that scores above own's `current` and whose refit with its
  //! neighbours lowers the misfit. Returns whether one did.
  bool put_back(OrderFit& fit, const FitState& without, const AtomParameters& own, const LineCandidate& current,
                std::span<const LineCandidate> candidates);
  //! Exchanges onsets (and, with a load per atom, loads) between two atoms, any two: a greedy
  //! path gives an atom the onset of another asperity whose plateau it met first, so the set
  //! of onsets the low band pins is right but not which line has which, and moving one atom's
  //! onset alone costs a plateau for what its tail gains. Every pair is screened on the raw
  //! residual, each moved atom's onset touched up over one period (its tail's phase); the
  //! best few are refitted and the first that lowers the misfit kept, while one does.
  //! Returns whether one was kept.
  bool exchange(OrderFit& fit);
  //! Each atom's placement (onset and load, as the layout frees them; its k held) chosen again
  //! on the residual without it: an early atom took its place on a record that held all the
  //! others' plateaus and first cycles, which pull the placement a whole tail period off (a
  //! load whose breakaway comes a period late, an onset on another's plateau). Kept where the
  //! refit with its neighbours lowers the misfit.
  void replace(OrderFit& fit);
  //! Every atom's breakaway read off the record's tail, all lines at once: past the last head
  //! the record is a sum of free oscillations at the atoms' known frequencies, linear in each
  //! one's quadrature pair, so a joint least-squares solve separates lines whose tails overlap
  //! (the greedy path and the placements above score one atom at a time, against every other
  //! asperity's tail). Each atom's onset is moved so its tail matches its share; all refitted,
  //! placements chosen again (replace). Kept where that lowers the misfit.
  bool tail_solve(OrderFit& fit);
  //! Atoms whose onsets lie within TRADE_WINDOW_S of each other (and more than a tenth of a
  //! period apart) trade onsets, two or three at a time, each keeping its breakaway to within a
  //! whole period (its load set again so that it breaks away there; the tail's phase pins the
  //! breakaway only so): the tail pins each breakaway, but an onset and a load trade against each other along
  //! it (t_b = t_on + tau(N, k)), so a greedy path can give a cluster of asperities each
  //! other's onsets, their loads bent to keep their tails, which no move of one atom or of one
  //! atom's onset alone undoes. Only the heads change; each trade is refitted with its atoms
  //! and kept where the misfit falls. Returns whether one was kept.
  bool trade_onsets(OrderFit& fit);
  //! Two atoms within a line width of each other exchange onsets and loads and are refitted,
  //! their k's free: close lines' k's must cross for their onsets to trade places, which
  //! exchange's screening (k held) scores as a loss. Kept where the misfit falls.
  bool cross(OrderFit& fit);
  //! The inverse of split: two atoms within a line width of each other that share one
  //! asperity's line (one atom's breakaway and amplitude patched by a second at the same k)
  //! while another asperity is missing, which no local fit undoes. The weaker of the pair is
  //! taken out, the rest refitted in full, the best addition on that residual put in and all
  //! refitted; kept where that lowers the misfit. The closest few pairs are tried. Returns
  //! whether one was kept.
  bool merge(OrderFit& fit);
  //! Two asperities within a line width or two of each other, fitted as one atom, with the
  //! greedy path's next atom spent elsewhere (no single atom added beside the merged one
  //! explains the pair): the best fit with one of `fit`'s atoms split in two (half a line
  //! width either side, each keeping the load and onset), the most promising splits by their
  //! scores refitted with their neighbours; and, for pairs a fraction of a line width apart,
  //! whose split scores badly whatever it is, the atoms with the most residual power around
  //! their line split an eighth of a width either side and refitted. None when `fit` fits to
  //! the noise or has no atom.
  std::optional<OrderFit> split(const OrderFit& fit);

  RecordFit* fit_;
  LineProposals* proposals_;
  LineSearchOptions options_;
  NoiseJudge judge_;
};

}  // namespace stengmc
