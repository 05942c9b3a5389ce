#pragma once
//! Everything an inversion needs to draw atoms for one known device, prior and record grid
//! (docs/inverse.md, "atoms"): the device's friction in the atoms' units, the shape family
//! over the (Pi, zeta) the prior can reach, the envelopes of its loads and damping, and the
//! model that puts them on the record grid. Built once per device, prior and grid (a bank
//! keeps the shapes, the rest is rebuilt in ~0.1 s).
#include <memory>

#include "inverse/atom_model.hpp"
#include "inverse/atom_shapes.hpp"
#include "inverse/envelope_family.hpp"
#include "inverse/fit_layout.hpp"
#include "inverse/friction_ratios.hpp"
#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! What the atoms cover.
struct AtomCoverage {
  double min_stiffness_n_per_m = 0.0, max_stiffness_n_per_m = 0.0;  //!< k [N/m]
  double min_load_ratio = 1.0, max_load_ratio = 1.0;                //!< N_i / N [-]
  double min_damping_rate = 0.0, max_damping_rate = 0.0;            //!< d [1/s]
};

//! The coverage a prior's fits need: stiffnesses [k_low, k_high] (atom_range), the layout's
//! load and damping bounds.
AtomCoverage atom_coverage(double k_low, double k_high, const FitLayout& layout);

//! The shapes' range for `coverage` on `device` (f_ref its friction ratio's reference).
AtomShapeRange atom_shape_range(const KnownDevice& device, double reference_friction, const AtomCoverage& coverage);

//! How many forward runs the shapes of `range` take, and the longest, in radians (the
//! reference frame's omega0 = 1e7 rad/s makes a radian 100 ns).
struct AtomShapeWork {
  std::size_t runs = 0;
  double longest_rad = 0.0;
};
AtomShapeWork atom_shape_work(const AtomShapeRange& range, const AtomShapeSettings& settings = {});

class AtomLibrary {
 public:
  //! Builds the shapes with the forward model (~1 s).
  AtomLibrary(const KnownDevice& device, const RecordGrid& grid, const AtomCoverage& coverage);
  //! Rebuilds around stored shapes (a bank's).
  AtomLibrary(const KnownDevice& device, const RecordGrid& grid, const AtomCoverage& coverage, AtomShapeData shapes);
  AtomLibrary(const AtomLibrary&) = delete;
  AtomLibrary& operator=(const AtomLibrary&) = delete;

  [[nodiscard]] const AtomModel& model() const { return *model_; }
  [[nodiscard]] const KnownDevice& device() const { return device_; }
  [[nodiscard]] const RecordGrid& grid() const { return grid_; }
  [[nodiscard]] const AtomCoverage& coverage() const { return coverage_; }
  [[nodiscard]] const AtomShapes& shapes() const { return *shapes_; }
  [[nodiscard]] const FrictionRatios& ratios() const { return *ratios_; }
  [[nodiscard]] double min_stiffness() const { return coverage_.min_stiffness_n_per_m; }
  [[nodiscard]] double max_stiffness() const { return coverage_.max_stiffness_n_per_m; }
  //! Worst head error of the shapes against the forward model at their checks [-].
  [[nodiscard]] double check_error() const { return shapes_->data().check_error; }

 private:
  void build_envelopes();

  KnownDevice device_;
  RecordGrid grid_;
  AtomCoverage coverage_;
  std::unique_ptr<FrictionRatios> ratios_;
  std::unique_ptr<AtomShapes> shapes_;
  std::unique_ptr<EnvelopeFamily> envelopes_;
  std::unique_ptr<AtomModel> model_;
};

}  // namespace stengmc
