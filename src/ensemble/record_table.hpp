#pragma once
//! The records of an ensemble as columns: one entry per realisation (by grid point, then
//! id) and the per-asperity columns flat over them; and the statistics of every grid point
//! as columns. What the ensemble file's /realisations, /asperities and /summary hold and
//! what the Python module returns, built once for both.
#include <array>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "ensemble/ensemble_settings.hpp"
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

//! The sweep's value of every axis at every grid point: a row a point, a column an
//! [[ensemble.sweep]] axis (/grid/values).
std::vector<std::vector<double>> tabulate_grid(const std::vector<GridPoint>& grid);

//! Each of `draws`' values per realisation: a row a realisation in the order of
//! RecordTable, a column a draw (/draws/values).
std::vector<std::vector<double>> tabulate_draws(const std::vector<DrawAxis>& draws, const std::vector<GridPoint>& grid);

//! One dataset of /summary over the grid points: /summary/<group>/<name>, with group a
//! scalar's name ("voltage_rms_v"), "pooled" or "target".
struct SummaryColumn {
  std::string group;
  std::string name;
  std::variant<std::vector<double>, std::vector<std::int64_t>, std::vector<std::string>> values;
};

//! Every dataset of /summary, in the order the ensemble file writes them: per scalar its
//! count, min and max, then the mean, std, median, p05 and p95 intervals, each as <name>,
//! <name>_low, <name>_high, <name>_known (1 when the interval could be computed) and
//! <name>_method; the pooled fft_ratio, hr_ratio and valid_fraction intervals; the
//! target's half_width reached and met (1 or 0).
std::vector<SummaryColumn> tabulate_summary(const std::vector<GridPoint>& grid);

}  // namespace stengmc
