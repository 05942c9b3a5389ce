#pragma once
//! `stengmc surface`: draw K realisations of a surface, assess each, and gather what the
//! figures compare them with (the target laws, the load-separation curve).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "surface/distribution.hpp"
#include "surface/surface.hpp"
#include "pipeline/validity.hpp"
#include "tribology/model1.hpp"
#include "tribology/model2.hpp"

namespace stengmc {

//! A law to draw over a histogram: a density on a grid, or (discrete laws) point masses.
struct TargetLaw {
  std::vector<double> value;    //!< grid or support points, in the quantity's unit
  std::vector<double> density;  //!< pdf on the grid (1/unit), or the probability of each point
  bool discrete = false;        //!< `fixed` laws: `density` holds probabilities
};

//! Total Hertz load of one realisation against the flat's separation (in interacting mode,
//! of the summits lowered by the solved interaction).
struct LoadSeparationCurve {
  std::uint64_t realisation = 0;
  std::vector<double> separation_m;  //!< d, from the highest summit down [m]
  std::vector<double> total_load_n;  //!< sum N_i(d) [N]
  double solved_separation_m = 0.0;  //!< the d that carries W [m]
  double nominal_load_n = 0.0;       //!< W [N]
};

struct SurfaceExamination {
  std::uint64_t seed = 0;
  ValidityThresholds thresholds;  //!< what the reports were judged against
  const RandomSurface* random_surface = nullptr;  //!< the surface examined (nullptr: a fixed list); outlives this
  std::vector<Population> populations;
  std::vector<ValidityReport> reports;
  std::optional<TargetLaw> heights_target;    //!< random surfaces
  std::optional<TargetLaw> stiffness_target;  //!< stiffness rule "sampled"
  std::optional<LoadSeparationCurve> load_separation;  //!< load rule "hertz", first realisation
};

//! The law as a curve: 400 points between its 1e-4 and 1 - 1e-4 quantiles (clipped to
//! its support), or its support points for `fixed`.
TargetLaw target_law(const Distribution& law);

//! Realisations first .. first + count - 1 of `surface` under `seed`, each assessed against
//! the given model parameters.
SurfaceExamination examine_surface(const Surface& surface, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                                   const Model1Params& model1, const Model2Params& model2, Progress* progress = nullptr,
                                   ModelScope scope = {});

//! The on-screen summary: a table of population statistics over the realisations and the
//! validity findings.
std::string format_surface_summary(const SurfaceExamination& examination);

}  // namespace stengmc
