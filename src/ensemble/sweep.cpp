#include "ensemble/sweep.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/format.hpp"
#include "pipeline/analyse_spectra.hpp"

namespace stengmc {

namespace {

//! Every realisation would fail alike on an analysis interval the run cannot hold: say it
//! before anything runs (a run cut short at x = l is another matter, see run_study).
void check_analysis_interval(const Study& study) {
  if (!study.spectrum) return;
  try {
    (void)analysis_range(study.grid().times(), *study.spectrum);
  } catch (const InputError& e) {
    throw InputError(study.file + ": [spectrum] start_s / end_s: " + e.what());
  }
}

//! Records stay in memory until the output is written (~600 bytes each plus ~100 per
//! asperity, plus the traces kept): refuse a study that cannot fit before it runs.
void check_memory(const std::vector<GridPoint>& grid, const WorkLimits& limits) {
  const double LIMIT_BYTES = limits.memory_bytes;
  double bytes = 0.0;
  for (const GridPoint& point : grid) {
    const StudyFile& s = point.study;
    const RandomSurface* random = s.surface->random_surface();
    const double asperities =
        random ? random->mean_summit_count() : static_cast<double>(s.surface->sample(0, 0).asperities.size());
    const double samples = std::round(s.duration_s * s.sample_rate_hz) + 1.0;
    bytes += static_cast<double>(s.ensemble->realisations) * (600.0 + 100.0 * asperities) +
             static_cast<double>(s.ensemble->trace_all ? s.ensemble->realisations : s.ensemble->trace_realisations.size()) *
                 (s.noise ? 32.0 : 24.0) * samples;
  }
  if (bytes > LIMIT_BYTES)
    throw InputError(grid.front().study.file + ": [ensemble] realisations = " +
                     std::to_string(grid.front().study.ensemble->realisations) + " over " + std::to_string(grid.size()) +
                     " grid point(s) would keep ~" + format_number(bytes / 1e9) + " GB of records in memory (limit " +
                     format_number(LIMIT_BYTES / 1e9) + " GB): run fewer realisations per study, or raise the limit "
                     "with --max-memory-gb");
}

}  // namespace

//! What every realisation of `study` costs at least: a random surface may draw a single
//! asperity, a fixed list always has its own.
void check_point_work(const Study& study, const WorkLimits& limits) {
  const double asperities =
      study.surface->random_surface() ? 1.0 : static_cast<double>(study.surface->sample(0, 0).asperities.size());
  check_work(estimate_run(study, asperities, false), limits,
             study.file + ": every realisation (at least " + format_number(asperities) + " asperit" +
                 (asperities == 1.0 ? "y" : "ies") + ")");
}

std::vector<GridPoint> prepare_grid(const StudyFile& base, const WorkLimits& limits) {
  const EnsembleSettings& settings = *base.ensemble;
  std::vector<GridPoint> grid(settings.grid_size());
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const std::vector<double> values = settings.grid_values(g);
    for (std::size_t a = 0; a < values.size(); ++a) grid[g].overrides.push_back({settings.sweep[a].parameter, values[a]});
    try {
      // From the study's text as first read (as run_realisation does), not the file again: a
      // study given as text (the Python module) has no file, and one edited meanwhile must
      // not split a grid between two versions.
      grid[g].study = grid[g].overrides.empty() ? base : parse_study_file(base.text, base.file, std::nullopt, grid[g].overrides);
      check_point_work(grid[g].study, limits);  // before anything the size of the run is allocated
      check_analysis_interval(grid[g].study);
    } catch (const InputError& e) {
      if (grid[g].overrides.empty()) throw;  // no sweep: the message already names the file
      throw InputError("grid point " + std::to_string(g + 1) + " of " + std::to_string(grid.size()) + " (" +
                       describe_grid_point(grid[g]) + "): " + e.what());
    }
  }
  check_memory(grid, limits);
  return grid;
}

std::string describe_grid_point(const GridPoint& point, bool short_names) {
  std::string out;
  for (const ParameterOverride& o : point.overrides) {
    const std::string name = short_names ? o.parameter.substr(o.parameter.rfind('.') + 1) : o.parameter;
    out += (out.empty() ? "" : ", ") + name + " = " + format_number(o.value);
  }
  return out;
}

std::string journal_path(const std::string& out, std::size_t index, std::size_t count) {
  return count == 1 ? out + ".journal" : out + ".point" + std::to_string(index) + ".journal";
}

}  // namespace stengmc
