#include "inverse/line_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include <Eigen/Dense>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "spectral/amplitude_spectrum.hpp"

namespace stengmc {

namespace {
// Atoms within this many line widths of a new one, or breaking away within this time of it
// (their plateaus and first cycles overlap), are refitted with it on the greedy path.
constexpr double NEIGHBOURHOOD_WIDTHS = 8.0;
constexpr double NEIGHBOURHOOD_TIME_S = 2e-6;
// An order HOPELESS_CHI2_GAP above the best before the full refits is refitted with only
// HOPELESS_ITERATIONS steps (LineSearch::refit).
constexpr std::size_t HOPELESS_ITERATIONS = 5;
// The pair re-seat (LineSearch::exchange): PAIR_ONSETS placements proposed for each atom of a
// pair, every combination screened, the best EXCHANGES_REFITTED refitted.
constexpr std::size_t PAIR_ONSETS = 6;
constexpr std::size_t EXCHANGES_REFITTED = 3;
// Splits refitted by LineSearch::split (the best by their scores).
constexpr std::size_t SPLITS_REFITTED = 2;
// Placements tried for each atom by LineSearch::replace.
constexpr std::size_t REPLACEMENTS = 3;
// Narrow splits (LineSearch::split): the NARROW_SPLITS atoms with the most residual power within
// NARROW_BAND_WIDTHS line widths (d / pi in Hz) of their line, split NARROW_SPLIT_WIDTHS of a
// line width either side.
constexpr std::size_t NARROW_SPLITS = 2;
constexpr double NARROW_BAND_WIDTHS = 2.0;
constexpr double NARROW_SPLIT_WIDTHS = 0.125;
// Crosses and merges (LineSearch::cross, LineSearch::merge): pairs of atoms closer than this
// many line widths; merges try the closest MERGES_TRIED of them.
constexpr double MERGE_WIDTHS = 1.0;
constexpr std::size_t MERGES_TRIED = 3;
// The tail solve (LineSearch::tail_solve) reads the record this far past the latest breakaway
// the prior allows: the head's 30 rad (atom_shapes.hpp, psi_post) [rad].
constexpr double TAIL_SOLVE_HEAD_RAD = 30.0;
// Atoms whose onsets lie this close trade them (LineSearch::trade_onsets): the neighbourhood's
// time, within which plateaus and first cycles overlap.
constexpr double TRADE_WINDOW_S = NEIGHBOURHOOD_TIME_S;
// Each trading atom's breakaway is kept to within this many of its periods.
constexpr int TRADE_PERIODS = 1;
// ... and trades only with atoms whose onsets are more than this many periods apart.
constexpr double TRADE_MIN_PERIODS = 0.1;

double dot(std::span<const double> x, std::span<const double> y) {
  double s = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) s += x[k] * y[k];
  return s;
}

struct PlacedPair {
  AtomParameters first, second;
  double gain;  // how much lower than `rss` the residual is with the two in [V^2]
};
// Every combination of two atoms' placements (`placed[0]` x `placed[1]`, proposed on a residual
// of squared norm `without` that lacks both) scored jointly, their overlap counted (close lines'
// tails are far from orthogonal): those that leave less than `rss`.
std::vector<PlacedPair> screen_pairs(const std::vector<std::vector<LineProposals::Placement>>& placed, double rss, double without,
                                     double amplitude) {
  std::vector<PlacedPair> out;
  for (const LineProposals::Placement& first : placed[0])
    for (const LineProposals::Placement& second : placed[1]) {
      const double joint = first.candidate.score_v2 + second.candidate.score_v2 -
                           2.0 * amplitude * amplitude * dot(first.unit_voltage, second.unit_voltage);
      const double gain = rss - (without - joint);
      if (gain > 0.0) out.push_back({first.candidate.atom, second.candidate.atom, gain});
    }
  return out;
}
}  // namespace

std::vector<double> LineSearch::unit_voltage(const AtomParameters& atom, double damping_rate_per_s) const {
  const std::size_t samples = fit_->record().size();
  AtomSums sums;
  sums.reset(samples);
  fit_->model().add(atom, damping_rate_per_s, sums);
  std::vector<double> g(samples);
  fit_->model().unit_voltage(sums, g);
  return g;
}

LineSearch::LineSearch(RecordFit& fit, LineProposals& proposals, const LineSearchOptions& options, NoiseJudge judge)
    : fit_(&fit), proposals_(&proposals), options_(options), judge_(std::move(judge)) {}

std::vector<bool> LineSearch::neighbours(const FitState& state) const {
  const AtomModel& model = fit_->model().atoms().model();
  const double d = state.damping_rate_per_s;
  const AtomParameters& added = state.atoms.back();
  const double omega = model.tail_angular_frequency(added, d);
  const double t_b = model.breakaway_time(added, d);
  // A line width d/pi is 2 d / omega in ln omega, twice that in ln k (the friction's share of
  // the damping counted too).
  const double width = 4.0 * (d + fit_->model().atoms().ratios().linear_damping() * model.carried_phase(added) *
                                      std::sqrt(added.stiffness_n_per_m / model.device().asperity.mass_kg)) / omega;
  const bool timed = fit_->layout().onset_free || fit_->layout().load_per_atom;
  std::vector<bool> active(state.atoms.size());
  for (std::size_t i = 0; i < state.atoms.size(); ++i) {
    const AtomParameters& a = state.atoms[i];
    active[i] = std::abs(std::log(a.stiffness_n_per_m / added.stiffness_n_per_m)) < NEIGHBOURHOOD_WIDTHS * width ||
                (timed && std::abs(model.breakaway_time(a, d) - t_b) < NEIGHBOURHOOD_TIME_S);
  }
  active.back() = true;
  return active;
}

LineCandidate LineSearch::best_addition(const OrderFit& fit, const std::vector<double>* only_at_steps) {
  FitState state = fit.state;
  const std::vector<double> r = fit_->residual(state);
  const std::vector<LineCandidate> candidates =
      proposals_->propose(r, state.amplitude, state.damping_rate_per_s, state.load_factor, options_.candidates, only_at_steps);
  const bool steps_only = only_at_steps != nullptr;
  const AtomLibrary& lib = fit_->model().atoms();
  const double lo = std::log(lib.min_stiffness()), hi = std::log(lib.max_stiffness());
  const double d = state.damping_rate_per_s;
  LineCandidate best{{}, -INFINITY, 0.0};
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    // The best two, and those placed at onset steps (their k refined here first reaches their
    // score); only the latter for a start from the steps.
    if (steps_only ? !candidates[c].at_step : c >= 2 && !candidates[c].at_step) continue;
    // Golden-section search of the exact score in ln k over +-1 line width (the proposals'
    // frequency grid is a tenth of one), load and onset held.
    AtomParameters atom = candidates[c].atom;
    const double omega = lib.model().tail_angular_frequency(atom, d);
    const double half_width = 2.0 * 2.0 * d / omega + 1e-4;
    double a = std::max(lo, std::log(atom.stiffness_n_per_m) - half_width);
    double b = std::min(hi, std::log(atom.stiffness_n_per_m) + half_width);
    auto score_at = [&](double x) {
      AtomParameters trial = atom;
      trial.stiffness_n_per_m = std::exp(x);
      return proposals_->score(trial, r, state.amplitude, d);
    };
    constexpr double GOLDEN = 0.6180339887498949;
    double x1 = b - GOLDEN * (b - a), x2 = a + GOLDEN * (b - a);
    LineCandidate f1 = score_at(x1), f2 = score_at(x2);
    for (int iteration = 0; iteration < 8; ++iteration) {
      if (f1.score_v2 > f2.score_v2) {
        b = x2, x2 = x1, f2 = f1;
        x1 = b - GOLDEN * (b - a);
        f1 = score_at(x1);
      } else {
        a = x1, x1 = x2, f1 = f2;
        x2 = a + GOLDEN * (b - a);
        f2 = score_at(x2);
      }
    }
    const LineCandidate& refined = f1.score_v2 > f2.score_v2 ? f1 : f2;
    LineCandidate chosen = refined.score_v2 > candidates[c].score_v2 ? refined : candidates[c];
    chosen.at_step = candidates[c].at_step;
    if (chosen.score_v2 > best.score_v2) best = chosen;
  }
  return best;
}

std::vector<OrderFit> LineSearch::search(const FitState& start, std::size_t max_count, std::size_t min_count) {
  std::vector<OrderFit> fits;
  FitState empty = start;
  empty.atoms.clear();
  fits.push_back(fit_->refine(empty, {}, true, false, options_.max_iterations));
  std::size_t stop = max_count;  // the greedy count; fits go on extra_orders beyond it
  for (std::size_t n = 1; n <= max_count && (n <= stop + options_.extra_orders || n <= min_count); ++n) {
    const LineCandidate best = best_addition(fits.back());
    if (best.energy_v2 <= 0.0) break;  // no candidate at all (nothing in the band)
    FitState state = fits.back().state;
    state.atoms.push_back(best.atom);
    const std::vector<bool> active = neighbours(state);
    fits.push_back(fit_->refine(std::move(state), active, false, false, options_.max_iterations));
    if (n >= 2) {
      // The order reached by splitting one of the order below's atoms instead, where that fits better.
      if (std::optional<OrderFit> halves = split(fits[n - 1]); halves && halves->residual_v2 < fits[n].residual_v2) {
        if (std::getenv("STENGMC_DEBUG_SEARCH"))
          std::fprintf(stderr, "n=%zu split instead: rss %.4g -> %.4g\n", n, fits[n].residual_v2, halves->residual_v2);
        fits[n] = std::move(*halves);
      }
      replace(fits.back());
    }
    if (std::getenv("STENGMC_DEBUG_SEARCH")) {
      std::fprintf(stderr, "n=%zu add k %.3f N %.3g on %.3f us score %.4g energy %.4g -> rss %.4g\n", n, best.atom.stiffness_n_per_m,
                   best.atom.load_n, 1e6 * best.atom.onset_s, best.score_v2, best.energy_v2, fits.back().residual_v2);
      for (const AtomParameters& a : fits.back().state.atoms)
        std::fprintf(stderr, "    k %.3f N %.3g on %.3f\n", a.stiffness_n_per_m, a.load_n, 1e6 * a.onset_s);
    }
    // Judged on the joint refit, not on the addition alone: an atom that only becomes
    // useful once its neighbours move is still found.
    const double gain = fits[n - 1].residual_v2 - fits[n].residual_v2;
    if (stop == max_count && gain < options_.stop_fraction * best.energy_v2) stop = n - 1;
  }
  const std::size_t first = std::max(stop > 0 ? stop - 1 : 0, min_count);
  // Re-seating is for records no order fits yet. Once one order fits to the noise, the others
  // are not re-seated: one below lacks an atom, whose misfit moving the others cannot explain;
  // one above has an atom too many, which adds at least what it cannot hide of its own energy
  // (an atom's amplitude is set by its k and load, never 0). Either way its posterior weight
  // is negligible whatever it becomes. (Where the greedy path left the fitting order with an
  // atom patching a local minimum, RecordEstimator's backward elimination removes it.) On
  // records the atoms fit this spares the re-seating, a third of the estimation's time.
  const bool one_fits = std::any_of(fits.begin() + static_cast<std::ptrdiff_t>(std::min(first, fits.size())), fits.end(),
                                    [&](const OrderFit& f) { return fits_noise(f); });
  if (!one_fits)
    for (std::size_t n = first; n < fits.size(); ++n) reseat(fits[n], options_.reseat_sweeps);
  refit(fits, first);
  return fits;
}

bool LineSearch::put_back(OrderFit& fit, const FitState& without, const AtomParameters& own, const LineCandidate& current,
                          std::span<const LineCandidate> candidates) {
  for (const LineCandidate& c : candidates) {
    if (!(c.score_v2 > current.score_v2)) continue;
    FitState trial = without;
    trial.atoms.push_back(c.atom);
    const std::vector<bool> active = neighbours(trial);
    OrderFit refitted = fit_->refine(std::move(trial), active, false, false, options_.max_iterations);
    if (refitted.residual_v2 < fit.residual_v2) {
      if (std::getenv("STENGMC_DEBUG_SEARCH"))
        std::fprintf(stderr, "re-seat k %.3f N %.3g on %.3f -> k %.3f N %.3g on %.3f: rss %.4g -> %.4g\n", own.stiffness_n_per_m,
                     own.load_n, 1e6 * own.onset_s, c.atom.stiffness_n_per_m, c.atom.load_n, 1e6 * c.atom.onset_s, fit.residual_v2,
                     refitted.residual_v2);
      fit = std::move(refitted);
      return true;
    }
  }
  return false;
}

void LineSearch::reseat(OrderFit& fit, std::size_t sweeps) {
  for (std::size_t sweep = 0; sweep < sweeps; ++sweep) {
    bool improved = false;
    if (sweep == 0 && tail_solve(fit)) improved = true;
    for (std::size_t i = 0; i < fit.state.atoms.size(); ++i) {
      if (fits_noise(fit)) return;
      FitState without = fit.state;
      const AtomParameters own = without.atoms[i];
      without.atoms.erase(without.atoms.begin() + static_cast<std::ptrdiff_t>(i));
      const std::vector<double> r = fit_->residual(without);
      const double d = without.damping_rate_per_s;
      const LineCandidate current = proposals_->score(own, r, without.amplitude, d);
      const std::vector<LineCandidate> candidates = proposals_->propose(r, without.amplitude, d, without.load_factor, 2);
      if (put_back(fit, without, own, current, candidates)) improved = true;
    }
    // Each atom's own placement again, now that every atom is in (a cycle of onsets handed
    // round is walked one atom at a time where each step pays), then pairs.
    const double before = fit.residual_v2;
    replace(fit);
    if (fit.residual_v2 < before) improved = true;
    if (!fits_noise(fit) && exchange(fit)) improved = true;
    if (!fits_noise(fit) && cross(fit)) improved = true;
    if (!fits_noise(fit) && trade_onsets(fit)) improved = true;
    if (!fits_noise(fit) && merge(fit)) improved = true;
    if (!improved) return;
  }
}

bool LineSearch::exchange(OrderFit& fit) {
  const FitLayout& layout = fit_->layout();
  if (!layout.onset_free && !layout.load_per_atom) return false;
  const std::size_t samples = fit_->record().size();
  const std::size_t n = fit.state.atoms.size();
  bool kept = false;
  for (std::size_t round = 0; round < n && !fits_noise(fit); ++round) {
    FitState state = fit.state;
    const std::vector<double> r = fit_->residual(state);
    const double a = state.amplitude, d = state.damping_rate_per_s;
    std::vector<std::vector<double>> g(n);
    for (std::size_t i = 0; i < n; ++i) g[i] = unit_voltage(state.atoms[i], d);
    const double rss = dot(r, r);
    struct Exchange {
      std::size_t i, j;
      AtomParameters first, second;
      double gain;
    };
    std::vector<Exchange> screened;
    std::vector<double> q(samples);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        // Both taken out; each one's best onsets on what is left; the best pair of them,
        // their overlap counted (close lines' tails are far from orthogonal).
        for (std::size_t k = 0; k < samples; ++k) q[k] = r[k] + a * (g[i][k] + g[j][k]);
        const double without = dot(q, q);
        // (Their unit voltages come with them: the scoring made them already.)
        const AtomParameters pair[2] = {state.atoms[i], state.atoms[j]};
        for (const PlacedPair& p : screen_pairs(proposals_->propose_placements_with_voltages(pair, q, a, d, PAIR_ONSETS), rss, without, a))
          screened.push_back({i, j, p.first, p.second, p.gain});
      }
    std::sort(screened.begin(), screened.end(), [](const Exchange& e, const Exchange& f) { return e.gain > f.gain; });
    if (std::getenv("STENGMC_DEBUG_SEARCH"))
      std::fprintf(stderr, "pair re-seat screening: n %zu rss %.4g, %zu gains > 0, best %.3g\n", n, rss, screened.size(),
                   screened.empty() ? 0.0 : screened.front().gain);
    // Down the screened list, every exchange that lowers the misfit is kept, while a pair's
    // atoms have not moved this round (its screening is then stale); EXCHANGES_REFITTED
    // refits that do not lower it end the round.
    // A refit sorts the atoms by k: an unmoved atom is found again by its (unchanged) parameters.
    auto find = [&](const AtomParameters& x) {
      for (std::size_t k = 0; k < n; ++k) {
        const AtomParameters& y = fit.state.atoms[k];
        if (y.stiffness_n_per_m == x.stiffness_n_per_m && y.load_n == x.load_n && y.onset_s == x.onset_s) return k;
      }
      return n;
    };
    bool improved = false;
    std::size_t failures = 0;
    for (std::size_t c = 0; c < screened.size() && failures < EXCHANGES_REFITTED; ++c) {
      const Exchange& e = screened[c];
      const std::size_t i = find(state.atoms[e.i]), j = find(state.atoms[e.j]);
      if (i == n || j == n) continue;  // moved this round
      FitState trial = fit.state;
      trial.atoms[i] = e.first;
      trial.atoms[j] = e.second;
      std::vector<bool> active(n, false);
      active[i] = active[j] = true;
      OrderFit refitted = fit_->refine(std::move(trial), active, false, false, options_.max_iterations);
      if (!(refitted.residual_v2 < fit.residual_v2)) {
        ++failures;
        continue;
      }
      if (std::getenv("STENGMC_DEBUG_SEARCH"))
        std::fprintf(stderr, "pair re-seat k %.3f on %.3f, k %.3f on %.3f -> on %.3f, %.3f (screened gain %.3g): rss %.4g -> %.4g\n",
                     fit.state.atoms[i].stiffness_n_per_m, 1e6 * fit.state.atoms[i].onset_s, fit.state.atoms[j].stiffness_n_per_m,
                     1e6 * fit.state.atoms[j].onset_s, 1e6 * e.first.onset_s, 1e6 * e.second.onset_s, e.gain, fit.residual_v2,
                     refitted.residual_v2);
      fit = std::move(refitted);
      improved = kept = true;
    }
    if (!improved) break;
  }
  return kept;
}

bool LineSearch::cross(OrderFit& fit) {
  const FitLayout& layout = fit_->layout();
  if (!layout.onset_free && !layout.load_per_atom) return false;
  const AtomModel& model = fit_->model().atoms().model();
  const double d = fit.state.damping_rate_per_s;
  bool kept = false;
  for (std::size_t i = 0; i < fit.state.atoms.size() && !fits_noise(fit); ++i)
    for (std::size_t j = i + 1; j < fit.state.atoms.size() && !fits_noise(fit); ++j) {
      const AtomParameters &x = fit.state.atoms[i], &y = fit.state.atoms[j];
      const double width = 4.0 * d / model.tail_angular_frequency(x, d);
      if (std::abs(std::log(x.stiffness_n_per_m / y.stiffness_n_per_m)) >= MERGE_WIDTHS * width) continue;
      FitState trial = fit.state;
      std::swap(trial.atoms[i].onset_s, trial.atoms[j].onset_s);
      std::swap(trial.atoms[i].load_n, trial.atoms[j].load_n);
      std::vector<bool> active(trial.atoms.size(), false);
      active[i] = active[j] = true;
      OrderFit refitted = fit_->refine(std::move(trial), active, false, false, options_.max_iterations);
      if (std::getenv("STENGMC_DEBUG_SEARCH"))
        std::fprintf(stderr, "cross k %.3f on %.3f and k %.3f on %.3f: rss %.4g -> %.4g\n", x.stiffness_n_per_m, 1e6 * x.onset_s,
                     y.stiffness_n_per_m, 1e6 * y.onset_s, fit.residual_v2, refitted.residual_v2);
      if (refitted.residual_v2 < fit.residual_v2) fit = std::move(refitted), kept = true;
    }
  return kept;
}

bool LineSearch::merge(OrderFit& fit) {
  const FitLayout& layout = fit_->layout();
  if (!layout.onset_free && !layout.load_per_atom) return false;
  const AtomModel& model = fit_->model().atoms().model();
  const std::size_t n = fit.state.atoms.size();
  if (n < 2) return false;
  const double d = fit.state.damping_rate_per_s;
  const std::vector<double> zeros(fit_->record().size(), 0.0);
  // Pairs by their distance in line widths (a width: 4 d / omega in ln k), the closest first.
  std::vector<std::pair<double, std::pair<std::size_t, std::size_t>>> pairs;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const AtomParameters &x = fit.state.atoms[i], &y = fit.state.atoms[j];
      const double width = 4.0 * d / model.tail_angular_frequency(x, d);
      const double apart = std::abs(std::log(x.stiffness_n_per_m / y.stiffness_n_per_m)) / width;
      if (apart < MERGE_WIDTHS) pairs.push_back({apart, {i, j}});
    }
  std::sort(pairs.begin(), pairs.end());
  for (std::size_t c = 0; c < pairs.size() && c < MERGES_TRIED; ++c) {
    auto [i, j] = pairs[c].second;
    // The weaker of the two goes; the stronger, refitted with all the others, takes the pair's
    // line, so that the residual shows what is missing rather than the pair's own remainder.
    const double ei = proposals_->score(fit.state.atoms[i], zeros, fit.state.amplitude, d).energy_v2;
    const double ej = proposals_->score(fit.state.atoms[j], zeros, fit.state.amplitude, d).energy_v2;
    FitState merged = fit.state;
    merged.atoms.erase(merged.atoms.begin() + static_cast<std::ptrdiff_t>(ei < ej ? i : j));
    const OrderFit one = fit_->refine(std::move(merged), {}, false, false, options_.max_iterations);
    const LineCandidate added = best_addition(one);
    if (added.energy_v2 <= 0.0) continue;
    FitState trial = one.state;
    trial.atoms.push_back(added.atom);
    OrderFit refitted = fit_->refine(std::move(trial), {}, false, false, options_.max_iterations);
    if (std::getenv("STENGMC_DEBUG_SEARCH"))
      std::fprintf(stderr, "merge k %.3f and %.3f (%.2f widths apart), add k %.3f N %.3g on %.3f: rss %.4g -> %.4g\n",
                   fit.state.atoms[i].stiffness_n_per_m, fit.state.atoms[j].stiffness_n_per_m, pairs[c].first,
                   added.atom.stiffness_n_per_m, added.atom.load_n, 1e6 * added.atom.onset_s, fit.residual_v2, refitted.residual_v2);
    if (refitted.residual_v2 < fit.residual_v2) {
      fit = std::move(refitted);
      return true;
    }
  }
  return false;
}

bool LineSearch::tail_solve(OrderFit& fit) {
  const FitLayout& layout = fit_->layout();
  const std::size_t n = fit.state.atoms.size();
  if (!layout.onset_free || n < 2 || fits_noise(fit)) return false;
  const RecordModel& record_model = fit_->model();
  const AtomModel& model = record_model.atoms().model();
  const double d = fit.state.damping_rate_per_s, mass = model.device().asperity.mass_kg;
  const std::size_t samples = fit_->record().size();
  const RecordGrid& grid = record_model.atoms().grid();
  // The tail window: past every head any placement the prior allows could have.
  double window_s = 0.0;
  for (const AtomParameters& a : fit.state.atoms) {
    AtomParameters latest = a;
    latest.onset_s = layout.onset_max_s;
    if (layout.load_per_atom) latest.load_n = layout.nominal_load_n * std::exp(layout.max_log_load);
    window_s = std::max(window_s, model.breakaway_time(latest, d) + TAIL_SOLVE_HEAD_RAD / std::sqrt(a.stiffness_n_per_m / mass));
  }
  // (A capture may start after the belt did: its first sample is at grid.start_s.)
  const std::size_t first = static_cast<std::size_t>(std::ceil(std::max(0.0, window_s - grid.start_s) / grid.step_s));
  if (first + 4 * n >= samples) return false;
  const std::size_t m = samples - first;
  auto unit = [&](const AtomParameters& atom) { return unit_voltage(atom, d); };
  // The quadrature pair of each atom's tail: its voltage and the voltage of the same atom a
  // quarter period later (the envelope's change over a quarter period is ~d T / 4, 0.1 %).
  Eigen::MatrixXd basis(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(2 * n));
  std::vector<double> periods(n);
  for (std::size_t i = 0; i < n; ++i) {
    const AtomParameters& a = fit.state.atoms[i];
    periods[i] = 2.0 * PI / model.tail_angular_frequency(a, d);
    AtomParameters later = a;
    later.onset_s += 0.25 * periods[i];
    const std::vector<double> g0 = unit(a), g1 = unit(later);
    for (std::size_t k = 0; k < m; ++k) basis(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(2 * i)) = g0[first + k],
                                        basis(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(2 * i + 1)) = g1[first + k];
  }
  Eigen::VectorXd y(static_cast<Eigen::Index>(m));
  for (std::size_t k = 0; k < m; ++k)
    y(static_cast<Eigen::Index>(k)) = (fit_->record()[first + k] - fit.state.offset_v) / fit.state.amplitude;
  const Eigen::VectorXd c = basis.colPivHouseholderQr().solve(y);
  FitState trial = fit.state;
  for (std::size_t i = 0; i < n; ++i) {
    const AtomParameters& a = fit.state.atoms[i];
    const Eigen::VectorXd share = basis.col(static_cast<Eigen::Index>(2 * i)) * c(static_cast<Eigen::Index>(2 * i)) +
                                  basis.col(static_cast<Eigen::Index>(2 * i + 1)) * c(static_cast<Eigen::Index>(2 * i + 1));
    // Its breakaway shift from the share's amplitude (the envelope ~ e^{-d t}), then the phase
    // on a grid a 24th of a period fine within a period and a half of it.
    const double ratio = share.norm() / basis.col(static_cast<Eigen::Index>(2 * i)).norm();
    if (!(ratio > 0.0)) continue;
    const double coarse = std::log(ratio) / d;
    double best_error = INFINITY, best_onset = a.onset_s;
    for (int j = -36; j <= 36; ++j) {
      AtomParameters moved = a;
      moved.onset_s = a.onset_s + coarse + periods[i] * j / 24.0;
      if (moved.onset_s < layout.onset_min_s || moved.onset_s > layout.onset_max_s) continue;
      const std::vector<double> g = unit(moved);
      double error = 0.0;
      for (std::size_t k = 0; k < m; ++k) error += (share(static_cast<Eigen::Index>(k)) - g[first + k]) * (share(static_cast<Eigen::Index>(k)) - g[first + k]);
      if (error < best_error) best_error = error, best_onset = moved.onset_s;
    }
    trial.atoms[i].onset_s = best_onset;
  }
  OrderFit solved = fit_->refine(std::move(trial), {}, false, false, options_.max_iterations);
  for (std::size_t sweep = 0; sweep < options_.reseat_sweeps; ++sweep) {
    const double before = solved.residual_v2;
    replace(solved);
    if (!(solved.residual_v2 < before)) break;
  }
  if (std::getenv("STENGMC_DEBUG_SEARCH")) {
    std::fprintf(stderr, "tail solve n %zu (window from %.2f us): rss %.4g -> %.4g\n", n, 1e6 * window_s, fit.residual_v2, solved.residual_v2);
    for (const AtomParameters& x : solved.state.atoms)
      std::fprintf(stderr, "    k %.3f N %.3g on %.3f\n", x.stiffness_n_per_m, x.load_n, 1e6 * x.onset_s);
  }
  if (!(solved.residual_v2 < fit.residual_v2)) return false;
  fit = std::move(solved);
  return true;
}

bool LineSearch::trade_onsets(OrderFit& fit) {
  const FitLayout& layout = fit_->layout();
  if (!layout.onset_free || !layout.load_per_atom) return false;
  const AtomModel& model = fit_->model().atoms().model();
  const double d = fit.state.damping_rate_per_s;
  const double log_lo = std::log(layout.nominal_load_n) + layout.min_log_load, log_hi = std::log(layout.nominal_load_n) + layout.max_log_load;
  // `atom` at `onset_s`, its load set so that it breaks away at `breakaway_s`; false where no
  // load within the prior's bounds does (the breakaway grows with the load).
  auto move_keeping_breakaway = [&](AtomParameters& atom, double onset_s, double breakaway_s) {
    AtomParameters x = atom;
    x.onset_s = onset_s;
    double lo = log_lo, hi = log_hi;
    x.load_n = std::exp(lo);
    if (model.breakaway_time(x, d) > breakaway_s) return false;
    x.load_n = std::exp(hi);
    if (model.breakaway_time(x, d) < breakaway_s) return false;
    for (int it = 0; it < 50; ++it) {
      x.load_n = std::exp(0.5 * (lo + hi));
      (model.breakaway_time(x, d) < breakaway_s ? lo : hi) = 0.5 * (lo + hi);
    }
    x.load_n = std::exp(0.5 * (lo + hi));
    atom = x;
    return true;
  };
  const std::size_t samples = fit_->record().size();
  auto unit = [&](const AtomParameters& atom) { return unit_voltage(atom, d); };
  // Tries the cycle of onsets over `members` (each takes the next one's), each member's
  // breakaway kept to within a whole number of its periods (the tail's phase pins it only so):
  // every such choice screened on the raw residual with the members taken out, the best
  // refitted with them and kept where it lowers the misfit.
  auto try_cycle = [&](const std::vector<std::size_t>& members) {
    const double a = fit.state.amplitude;
    FitState current = fit.state;
    std::vector<double> q = fit_->residual(current);  // (its linear parameters as the fit's)
    for (std::size_t i : members) {
      const std::vector<double> g = unit(fit.state.atoms[i]);
      for (std::size_t k = 0; k < samples; ++k) q[k] += a * g[k];
    }
    // The best choice is refitted whatever its screened misfit: unrefined, a trade that is right
    // can still score below the local optimum it leaves.
    double best_rss = INFINITY;
    std::optional<FitState> best;
    const std::size_t choices = static_cast<std::size_t>(std::pow(2 * TRADE_PERIODS + 1, members.size()));
    for (std::size_t choice = 0; choice < choices; ++choice) {
      FitState trial = fit.state;
      std::vector<double> rest = q;
      bool valid = true;
      std::size_t code = choice;
      for (std::size_t c = 0; c < members.size() && valid; ++c) {
        const int j = static_cast<int>(code % (2 * TRADE_PERIODS + 1)) - TRADE_PERIODS;
        code /= 2 * TRADE_PERIODS + 1;
        const AtomParameters& own = fit.state.atoms[members[c]];
        const double period = 2.0 * PI / model.tail_angular_frequency(own, d);
        const double onset = fit.state.atoms[members[(c + 1) % members.size()]].onset_s;
        valid = move_keeping_breakaway(trial.atoms[members[c]], onset, model.breakaway_time(own, d) + j * period);
        if (!valid) break;
        const std::vector<double> g = unit(trial.atoms[members[c]]);
        for (std::size_t k = 0; k < samples; ++k) rest[k] -= a * g[k];
      }
      if (!valid) continue;
      const double rss = dot(rest, rest);
      if (rss < best_rss) best_rss = rss, best = std::move(trial);
    }
    if (!best) return false;
    std::vector<bool> active(best->atoms.size(), false);
    for (std::size_t i : members) active[i] = true;
    OrderFit refitted = fit_->refine(std::move(*best), active, false, false, options_.max_iterations);
    if (std::getenv("STENGMC_DEBUG_SEARCH"))
      std::fprintf(stderr, "trade onsets of %zu atoms (first k %.3f): rss %.4g -> %.4g\n", members.size(),
                   fit.state.atoms[members[0]].stiffness_n_per_m, fit.residual_v2, refitted.residual_v2);
    if (!(refitted.residual_v2 < fit.residual_v2)) return false;
    fit = std::move(refitted);
    return true;
  };
  bool kept = false;
  const std::size_t n = fit.state.atoms.size();
  // Close enough to trade, and apart enough that the trade moves something (atoms that share an
  // onset, as every atom of a record whose contact starts at once does, have nothing to trade:
  // trying their pairs and triples made a record of 15 such atoms at 1 m/s take 980 s).
  auto near = [&](std::size_t i, std::size_t j) {
    const AtomParameters &x = fit.state.atoms[i], &y = fit.state.atoms[j];
    const double apart = std::abs(x.onset_s - y.onset_s);
    const double shorter = 2.0 * PI / std::max(model.tail_angular_frequency(x, d), model.tail_angular_frequency(y, d));
    return apart < TRADE_WINDOW_S && apart > TRADE_MIN_PERIODS * shorter;
  };
  for (std::size_t i = 0; i < n && !fits_noise(fit); ++i)
    for (std::size_t j = i + 1; j < n && !fits_noise(fit); ++j) {
      if (!near(i, j)) continue;
      if (try_cycle({i, j})) kept = true;
      for (std::size_t k = j + 1; k < n && !fits_noise(fit); ++k)
        if (near(i, k) && near(j, k) && (try_cycle({i, j, k}) || try_cycle({i, k, j}))) kept = true;
    }
  return kept;
}

void LineSearch::replace(OrderFit& fit) {
  const FitLayout& layout = fit_->layout();
  if (!layout.onset_free && !layout.load_per_atom) return;
  for (std::size_t i = 0; i < fit.state.atoms.size() && !fits_noise(fit); ++i) {
    FitState without = fit.state;
    const AtomParameters own = without.atoms[i];
    without.atoms.erase(without.atoms.begin() + static_cast<std::ptrdiff_t>(i));
    const std::vector<double> q = fit_->residual(without);
    const double a = without.amplitude, d = without.damping_rate_per_s;
    const LineCandidate current = proposals_->score(own, q, a, d);
    put_back(fit, without, own, current, proposals_->propose_placements(own, q, a, d, REPLACEMENTS));
  }
}

std::optional<OrderFit> LineSearch::split(const OrderFit& fit) {
  const RecordModel& record_model = fit_->model();
  const AtomModel& model = record_model.atoms().model();
  const std::size_t samples = fit_->record().size();
  const double lo = std::log(record_model.atoms().min_stiffness()), hi = std::log(record_model.atoms().max_stiffness());
  std::optional<OrderFit> best;
  // On the ideal device (k alone free) two close lines are told apart by the greedy path: the
  // amplitude an atom must have leaves the second one in the residual.
  if (!fit_->layout().onset_free && !fit_->layout().load_per_atom) return best;
  {
    if (fit.state.atoms.empty() || fits_noise(fit)) return best;
    FitState state = fit.state;
    const std::vector<double> r = fit_->residual(state);
    const double a = state.amplitude, d = state.damping_rate_per_s;
    struct Split {
      std::size_t i;
      AtomParameters lower, upper;
      double gain;
    };
    std::vector<Split> screened;
    std::vector<double> q(samples), g(samples);
    double rss = 0.0;
    for (double x : r) rss += x * x;
    for (std::size_t i = 0; i < state.atoms.size(); ++i) {
      const AtomParameters& own = state.atoms[i];
      AtomSums sums;
      sums.reset(samples);
      record_model.add(own, d, sums);
      record_model.unit_voltage(sums, g);
      for (std::size_t k = 0; k < samples; ++k) q[k] = r[k] + a * g[k];
      // Half a line width (4 d / omega in ln k) either side.
      const double half = 2.0 * d / model.tail_angular_frequency(own, d);
      AtomParameters lower = own, upper = own;
      lower.stiffness_n_per_m = std::exp(std::max(lo, std::log(own.stiffness_n_per_m) - half));
      upper.stiffness_n_per_m = std::exp(std::min(hi, std::log(own.stiffness_n_per_m) + half));
      // |r|^2 against |q - a g_lower - a g_upper|^2, q = r + a g_own: the two scored in turn.
      AtomSums only;
      only.reset(samples);
      record_model.add(lower, d, only);
      record_model.unit_voltage(only, g);
      for (std::size_t k = 0; k < samples; ++k) q[k] -= a * g[k];
      const LineCandidate second_half = proposals_->score(upper, q, a, d);
      double after = -second_half.score_v2;
      for (std::size_t k = 0; k < samples; ++k) after += q[k] * q[k];
      screened.push_back({i, lower, upper, rss - after});
    }
    std::sort(screened.begin(), screened.end(), [](const Split& x, const Split& y) { return x.gain > y.gain; });
    for (std::size_t c = 0; c < screened.size() && c < SPLITS_REFITTED; ++c) {
      FitState trial = fit.state;
      trial.atoms.erase(trial.atoms.begin() + static_cast<std::ptrdiff_t>(screened[c].i));
      trial.atoms.push_back(screened[c].lower);
      std::vector<bool> active = neighbours(trial);
      trial.atoms.push_back(screened[c].upper);
      active.push_back(true);
      OrderFit refitted = fit_->refine(std::move(trial), active, false, false, options_.max_iterations);
      if (!best || refitted.residual_v2 < best->residual_v2) best = std::move(refitted);
    }
    // Narrow splits. Two asperities a fraction of a line width apart sum to one line whose
    // amplitude no single atom of their loads has: their split, screened as above, scores about
    // minus an atom's energy (two full atoms where one line was) whatever it is, and the wide
    // halves above are too far apart to refit into them. Their trace is the residual's power
    // around the merged atom's line: the atoms with the most of it are split a quarter of a line
    // width apart and refitted (a held-out loads record's pair 0.26 widths apart, loads 0.74 and
    // 1.42 x the device's, fitted as one atom of 1.09 and patched with four weak ones).
    SpectrumAnalyzer analyzer(samples, WindowKind::hann);
    const AmplitudeSpectrum spectrum = analyzer.analyse(r, record_model.atoms().grid().sample_rate_hz());
    std::vector<std::pair<double, std::size_t>> band_power;
    for (std::size_t i = 0; i < state.atoms.size(); ++i) {
      const double f = model.tail_angular_frequency(state.atoms[i], d) / (2.0 * PI), width_hz = d / PI;
      double sum = 0.0;
      std::size_t bins = 0;
      for (std::size_t k = 1; k < spectrum.frequency_hz.size(); ++k)
        if (std::abs(spectrum.frequency_hz[k] - f) <= NARROW_BAND_WIDTHS * width_hz) sum += spectrum.amplitude[k] * spectrum.amplitude[k], ++bins;
      band_power.emplace_back(bins ? sum / static_cast<double>(bins) : 0.0, i);
    }
    std::sort(band_power.begin(), band_power.end(), std::greater<>());
    for (std::size_t c = 0; c < band_power.size() && c < NARROW_SPLITS; ++c) {
      const AtomParameters& own = state.atoms[band_power[c].second];
      const double apart = NARROW_SPLIT_WIDTHS * 4.0 * d / model.tail_angular_frequency(own, d);  // a width: 4 d / omega in ln k
      AtomParameters lower = own, upper = own;
      lower.stiffness_n_per_m = std::exp(std::max(lo, std::log(own.stiffness_n_per_m) - apart));
      upper.stiffness_n_per_m = std::exp(std::min(hi, std::log(own.stiffness_n_per_m) + apart));
      FitState trial = fit.state;
      trial.atoms.erase(trial.atoms.begin() + static_cast<std::ptrdiff_t>(band_power[c].second));
      trial.atoms.push_back(lower);
      std::vector<bool> active = neighbours(trial);
      trial.atoms.push_back(upper);
      active.push_back(true);
      OrderFit refitted = fit_->refine(std::move(trial), active, false, false, options_.max_iterations);
      if (std::getenv("STENGMC_DEBUG_SEARCH"))
        std::fprintf(stderr, "  narrow split of k %.3f: rss %.4g -> %.4g\n", own.stiffness_n_per_m, fit.residual_v2, refitted.residual_v2);
      if (!best || refitted.residual_v2 < best->residual_v2) best = std::move(refitted);
    }
  }
  return best;
}

void keep_better_start(std::vector<OrderFit>& fits, OrderFit seeded, double sigma_v) {
  const std::size_t n = seeded.state.atoms.size();
  const double s2 = sigma_v * sigma_v;
  auto chi2 = [&](const OrderFit& f) { return f.residual_v2 / s2 + f.penalty; };
  if (std::getenv("STENGMC_DEBUG_SEARCH"))
    std::fprintf(stderr, "start of order %zu: chi2 %.6g (the search's %.6g)\n", n, chi2(seeded), n < fits.size() ? chi2(fits[n]) : -1.0);
  if (n == fits.size()) fits.push_back(std::move(seeded));
  else if (n < fits.size() && chi2(seeded) < chi2(fits[n])) fits[n] = std::move(seeded);
}

OrderFit LineSearch::place_at_steps(const FitState& start, const std::vector<double>& onsets_s) {
  FitState empty = start;
  empty.atoms.clear();
  OrderFit fit = fit_->refine(empty, {}, true, false, options_.max_iterations);
  std::vector<double> left = onsets_s;
  while (!left.empty()) {
    LineCandidate best = best_addition(fit, &left);
    if (!best.at_step || best.energy_v2 <= 0.0) break;
    // Where no line the map offers explains enough of what is left at any onset still free
    // (the greedy path's own stop), the atoms placed so far have taken that asperity's share:
    // forcing one in there placed it on no line (a library-wide scan of k found none either).
    if (best.score_v2 < options_.stop_fraction * best.energy_v2) break;
    // The onset taken (once: a step of two units stays for the second).
    left.erase(std::min_element(left.begin(), left.end(),
                                [&](double x, double y) { return std::abs(x - best.atom.onset_s) < std::abs(y - best.atom.onset_s); }));
    FitState state = fit.state;
    state.atoms.push_back(best.atom);
    const std::vector<bool> active = neighbours(state);
    fit = fit_->refine(std::move(state), active, false, false, options_.max_iterations);
    if (std::getenv("STENGMC_DEBUG_SEARCH"))
      std::fprintf(stderr, "at steps: n=%zu add k %.3f N %.3g on %.3f us -> rss %.4g\n", fit.state.atoms.size(),
                   best.atom.stiffness_n_per_m, best.atom.load_n, 1e6 * best.atom.onset_s, fit.residual_v2);
  }
  return polish(std::move(fit.state));
}

OrderFit LineSearch::polish(FitState start) {
  OrderFit fit = fit_->refine(std::move(start), {}, true, false, options_.max_iterations);
  // A start with every load at the device's: each unequal load's breakaway, hence its tail's
  // phase, is off by a fraction of a period or more, which the local fit does not undo.
  for (std::size_t sweep = 0; sweep < options_.reseat_sweeps; ++sweep) {
    const double before = fit.residual_v2;
    replace(fit);
    if (!(fit.residual_v2 < before)) break;
  }
  reseat(fit, options_.reseat_sweeps);
  return fit_->refine(std::move(fit.state), {}, true, true, options_.max_iterations);
}

void LineSearch::refit(std::vector<OrderFit>& fits, std::size_t first) {
  // Every order from `first` on, in full: all atoms and the device's shared parameters. An
  // order whose misfit already exceeds the best one's by HOPELESS_CHI2_GAP has a posterior
  // weight below e^{-GAP/2} of the best's, which no refit of its wrong atoms brings back: the
  // Levenberg-Marquardt steps then crawl to the iteration cap (60) for nothing (on ideal
  // records the orders around the true count took 56-60 iterations, the true one 2-3). Such
  // an order gets a few steps, enough for its evidence's J^T J.
  const double s2 = fit_->sigma_v() * fit_->sigma_v();
  double best = INFINITY;
  for (std::size_t n = first; n < fits.size(); ++n) best = std::min(best, fits[n].residual_v2 / s2 + fits[n].penalty);
  for (std::size_t n = first; n < fits.size(); ++n) {
    const bool hopeless = fits[n].residual_v2 / s2 + fits[n].penalty > best + HOPELESS_CHI2_GAP;
    fits[n] = fit_->refine(fits[n].state, {}, true, true, hopeless ? HOPELESS_ITERATIONS : options_.max_iterations);
  }
}

}  // namespace stengmc
