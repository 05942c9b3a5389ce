#pragma once
//! Parameter sweeps: every grid point of [[ensemble.sweep]] is an ensemble of the same
//! realisation ids under its own parameter values (docs/ensembles.md).
#include <string>
#include <vector>

#include "ensemble/ensemble_runner.hpp"
#include "ensemble/ensemble_summary.hpp"
#include "ensemble/study_file.hpp"

namespace stengmc {

struct GridPoint {
  std::vector<ParameterOverride> overrides;  //!< one per sweep axis (none without a sweep)
  StudyFile study;                              //!< the study read with them
  EnsembleRun run;
  EnsembleSummary summary;
};

//! Reads the study at every grid point of `base`'s sweep (a single point without one), so
//! a value that breaks the study is reported before anything runs, naming the point. So
//! is a point whose work no realisation could do within `limits` (with the fewest
//! asperities it may draw: one for a random surface), and records that would not fit.
std::vector<GridPoint> prepare_grid(const StudyFile& base, const WorkLimits& limits = {});

//! "param = value, ..." of a grid point, for messages; with `short_names`, each parameter
//! by its last key only ("count = 4"), for tables.
std::string describe_grid_point(const GridPoint& point, bool short_names = false);

//! The journal of grid point `index` of `count` beside the output `out`.
std::string journal_path(const std::string& out, std::size_t index, std::size_t count);

}  // namespace stengmc
