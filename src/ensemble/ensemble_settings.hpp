#pragma once
//! The [ensemble] table of a study (docs/ensembles.md).
#include <cstdint>
#include <string>
#include <optional>
#include <vector>

#include "core/random_stream.hpp"
#include "ensemble/realisation_record.hpp"
#include "core/toml_reader.hpp"

namespace stengmc {

//! One axis of a parameter sweep: a dotted key of the study ("model.belt_velocity_m_per_s";
//! "surface.<table>.<key>" reaches into a surface file the study names) and its values.
struct SweepAxis {
  std::string parameter;
  std::vector<double> values;
};

//! One parameter drawn afresh for every realisation ([[ensemble.draw]]): a prior over a
//! study key, where a sweep is a grid. Realisation r's value comes from the stream
//! (seed, r, draws, index of the draw) alone.
struct DrawAxis {
  enum class Kind { uniform, integer, choice };
  std::string parameter;        //!< dotted key, as a sweep's
  Kind kind = Kind::uniform;
  double min = 0.0, max = 0.0;  //!< uniform on [min, max); integer: uniform on min .. max
  std::vector<double> values;   //!< choice: one of these, equally likely

  //! The value for a realisation, from that realisation's stream of this draw.
  [[nodiscard]] double draw(RandomEngine& engine) const;
};

//! How many realisations, and which keep their traces.
struct EnsembleSettings {
  //! Fixed size K; with a target, the most the run may draw.
  std::uint64_t realisations = 0;
  //! Optional stopping rule: stop once the 95 % CI half-width of the mean of `target`
  //! is at most `target_half_width` (checked after every `batch` realisations, in id
  //! order, so where it stops does not depend on the number of threads).
  std::optional<Scalar> target;
  double target_half_width = 0.0;
  std::uint64_t batch = 64;
  //! Realisations whose time, voltage and charge traces are written.
  std::vector<std::uint64_t> trace_realisations{0};
  //! Every realisation keeps its traces (trace_all = true), e.g. to invert them later.
  bool trace_all = false;
  //! [[ensemble.draw]]: parameters drawn per realisation (applied after a sweep's values).
  std::vector<DrawAxis> draws;
  //! [[ensemble.sweep]] axes: every combination of their values (the first axis varying
  //! slowest) is a grid point, each an ensemble of the same realisation ids (common random
  //! numbers: differences between grid points are not blurred by different draws).
  std::vector<SweepAxis> sweep;

  //! Grid points: the product of the axes' sizes (1 without a sweep).
  [[nodiscard]] std::size_t grid_size() const;
  //! The value of each axis at grid point `point`.
  [[nodiscard]] std::vector<double> grid_values(std::size_t point) const;
};

//! Most grid points a sweep may have.
inline constexpr std::size_t MAX_GRID_POINTS = 10'000;

EnsembleSettings read_ensemble_settings(TomlTable& table);

}  // namespace stengmc
