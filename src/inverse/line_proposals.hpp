#pragma once
//! Where one more atom would explain a residual best (docs/inverse.md, "the search").
//!
//! Adding atom g to a fit with residual r and amplitude a lowers the squared residual by
//! 2 a <r, g> - a^2 |g|^2. An atom is a belt-carried plateau from its onset t_on to its
//! breakaway t_b, then a tail ~ A(t - t_b) cos(omega (t - t_b) + phi) on the envelope A of its
//! load and damping. So <r, g> is approximated, for every candidate at once, by
//!  - the plateau's share: prefix sums of r between t_on and t_b;
//!  - the tail's: Re[e^{i (phi - omega t_b)} conj(C_s(omega))] e^{d (t_b - T_s)}, with
//!    C_s = FFT of r(t) E(t - T_s) over t >= T_s (E the device's nominal envelope, T_s on a
//!    grid of tail starts half an envelope decay apart): one zero-padded FFT per start gives
//!    every frequency;
//! and the candidates are the stiffnesses of the map's best frequencies, each with the loads
//! and onsets the prior allows whose breakaway puts the tail in phase with C (t_b where
//! phi - omega t_b = arg C mod 2 pi). The best of them by this estimate are scored exactly
//! (their atoms evaluated), and returned best first.
#include <complex>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "inverse/fit_layout.hpp"
#include "inverse/load_prior.hpp"
#include "inverse/record_model.hpp"

namespace stengmc {

struct LineCandidate {
  AtomParameters atom;
  double score_v2 = 0.0;   //!< exact decrease of the squared residual [V^2]
  double energy_v2 = 0.0;  //!< the atom's own energy a^2 |g|^2 [V^2]
  bool at_step = false;    //!< placed at an onset step (LineProposals::set_step_onsets)
};

class LineProposals {
 public:
  //! @param padding FFT length >= padding x samples (frequency grid 1 / (padding T))
  LineProposals(const RecordModel& model, const FitLayout& layout, const LoadPrior& loads, std::size_t padding = 4);
  ~LineProposals();
  LineProposals(const LineProposals&) = delete;
  LineProposals& operator=(const LineProposals&) = delete;

  //! At most `count` candidates for one more atom on the (raw) residual `r` of a fit with
  //! amplitude a, damping rate d and shared load factor, best first by exact score.
  //! `step_onsets_s`, where given, are the onsets tried as steps instead of those set
  //! (set_step_onsets): a start from the steps asks only at the onsets it has not yet taken.
  std::vector<LineCandidate> propose(std::span<const double> residual, double amplitude, double damping_rate,
                                     double load_factor, std::size_t count,
                                     const std::vector<double>* step_onsets_s = nullptr);

  //! At most `count` placements (onset and load, as the layout frees them) for `atom` (its
  //! stiffness held) on the residual `r`, distinct (half a period or a load step apart), best
  //! first by exact score: the same sliding matched filter and plateau sums as `propose`, at
  //! one frequency.
  std::vector<LineCandidate> propose_placements(const AtomParameters& atom, std::span<const double> residual, double amplitude,
                                            double damping_rate, std::size_t count);

  //! A placement with the atom's unit-amplitude voltage g (the record model of it alone), for
  //! callers that score combinations of atoms by their overlaps <g_1, g_2>.
  struct Placement {
    LineCandidate candidate;
    std::vector<double> unit_voltage;
  };
  //! propose_placements for each of `atoms` on the one residual `r` (transformed once), with
  //! each placement's g kept: the candidates and their order are those of propose_placements.
  std::vector<std::vector<Placement>> propose_placements_with_voltages(std::span<const AtomParameters> atoms,
                                                                       std::span<const double> residual, double amplitude,
                                                                       double damping_rate, std::size_t count);

  //! Contact onsets the record shows as steps (inverse/onset_steps.hpp) [s]: where the layout
  //! frees onsets, every proposal and placement also scores exactly, for each of them, the
  //! atom starting there with its best load, beside the matched filter's best (empty: none).
  //! `propose` returns the best STEP_PROPOSALS of those after its `count` (marked at_step) even
  //! where they score lower: their stiffness is the map's, on a grid a tenth of a line width
  //! wide, which over a 100 us record turns the tail by a fifth of a period, so a placement at
  //! the right onset scores below one a period off until its k is refined.
  void set_step_onsets(std::vector<double> onsets_s) { step_onsets_s_ = std::move(onsets_s); }

  //! The exact score 2 a <r, g> - a^2 |g|^2 of one atom, and its energy.
  LineCandidate score(const AtomParameters& atom, std::span<const double> residual, double amplitude, double damping_rate) const;
  //! The same, with the atom's unit-amplitude voltage g written into `unit_voltage`.
  LineCandidate score(const AtomParameters& atom, std::span<const double> residual, double amplitude, double damping_rate,
                      std::vector<double>& unit_voltage) const;

 private:
  struct Fft;
  struct Residual;
  struct Rough;
  //! The tail where it starts, from an atom's shape weights: the same for every breakaway
  //! time of one shape, so worked out once per shape, not once per rough candidate.
  struct TailStart {
    std::complex<double> phase;  //!< e^{i phi}
    double amplitude = 0.0;      //!< the tail's velocity amplitude where it starts [v_b]
  };
  static TailStart tail_start(const ShapeWeights& w);
  //! Prefix sums and the sliding transform of a residual.
  void load_residual(Residual& q) const;
  //! The sliding matched filter of the loaded residual at tail frequency omega [rad/s].
  void matched_filter(double omega, std::vector<std::complex<double>>& matched);
  //! One value of the sliding matched filter of `r` at tail frequency omega, C(t_b) at sample
  //! `at`, summed directly.
  [[nodiscard]] std::complex<double> matched_value(std::span<const double> r, double omega, std::size_t at) const;
  //! The transform of the matched filter's kernel E(tau) e^{i omega tau}: it depends on omega
  //! alone, and the pair re-seat asks for each atom's once per pair it is in, so the last
  //! KERNELS_KEPT are kept.
  const std::vector<std::complex<double>>& kernel_transform(double omega);
  //! `count` placements of `atom` on the loaded residual `q`, best first (propose_placements),
  //! each one's g into `units` when given.
  std::vector<LineCandidate> placements(const AtomParameters& atom, const Residual& q, std::size_t count,
                                        std::vector<std::vector<double>>* units);
  //! The rough score of `atom` (carried phase pi, its tail starting as `tail`) breaking away at sample `breakaway`.
  void add_rough(const AtomParameters& atom, double pi, const TailStart& tail, std::size_t breakaway, const Residual& q,
                 std::span<const std::complex<double>> matched, std::vector<Rough>& rough) const;
  //! `atom` at its onset, or at every onset the layout allows.
  void add_breakaways(AtomParameters atom, const Residual& q, std::span<const std::complex<double>> matched,
                      std::vector<Rough>& rough) const;
  //! Every load and onset the layout allows for an atom of `nominal`'s stiffness.
  void add_placements(const AtomParameters& nominal, const Residual& q, std::span<const std::complex<double>> matched,
                      std::vector<Rough>& rough) const;
  //! For each of `onsets_s` the layout allows, the atom of `nominal`'s stiffness starting there
  //! with the load (of those the layout allows) of the best rough score, best first.
  [[nodiscard]] std::vector<Rough> step_placements(const AtomParameters& nominal, const Residual& q,
                                                   std::span<const std::complex<double>> matched,
                                                   const std::vector<double>& onsets_s) const;
  [[nodiscard]] std::size_t index_of(double t) const;
  const RecordModel* model_;
  FitLayout layout_;
  const LoadPrior* loads_;
  std::size_t length_ = 0;
  std::unique_ptr<Fft> fft_;
  std::vector<double> envelope_;        // E(j h) of the nominal atom, from its breakaway
  std::vector<double> envelope_energy_; // sum_{i < j} E(i h)^2
  std::vector<double> starts_s_;        // tail starts T_s
  std::size_t first_bin_ = 0, last_bin_ = 0;
  std::vector<double> loads_grid_;      // candidate loads when each atom has its own [N]
  std::vector<double> step_onsets_s_;   // onsets the record shows as steps [s]
  struct KernelTransform {
    double omega = 0.0;
    std::vector<std::complex<double>> transform;
  };
  std::vector<KernelTransform> kernels_;  // the last few kernel transforms, oldest first
};

}  // namespace stengmc
