#pragma once
//! One sliding asperity's velocity on the record grid, from its stiffness, load and contact
//! onset and the device's damping: the atoms of the inversion (docs/inverse.md, "atoms").
//! The head comes from the shape family (atom_shapes.hpp) at Pi = N f_ref / (m omega0 v_b)
//! and zeta = d / omega0, theta = omega0 (t - t_on); the tail is the free oscillation on the
//! envelope of its load and damping (envelope_family.hpp). Exact in the onset: an asperity
//! that comes into contact later moves as one from t = 0, shifted (MODEL.md §1.3).
#include <cstddef>
#include <vector>

#include "inverse/atom_shapes.hpp"
#include "inverse/envelope_family.hpp"
#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! What an atom is made of.
struct AtomParameters {
  double stiffness_n_per_m = 0.0;  //!< k [N/m]
  double load_n = 0.0;             //!< N, its normal load at the device's friction coefficients [N]
  double onset_s = 0.0;            //!< t_on, when it comes into contact [s]
};

//! An atom on its support, the samples from its onset on.
struct AtomValues {
  std::size_t first = 0;       //!< first sample with t >= t_on
  std::vector<double> u;       //!< x' / v_b [-]
  std::vector<double> slope;   //!< du/dt [1/s]
  //! With derivatives: du/d ln k, du/d ln N, du/d t_on [1/s], du/d ln d
  std::vector<double> d_lnk, d_lnn, d_onset, d_lnd;
  [[nodiscard]] std::size_t end() const { return first + u.size(); }
};

class AtomModel {
 public:
  AtomModel(const KnownDevice& device, const RecordGrid& grid, const AtomShapes& shapes, const EnvelopeFamily& envelopes);

  //! The atom with device damping rate d = c/2m [1/s] on its support; with `derivatives`,
  //! its derivatives in ln k, ln N, t_on and ln d (the scratch vectors of `out` are reused).
  void evaluate(const AtomParameters& atom, double damping_rate_per_s, AtomValues& out, bool derivatives) const;

  //! When the asperity leaves the belt: t_on + theta_b / omega0 [s].
  [[nodiscard]] double breakaway_time(const AtomParameters& atom, double damping_rate_per_s) const;
  //! Pi of the atom [-].
  [[nodiscard]] double carried_phase(const AtomParameters& atom) const;
  //! Its element's displacement at time t, to the accuracy its capacitance needs: carried at
  //! v_b from the onset until it reaches its mean F_s/k, then about that mean [m].
  [[nodiscard]] double displacement(const AtomParameters& atom, double t_s) const;
  //! Angular frequency of its tail, omega0 nu [rad/s].
  [[nodiscard]] double tail_angular_frequency(const AtomParameters& atom, double damping_rate_per_s) const;

  [[nodiscard]] const KnownDevice& device() const { return *device_; }
  [[nodiscard]] const RecordGrid& grid() const { return grid_; }
  [[nodiscard]] const AtomShapes& shapes() const { return *shapes_; }
  [[nodiscard]] const EnvelopeFamily& envelopes() const { return *envelopes_; }

 private:
  const KnownDevice* device_;
  RecordGrid grid_;
  const AtomShapes* shapes_;
  const EnvelopeFamily* envelopes_;
  double reference_friction_ = 0.0;  // f_ref
};

}  // namespace stengmc
