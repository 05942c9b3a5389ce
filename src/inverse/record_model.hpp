#pragma once
//! The voltage of n sliding asperities of the known device, from their atoms (docs/inverse.md,
//! "the record model").
//!
//! Each atom is an asperity's velocity u_i = x_i'/v_b (atom_model.hpp); the elements share the
//! load (MODEL.md §2): (C_sum + C_L) V' = sigma w sum x_i' + V sum eps0 w x_i'/d0 - V/R. With
//! U = R sigma w v_b sum u_i, to first order in tau = R (C_sum + C_L) and gamma = eps0/(sigma d0),
//!
//!   M = U + gamma U^2 - R (C_sum(t) + C_L) U',   C_sum(t) = sum eps0 w (l - x_i(t)) / d0,
//!
//! except within a few tau of an onset, where the slope jumps from 0 and the circuit follows
//! it as 1 - e^{-(t - t_on)/tau} (tau ~ 1e-10 s: the first sample only, but at an onset on a
//! sample, t = 0 most of all, the plain term puts -tau U' where V is still 0);
//! and the record is a M + b: the amplitude a (sigma and R known within the prior's
//! tolerance; gamma scales as 1/a, so a M holds exactly) and the offset b enter linearly. The
//! neglected terms are of order (omega tau)^2 ~ 2e-4 at n = 16, 2 MHz; x_i(t) is the element's
//! displacement to the accuracy its capacitance needs (AtomModel::displacement).
#include <span>
#include <vector>

#include "inverse/atom_library.hpp"

namespace stengmc {

//! Everything a fit adjusts, for one record.
struct FitState {
  std::vector<AtomParameters> atoms;   //!< in no particular order
  double damping_rate_per_s = 0.0;     //!< d = c/2m of the device [1/s]
  double load_factor = 1.0;            //!< the shared load factor (FitLayout::load_shared) [-]
  double amplitude = 1.0;              //!< a [-]
  double offset_v = 0.0;               //!< b [V]
};

//! Sums over atoms that the coupling needs, so a fit can keep the atoms it does not move summed once.
struct AtomSums {
  std::vector<double> value;         //!< U [V] (unit amplitude)
  std::vector<double> slope;         //!< U' [V/s]
  std::vector<double> displacement;  //!< sum x_i [m]
  //! Each atom's first sample: how long after its onset, and its slope there [V/s] (the
  //! circuit's lag behind the slope's jump at the onset, unit_voltage).
  struct Onset {
    std::size_t sample = 0;
    double since_s = 0.0;
    double slope = 0.0;
  };
  std::vector<Onset> onsets;
  std::size_t atoms = 0;
  //! Zeros for `samples` samples.
  void reset(std::size_t samples);
};

class RecordModel {
 public:
  explicit RecordModel(const AtomLibrary& atoms);

  //! Adds atom `a` (damping rate d) to `sums`; with `values`, the atom's evaluation is kept
  //! there (derivatives too when `derivatives`).
  void add(const AtomParameters& a, double d, AtomSums& sums, AtomValues* values = nullptr, bool derivatives = false) const;
  //! M of the atoms in `sums` (unit amplitude, no offset) [V].
  void unit_voltage(const AtomSums& sums, std::span<double> out) const;
  //! a M + b for `state` [V].
  void voltage(const FitState& state, std::span<double> out) const;
  //! R sigma w v_b: one atom's belt-carried voltage at unit amplitude [V].
  [[nodiscard]] double volts_per_unit() const { return volts_per_unit_; }

  [[nodiscard]] const AtomLibrary& atoms() const { return *atoms_; }
  [[nodiscard]] std::size_t samples() const { return atoms_->grid().samples; }

 private:
  const AtomLibrary* atoms_;
  double volts_per_unit_ = 0.0;   // R sigma w v_b
  double gamma_per_v_ = 0.0;      // eps0 / (sigma d0)
  double capacitance_per_length_ = 0.0;  // eps0 w / d0 [F/m]
};

}  // namespace stengmc
