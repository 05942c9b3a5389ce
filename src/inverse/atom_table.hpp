#pragma once
//! Fast, accurate atoms: the voltage V_1(t; k) one asperity of stiffness k produces alone on
//! the known device, for any k in a range, in ~20 us instead of the forward model's ~10 ms
//! (docs/inverse.md, "atoms").
//!
//! An atom has a head (the belt drags the asperity up to breakaway, then the first cycles,
//! where the friction's regularisation shapes the motion) and a tail (a free oscillation on
//! the universal friction envelope, FrictionEnvelope). The table keeps
//!  - heads: the forward model's V_1 over [0, T_head) on a fine grid of ln k (step 0.01),
//!    interpolated in ln k at each sample by 4-point Lagrange (cubic) interpolation;
//!  - tails: V_1 ~ (R sigma w) A(t + e_k) cos(omega_k t + phi_k) with omega_k the damped
//!    frequency sqrt(k/m - d^2) and (e_k, phi_k) fitted to the forward model on a coarse grid
//!    of ln k, interpolated by cubic B-splines;
//! and blends the two linearly over 0.5 us ending 3 us after the asperity's breakaway. The build checks itself:
//! at midpoints of the head grid it compares atoms with the forward model
//! (`check_error`, relative L2).
#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inverse/friction_envelope.hpp"
#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

struct AtomTableSettings {
  double head_log_step = 0.01;            //!< ln k step of the head grid
  double tail_log_step = 0.05;            //!< ln k step of the tail-parameter grid
  double head_after_breakaway_s = 3e-6;   //!< heads reach this far past the latest breakaway [s]
  double blend_s = 0.5e-6;                //!< head-to-tail cross-fade [s]
  std::size_t checks = 8;                 //!< midpoints compared with the forward model
};

//! What a table is made of, for storing it in a calibration bank and reading it back.
struct AtomTableData {
  double min_stiffness_n_per_m = 0.0;
  double max_stiffness_n_per_m = 0.0;
  AtomTableSettings settings;
  std::size_t head_samples = 0;                 //!< samples per head
  std::vector<double> heads;                    //!< [head][sample], row after row [V]
  std::vector<double> head_slopes;              //!< dV/dt of the heads, same layout [V/s]
  std::vector<double> tail_shift_s;             //!< e_k on the tail grid [s]
  std::vector<double> tail_phase_rad;           //!< phi_k on the tail grid [rad]
  std::vector<double> tail_fit_error;           //!< relative L2 misfit of each tail fit [-]
  double check_error = 0.0;                     //!< worst relative L2 error at the check points [-]
};

//! The forward runs a table over [k_min, k_max] makes, for the work estimate
//! (inverse/inversion_work.hpp): over the whole grid (tails and checks) and over the heads
//! only, and how many samples a head holds.
struct AtomTableRuns {
  std::size_t full = 0;
  std::size_t heads = 0;
  std::size_t head_samples = 0;
};
AtomTableRuns atom_table_runs(const KnownDevice& device, const RecordGrid& grid, double min_stiffness_n_per_m,
                              double max_stiffness_n_per_m, const AtomTableSettings& settings = {});

class AtomTable {
 public:
  //! Builds the table for stiffnesses in [k_min, k_max] on `grid` (costs ~1 s: one forward
  //! run per tail-grid point and check, a short one per head).
  //! @throws InputError when the range holds stiffnesses whose asperity would reach l.
  AtomTable(const KnownDevice& device, const RecordGrid& grid, double min_stiffness_n_per_m,
            double max_stiffness_n_per_m, const AtomTableSettings& settings = {});
  //! Rebuilds a stored table (only the envelope is recomputed).
  AtomTable(const KnownDevice& device, const RecordGrid& grid, AtomTableData data);

  //! V_1(t_m; k) for every sample m [V]; if not empty, dV_1/d ln k [V] and dV_1/dt [V/s].
  //! k is clamped to the table's range.
  void evaluate(double stiffness_n_per_m, std::span<double> value, std::span<double> d_dlnk = {},
                std::span<double> d_dt = {}) const;
  //! sum_m V_1(t_m; k)^2 [V^2].
  [[nodiscard]] double energy(double stiffness_n_per_m) const;

  [[nodiscard]] double min_stiffness() const { return data_.min_stiffness_n_per_m; }
  [[nodiscard]] double max_stiffness() const { return data_.max_stiffness_n_per_m; }
  [[nodiscard]] const AtomTableData& data() const { return data_; }
  [[nodiscard]] const KnownDevice& device() const { return device_; }
  [[nodiscard]] const RecordGrid& grid() const { return grid_; }
  //! Mean displacement the asperity oscillates about, F / k [m].
  [[nodiscard]] double equilibrium_displacement(double stiffness_n_per_m) const;
  //! Breakaway time estimate of the belt-dragged asperity [s] (closed form, for proposals).
  [[nodiscard]] double breakaway_time(double stiffness_n_per_m) const;
  //! The tail's phase phi_k and envelope shift e_k (interpolated).
  void tail_parameters(double stiffness_n_per_m, double& shift_s, double& phase_rad) const;
  [[nodiscard]] const FrictionEnvelope& envelope() const { return envelope_; }

 private:
  void build_tails();
  void build_heads();
  void check();
  void finish();
  void make_splines();
  [[nodiscard]] std::size_t tail_points() const;
  [[nodiscard]] std::size_t head_points() const;

  KnownDevice device_;
  RecordGrid grid_;
  AtomTableData data_;
  FrictionEnvelope envelope_;
  //! First sample of the head-to-tail cross-fade for stiffness k (heads are shorter for
  //! stiffer asperities, which break away sooner and whose phase moves faster with k).
  [[nodiscard]] std::size_t blend_start(double stiffness_n_per_m) const;

  std::size_t blend_samples_ = 0;  // length of the cross-fade
  std::size_t tail_start_ = 0;     // samples every head holds
  using Spline = boost::math::interpolators::cardinal_cubic_b_spline<double>;
  std::optional<Spline> shift_spline_;  // tail corrections against ln k
  std::optional<Spline> phase_spline_;
};

}  // namespace stengmc
