#pragma once
//! Where one more atom would explain a residual best, for every stiffness at once: the
//! proposals of the line search (docs/inverse.md, "search").
//!
//! Adding atom g_k to a fit with residual r lowers the squared residual by
//! score(k) = 2 <r, g_k> - |g_k|^2. An atom's tail is E(t) cos(omega_k t + phi_k) with the
//! device's one envelope E, so <r, g_k> ~ Re[e^{i phi_k} conj(C(omega_k))] with
//! C(omega) = sum_m r_m E(t_m) e^{-i omega t_m}: one zero-padded FFT of r E gives it on a
//! fine frequency grid (1/(8T)). The belt-carried plateau before breakaway is left out
//! (every atom has one: it tells the count, not where the line is). The map is approximate
//! (the envelope's start is shifted by a few percent); the caller refines the best
//! candidates with exact atoms.
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "inverse/atom_table.hpp"

namespace stengmc {

struct LineCandidate {
  double stiffness_n_per_m = 0.0;
  double score_v2 = 0.0;  //!< estimated decrease of the squared residual [V^2]
};

class LineProposals {
 public:
  //! @param padding FFT length >= padding x samples (frequency grid 1 / (padding T))
  explicit LineProposals(const AtomTable& atoms, std::size_t padding = 8);
  ~LineProposals();
  LineProposals(const LineProposals&) = delete;
  LineProposals& operator=(const LineProposals&) = delete;

  //! The local maxima of the tails' score over the frequency grid, best first, at most `count`.
  std::vector<LineCandidate> propose(std::span<const double> residual, std::size_t count);

  //! |g_k|^2 [V^2], interpolated from a table over ln k.
  [[nodiscard]] double atom_energy(double stiffness_n_per_m) const;

 private:
  struct Fft;
  const AtomTable* atoms_;
  std::size_t length_ = 0;            // FFT length
  std::unique_ptr<Fft> fft_;
  std::vector<double> weight_;        // E(t_m)
  std::size_t first_bin_ = 0, last_bin_ = 0;
  std::vector<double> bin_stiffness_, bin_phase_, bin_energy_, bin_breakaway_;
  std::vector<double> energy_log_k_, energy_table_;
};

}  // namespace stengmc
