#include "ensemble/record_table.hpp"

#include <utility>

namespace stengmc {

RecordTable tabulate_records(const std::vector<GridPoint>& grid) {
  RecordTable t;
  t.asperity_offset.push_back(0);
  for (std::size_t g = 0; g < grid.size(); ++g)
    for (const RealisationRecord& r : grid[g].run.records) {
      t.grid_point.push_back(static_cast<std::int64_t>(g));
      t.realisation.push_back(static_cast<std::int64_t>(r.realisation));
      t.valid.push_back(r.valid ? 1 : 0);
      t.failure.push_back(r.failure);
      t.asperity_offset.push_back(t.asperity_offset.back() + static_cast<std::int64_t>(r.asperity_count()));
      for (std::size_t k = 0; k < SCALAR_COUNT; ++k) t.scalars[k].push_back(r.scalars[k]);
      for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c)
        t.asperities[c].insert(t.asperities[c].end(), r.asperities[c].begin(), r.asperities[c].end());
    }
  return t;
}

std::vector<std::vector<double>> tabulate_grid(const std::vector<GridPoint>& grid) {
  std::vector<std::vector<double>> rows;
  for (const GridPoint& point : grid) {
    rows.emplace_back();
    for (const ParameterOverride& o : point.overrides) rows.back().push_back(o.value);
  }
  return rows;
}

std::vector<std::vector<double>> tabulate_draws(const std::vector<DrawAxis>& draws, const std::vector<GridPoint>& grid) {
  std::vector<std::vector<double>> rows;
  for (const GridPoint& point : grid)
    for (const RealisationRecord& r : point.run.records) {
      rows.emplace_back();
      for (const DrawAxis& d : draws) {
        const RecordExtra* e = r.extra("draw:" + d.parameter);
        rows.back().push_back(e && !e->values.empty() ? e->values.front() : 0.0);
      }
    }
  return rows;
}

namespace {

//! A statistic of every grid point, as the column /summary/<group>/<name>.
template <typename T, typename Pick>
void add_column(std::vector<SummaryColumn>& out, const std::string& group, const std::string& name,
                const std::vector<GridPoint>& grid, Pick pick) {
  std::vector<T> values;
  for (const GridPoint& point : grid) values.push_back(static_cast<T>(pick(point)));
  out.push_back({group, name, std::move(values)});
}

//! An interval of every grid point, as the columns <name>, <name>_low, <name>_high,
//! <name>_known and <name>_method of `group`.
template <typename Pick>
void add_interval(std::vector<SummaryColumn>& out, const std::string& group, const std::string& name,
                  const std::vector<GridPoint>& grid, Pick pick) {
  add_column<double>(out, group, name, grid, [&](const GridPoint& p) { return pick(p).estimate; });
  add_column<double>(out, group, name + "_low", grid, [&](const GridPoint& p) { return pick(p).low; });
  add_column<double>(out, group, name + "_high", grid, [&](const GridPoint& p) { return pick(p).high; });
  add_column<std::int64_t>(out, group, name + "_known", grid, [&](const GridPoint& p) { return pick(p).known ? 1 : 0; });
  add_column<std::string>(out, group, name + "_method", grid, [&](const GridPoint& p) { return pick(p).method; });
}

}  // namespace

std::vector<SummaryColumn> tabulate_summary(const std::vector<GridPoint>& grid) {
  std::vector<SummaryColumn> out;
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const std::string g(scalar_info(static_cast<Scalar>(k)).name);
    auto scalar = [k](const GridPoint& p) -> const ScalarSummary& { return p.summary.scalars[k]; };
    add_column<std::int64_t>(out, g, "count", grid, [&](const GridPoint& p) { return scalar(p).count; });
    add_column<double>(out, g, "min", grid, [&](const GridPoint& p) { return scalar(p).min; });
    add_column<double>(out, g, "max", grid, [&](const GridPoint& p) { return scalar(p).max; });
    add_interval(out, g, "mean", grid, [&](const GridPoint& p) -> const Interval& { return scalar(p).mean; });
    add_interval(out, g, "std", grid, [&](const GridPoint& p) -> const Interval& { return scalar(p).standard_deviation; });
    add_interval(out, g, "median", grid, [&](const GridPoint& p) -> const Interval& { return scalar(p).median; });
    add_interval(out, g, "p05", grid, [&](const GridPoint& p) -> const Interval& { return scalar(p).p05; });
    add_interval(out, g, "p95", grid, [&](const GridPoint& p) -> const Interval& { return scalar(p).p95; });
  }
  add_interval(out, "pooled", "fft_ratio", grid, [](const GridPoint& p) -> const Interval& { return p.summary.fft_pooled_ratio; });
  add_interval(out, "pooled", "hr_ratio", grid, [](const GridPoint& p) -> const Interval& { return p.summary.hr_pooled_ratio; });
  add_interval(out, "pooled", "valid_fraction", grid,
               [](const GridPoint& p) -> const Interval& { return p.summary.valid_fraction; });
  add_column<double>(out, "target", "half_width", grid, [](const GridPoint& p) { return p.run.target_half_width_reached; });
  add_column<std::int64_t>(out, "target", "met", grid, [](const GridPoint& p) { return p.run.target_met ? 1 : 0; });
  return out;
}

}  // namespace stengmc
