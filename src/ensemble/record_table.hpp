#pragma once
//! The records of an ensemble as columns: one entry per realisation (by grid point, then
//! id) and the per-asperity columns flat over them. What the ensemble file's /realisations
//! and /asperities hold and what the Python module returns, built once for both.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ensemble/realisation_record.hpp"
#include "ensemble/sweep.hpp"
#include "stats/ensemble_statistics.hpp"

namespace stengmc {

struct RecordTable {
  std::vector<std::int64_t> grid_point;       //!< the grid point of each realisation
  std::vector<std::int64_t> realisation;      //!< its id
  std::vector<std::int64_t> valid;            //!< 1 valid, 0 not
  std::vector<std::string> failure;           //!< why not ("" when valid)
  std::vector<std::int64_t> asperity_offset;  //!< realisation i's asperities: [offset[i], offset[i+1])
  std::array<std::vector<double>, SCALAR_COUNT> scalars;                //!< by Scalar
  std::array<std::vector<double>, ASPERITY_COLUMN_COUNT> asperities;  //!< by AsperityColumn
};

RecordTable tabulate_records(const std::vector<GridPoint>& grid);

//! One interval of every grid point's summary, as the columns <name>, <name>_low,
//! <name>_high, <name>_known, <name>_method of /summary.
struct IntervalColumns {
  std::vector<double> estimate, low, high;
  std::vector<std::int64_t> known;  //!< 1 when the interval could be computed
  std::vector<std::string> method;
};

IntervalColumns tabulate_intervals(const std::vector<GridPoint>& grid,
                                   const std::function<const Interval&(const GridPoint&)>& pick);

}  // namespace stengmc
