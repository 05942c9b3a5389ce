#pragma once
//! The shape of one asperity's velocity, for every asperity an inversion may meet, in the
//! units where it depends on two numbers only (docs/inverse.md, "atoms").
//!
//! With u = x'/v_b, theta = omega0 (t - t_on) (omega0 = sqrt(k/m), t_on the contact onset)
//! and X = x omega0 / v_b, Model 2 reads
//!
//!   du/dtheta = Pi phi(u) - 2 zeta u - X,   Pi = N f_ref / (m omega0 v_b),   zeta = c / (2 m omega0),
//!
//! phi the device's friction ratio (friction_ratios.hpp). So every asperity's motion is one
//! of a two-parameter family u(theta; Pi, zeta): Pi is the belt-carried stretch in radians
//! (omega0 times the breakaway time), zeta the damping ratio. Without regularisation the
//! motion is: a pick-up u = Pi sin(theta) until u = 1 at theta_p = asin(1/Pi), the belt's
//! velocity until the spring and damper need more than the friction gives, then a free
//! oscillation u = cos(theta - theta_b) about F/k, with
//!
//!   theta_b = asin(min(1, 1/Pi)) + sqrt(max(0, Pi^2 - 1)) - 2 zeta;
//!
//! for Pi <= 1 the asperity never reaches the belt's velocity and oscillates from the onset.
//! Up to theta_p (Pi > 1) the pick-up is written out, u = Pi e^{-zeta theta} sin(nu theta)/nu
//! (the friction is F_s while the asperity is far below the belt's velocity), and so is the
//! stick after it: u = 1 - v_r(y)/v_b, the creep of the friction's regularisation at the
//! force share y = (X + 2 zeta u)/Pi, X grown from Pi (1 - cos theta_p) at the belt's rate.
//! The rest of the head comes from the forward model on a grid of ln Pi (step 0.02) and
//! ln zeta (a few nodes), the viscous decay e^{-zeta g} divided out (g: how long the
//! asperity has moved relative to the belt, decay_phase) so that what is left varies slowly
//! with zeta:
//!  - Pi below a split (12): one piece from the onset, theta in [0, theta_b + psi_post] (used
//!    past the pick-up's kink);
//!  - above it: a piece aligned on the breakaway, psi = theta - theta_b in [-8, psi_post]; the
//!    stick's share y is interpolated linearly up to where that piece starts.
//! Aligned so, each piece moves smoothly with Pi: 4-point Lagrange in ln Pi, linear in
//! ln zeta, cubic Hermite (values and slopes) in theta. Below the smallest Pi node the
//! asperity's velocity stays far from v_b and the shape scales with Pi (the friction is
//! constant there). After the head a free oscillation on the envelope of the asperity's
//! load and damping takes over (envelope_family.hpp), with its amplitude where the tail
//! starts (psi_s = psi_post - blend) and its phase fitted at each node:
//!
//!   u = A(t - t_s + sigma) cos(nu (theta - theta_b) + phi),  nu = sqrt(1 - (zeta + Pi q0)^2),
//!
//! (q0 the friction's linear damping, FrictionRatios::linear_damping: it lowers the frequency
//! as viscous damping does), t_s = t_on + (theta_b + psi_s) / omega0 and sigma where the envelope has that amplitude,
//! cross-faded from the head over the last 5 rad of the head. (Stored as an amplitude, not a
//! shift: for light loads the shift runs to ~ln(1/Pi)/zeta and moves steeply with zeta.)
#include <array>
#include <cstddef>
#include <vector>

#include "inverse/friction_ratios.hpp"
#include "inverse/known_device.hpp"

namespace stengmc {

struct AtomShapeSettings {
  double log_pi_step = 0.02;           //!< ln Pi step of the node grid
  std::size_t zeta_nodes = 4;          //!< nodes in ln zeta (1 when zeta has one value)
  double theta_step = 0.05;            //!< sample step of the stored shapes [rad]
  double after_breakaway = 30.0;       //!< psi_post: the head reaches this far past breakaway [rad]
  double before_breakaway = 8.0;       //!< the breakaway piece starts this far before it [rad]
  double split_pi = 12.0;              //!< below: one piece from the onset; above: pick-up, stick, breakaway
  double blend = 5.0;                  //!< head-to-tail cross-fade, ending at psi_post [rad]
  double tail_fit_span = 80.0;         //!< the tail's (eps, phi) are fitted over this much past the head [rad]
};

//! What the shapes range over.
struct AtomShapeRange {
  double min_pi = 0.0, max_pi = 0.0;
  double min_zeta = 0.0, max_zeta = 0.0;
};

//! The stored family (for a bank file).
struct AtomShapeData {
  AtomShapeRange range;
  AtomShapeSettings settings;
  std::vector<double> pi_nodes, zeta_nodes;
  std::size_t onset_samples = 0;      //!< samples of the one-piece (small Pi) head
  std::size_t breakaway_samples = 0;  //!< samples of the breakaway piece (large Pi)
  //! Per node (pi index major, zeta minor): shapes (values, then slopes d/dtheta), each block
  //! empty where the node does not need that representation.
  std::vector<std::vector<double>> onset_values, onset_slopes, breakaway_values, breakaway_slopes;
  std::vector<double> breakaway_share;                //!< y where the breakaway piece starts
  //! Per node: the tail's -ln A where it starts (psi_post - blend), and its phase phi [rad]
  std::vector<double> tail_log_amplitude, tail_phase;
  double check_error = 0.0;                           //!< worst head error at midpoints (relative L2) [-]
};

//! Weights of one (Pi, zeta) over the nodes, computed once per atom and used at every sample.
struct ShapeWeights {
  bool small = true;                 //!< the one-piece representation
  double scale = 1.0;                //!< Pi below the smallest node: the shape is the node's x Pi / Pi_0
  std::array<std::size_t, 8> node{}; //!< node indices (4 in Pi x 2 in zeta)
  std::array<double, 8> w{};         //!< weights of the value
  std::array<double, 8> w_lnpi{};    //!< weights of d/d ln Pi
  std::array<double, 8> w_lnzeta{};  //!< weights of d/d ln zeta
  double pi = 0.0, zeta = 0.0;
  double theta_b = 0.0;              //!< closed-form breakaway phase [rad]
  double theta_p = 0.0;              //!< the pick-up's end, asin(min(1, 1/Pi)) [rad]
  double theta_b_lnpi = 0.0, theta_b_lnzeta = 0.0;  //!< its derivatives
  double breakaway_share = 0.0;                     //!< y where the breakaway piece starts (large Pi)
  //! The tail: its envelope's log amplitude -ln A where it starts (psi = psi_post - blend),
  //! and its phase [rad]; with their derivatives in ln Pi and ln zeta.
  double log_amplitude = 0.0, phi = 0.0;
  double log_amplitude_lnpi = 0.0, log_amplitude_lnzeta = 0.0, phi_lnpi = 0.0, phi_lnzeta = 0.0;
};

//! u and its derivatives at one theta.
struct ShapePoint {
  double u = 0.0;         //!< x' / v_b
  double u_theta = 0.0;   //!< du/dtheta
  double u_lnpi = 0.0;    //!< du/d ln Pi at fixed theta
  double u_lnzeta = 0.0;  //!< du/d ln zeta at fixed theta
};

class AtomShapes {
 public:
  //! Builds the family over `range` with the forward model (solve_model2_motion) of the
  //! device's friction law and belt velocity (~1 s per 100 nodes).
  AtomShapes(const KnownDevice& device, const FrictionRatios& ratios, const AtomShapeRange& range,
             const AtomShapeSettings& settings = {});
  AtomShapes(const KnownDevice& device, const FrictionRatios& ratios, AtomShapeData data);

  //! theta_b(Pi, zeta), the closed form above [rad].
  static double breakaway_phase(double pi, double zeta);
  //! nu = omega_tail / omega0 = sqrt(1 - (zeta + Pi q0)^2) [-].
  static double tail_frequency_ratio(double pi, double zeta, const FrictionRatios& ratios);
  //! theta_p = asin(min(1, 1/Pi)): where the pick-up reaches the belt's velocity [rad].
  static double pickup_phase(double pi);
  //! g = min(theta, theta_p) + max(0, theta - theta_b): how long the asperity has moved
  //! relative to the belt, the time its viscous decay e^{-zeta g} has run [rad]. The table
  //! holds u e^{zeta g}, which varies slowly with zeta.
  static double decay_phase(double theta, double theta_p, double theta_b);
  //! dg/dtheta (0 or 1, 2 never: theta_p <= theta_b).
  static double decay_phase_rate(double theta, double theta_p, double theta_b);

  [[nodiscard]] ShapeWeights weights(double pi, double zeta) const;
  //! u at theta >= 0 (onset at 0) within the head, theta <= head_end(w).
  [[nodiscard]] ShapePoint head(const ShapeWeights& w, double theta) const;
  //! Where the head ends and the tail alone holds: theta_b + psi_post [rad].
  [[nodiscard]] double head_end(const ShapeWeights& w) const { return w.theta_b + data_.settings.after_breakaway; }
  //! Where the cross-fade into the tail starts, psi_s past breakaway: theta_b + psi_s [rad].
  [[nodiscard]] double blend_start(const ShapeWeights& w) const { return head_end(w) - data_.settings.blend; }

  [[nodiscard]] const AtomShapeData& data() const { return data_; }
  [[nodiscard]] const FrictionRatios& ratios() const { return *ratios_; }

 private:
  void build(const KnownDevice& device);
  void check(const KnownDevice& device);
  [[nodiscard]] std::size_t node_index(std::size_t j, std::size_t q) const { return j * data_.zeta_nodes.size() + q; }

  const FrictionRatios* ratios_;
  double belt_velocity_m_per_s_ = 0.0;
  AtomShapeData data_;
};

}  // namespace stengmc
