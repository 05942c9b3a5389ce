#include "ensemble/record_table.hpp"

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

IntervalColumns tabulate_intervals(const std::vector<GridPoint>& grid,
                                   const std::function<const Interval&(const GridPoint&)>& pick) {
  IntervalColumns c;
  for (const GridPoint& point : grid) {
    const Interval& i = pick(point);
    c.estimate.push_back(i.estimate);
    c.low.push_back(i.low);
    c.high.push_back(i.high);
    c.known.push_back(i.known ? 1 : 0);
    c.method.push_back(i.method);
  }
  return c;
}

}  // namespace stengmc
