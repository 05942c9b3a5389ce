#include "io/ensemble_file.hpp"

#include <cstdint>
#include <functional>

#include "core/hdf5_file.hpp"
#include "ensemble/record_table.hpp"
#include "io/run_file.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc {

namespace {

void write_grid(Hdf5Writer& f, const StudyFile& base, const std::vector<GridPoint>& grid) {
  const EnsembleSettings& e = *base.ensemble;
  if (e.sweep.empty()) return;
  std::vector<std::string> names;
  for (const SweepAxis& axis : e.sweep) names.push_back(axis.parameter);
  f.write("/grid/parameter", names);
  std::vector<std::vector<double>> values;
  for (const GridPoint& point : grid) {
    values.emplace_back();
    for (const ParameterOverride& o : point.overrides) values.back().push_back(o.value);
  }
  f.write("/grid/values", values);
}

void write_realisations(Hdf5Writer& f, const std::vector<GridPoint>& grid) {
  const RecordTable t = tabulate_records(grid);
  f.write("/realisations/grid_point", t.grid_point);
  f.write("/realisations/realisation", t.realisation);
  f.write("/realisations/valid", t.valid);
  f.write("/realisations/failure", t.failure);
  f.write("/realisations/asperity_offset", t.asperity_offset);
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k)
    f.write("/realisations/" + std::string(scalar_info(static_cast<Scalar>(k)).name), t.scalars[k]);
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c)
    f.write("/asperities/" + std::string(column_info(static_cast<AsperityColumn>(c)).name), t.asperities[c]);
}

//! [[ensemble.draw]] values, one row per realisation in /realisations order.
void write_draws(Hdf5Writer& f, const StudyFile& base, const std::vector<GridPoint>& grid) {
  const auto& draws = base.ensemble->draws;
  if (draws.empty()) return;
  std::vector<std::string> names;
  for (const DrawAxis& d : draws) names.push_back(d.parameter);
  std::vector<std::vector<double>> rows;
  for (const GridPoint& point : grid)
    for (const RealisationRecord& r : point.run.records) {
      std::vector<double> row;
      for (const DrawAxis& d : draws) {
        const RecordExtra* e = r.extra("draw:" + d.parameter);
        row.push_back(e && !e->values.empty() ? e->values.front() : 0.0);
      }
      rows.push_back(std::move(row));
    }
  f.write("/draws/parameter", names);
  f.write("/draws/values", rows);
}

void write_traces(Hdf5Writer& f, const std::vector<GridPoint>& grid) {
  for (std::size_t g = 0; g < grid.size(); ++g)
    for (const RealisationRecord& r : grid[g].run.records) {
      if (r.time_s.empty()) continue;
      const std::string base = grid.size() == 1 ? "/traces" : "/traces/point_" + std::to_string(g);
      const std::string group = base + "/realisation_" + std::to_string(r.realisation);
      f.write(group + "/time", r.time_s);
      f.write(group + "/voltage", r.voltage_v);
      f.write(group + "/charge", r.charge_c);
      if (!r.measured_voltage_v.empty()) f.write(group + "/measured_voltage", r.measured_voltage_v);
    }
}

//! One interval per grid point, as datasets <name>, <name>_low, <name>_high.
void write_intervals(Hdf5Writer& f, const std::string& group, const std::string& name, const std::vector<GridPoint>& grid,
                     const std::function<const Interval&(const GridPoint&)>& pick) {
  const IntervalColumns c = tabulate_intervals(grid, pick);
  f.write(group + "/" + name, c.estimate);
  f.write(group + "/" + name + "_low", c.low);
  f.write(group + "/" + name + "_high", c.high);
  f.write(group + "/" + name + "_known", c.known);
  f.write(group + "/" + name + "_method", c.method);
}

void write_summary(Hdf5Writer& f, const std::vector<GridPoint>& grid) {
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const ScalarInfo& info = scalar_info(static_cast<Scalar>(k));
    const std::string g = "/summary/" + std::string(info.name);
    std::vector<std::int64_t> count;
    std::vector<double> min, max;
    for (const GridPoint& point : grid) {
      const ScalarSummary& v = point.summary.scalars[k];
      count.push_back(static_cast<std::int64_t>(v.count));
      min.push_back(v.min);
      max.push_back(v.max);
    }
    f.write(g + "/count", count);
    f.write(g + "/min", min);
    f.write(g + "/max", max);
    write_intervals(f, g, "mean", grid, [k](const GridPoint& p) -> const Interval& { return p.summary.scalars[k].mean; });
    write_intervals(f, g, "std", grid,
                    [k](const GridPoint& p) -> const Interval& { return p.summary.scalars[k].standard_deviation; });
    write_intervals(f, g, "median", grid, [k](const GridPoint& p) -> const Interval& { return p.summary.scalars[k].median; });
    write_intervals(f, g, "p05", grid, [k](const GridPoint& p) -> const Interval& { return p.summary.scalars[k].p05; });
    write_intervals(f, g, "p95", grid, [k](const GridPoint& p) -> const Interval& { return p.summary.scalars[k].p95; });
  }
  write_intervals(f, "/summary/pooled", "fft_ratio", grid, [](const GridPoint& p) -> const Interval& { return p.summary.fft_pooled_ratio; });
  write_intervals(f, "/summary/pooled", "hr_ratio", grid, [](const GridPoint& p) -> const Interval& { return p.summary.hr_pooled_ratio; });
  write_intervals(f, "/summary/pooled", "valid_fraction", grid,
                  [](const GridPoint& p) -> const Interval& { return p.summary.valid_fraction; });
  std::vector<double> width;
  std::vector<std::int64_t> met;
  for (const GridPoint& point : grid) {
    width.push_back(point.run.target_half_width_reached);
    met.push_back(point.run.target_met ? 1 : 0);
  }
  f.write("/summary/target/half_width", width);
  f.write("/summary/target/met", met);
}

}  // namespace

void write_ensemble_file(const std::string& path, const StudyFile& base, const std::vector<GridPoint>& grid) {
  Hdf5Writer file(path, describe_output);
  write_provenance(file, {.file_type = "stengmc-ensemble",
                          .input_file = base.file,
                          .input_text = base.text,
                          .seed = base.seed,
                          .surface_file = base.surface_file,
                          .surface_text = base.surface_text,
                          .auxiliary_inputs = base.surface->auxiliary_inputs()});
  write_netlist_provenance(file, base.netlist);
  const EnsembleSettings& e = *base.ensemble;
  std::size_t run = 0, valid = 0;
  bool stopped = false;
  for (const GridPoint& point : grid) {
    run += point.run.records.size();
    valid += point.summary.valid;
    stopped = stopped || point.run.stopped_at_target;
  }
  file.attribute("/", "title", base.title);
  file.attribute("/", "grid_points", static_cast<std::int64_t>(grid.size()));
  file.attribute("/", "realisations_requested", static_cast<std::int64_t>(e.realisations));
  file.attribute("/", "realisations_run", static_cast<std::int64_t>(run));
  file.attribute("/", "valid_realisations", static_cast<std::int64_t>(valid));
  file.attribute("/", "stopped_at_target", static_cast<std::int64_t>(stopped ? 1 : 0));
  file.attribute("/", "target_statistic", e.target ? scalar_info(*e.target).name : "");
  file.attribute("/", "target_half_width", e.target_half_width);
  const auto& only = grid.front().run.only;
  file.attribute("/", "only_realisation", static_cast<std::int64_t>(only ? static_cast<std::int64_t>(*only) : -1));
  write_grid(file, base, grid);
  write_realisations(file, grid);
  write_draws(file, base, grid);
  write_traces(file, grid);
  write_summary(file, grid);
  file.commit();
}

}  // namespace stengmc
