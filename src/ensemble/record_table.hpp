#pragma once
//! The records of an ensemble as columns: one entry per realisation (by grid point, then
//! id) and the per-asperity columns flat over them. What the ensemble file's /realisations
//! and /asperities hold and what the Python module returns, built once for both.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ensemble/realisation_record.hpp"
#include "ensemble/sweep.hpp"

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

}  // namespace stengmc
