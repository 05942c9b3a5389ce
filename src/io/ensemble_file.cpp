#include "io/ensemble_file.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <type_traits>
#include <variant>

#include "core/hdf5_file.hpp"
#include "ensemble/record_table.hpp"
#include "io/ensemble_coordinates.hpp"
#include "io/run_file.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc {

namespace {

void write_grid(Hdf5Writer& f, const StudyFile& base, const std::vector<GridPoint>& grid, const EnsembleAxes& axes) {
  const EnsembleSettings& e = *base.ensemble;
  if (e.sweep.empty()) return;
  std::vector<std::string> names;
  for (const SweepAxis& axis : e.sweep) names.push_back(axis.parameter);
  f.write("/grid/parameter", names);
  f.write("/grid/values", tabulate_grid(grid));
  write_grid_coordinates(f, "/grid", axes, grid, {"/grid/values"});
}

void write_realisations(Hdf5Writer& f, const std::vector<GridPoint>& grid, const EnsembleAxes& axes, bool draws) {
  const RecordTable t = tabulate_records(grid);
  f.write("/realisations/grid_point", t.grid_point);
  f.write("/realisations/realisation", t.realisation);
  f.write("/realisations/valid", t.valid);
  f.write("/realisations/failure", t.failure);
  f.write("/realisations/asperity_offset", t.asperity_offset);
  std::vector<std::string> per_member{"/realisations/valid", "/realisations/failure"};
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    per_member.push_back("/realisations/" + std::string(scalar_info(static_cast<Scalar>(k)).name));
    f.write(per_member.back(), t.scalars[k]);
  }
  write_member_coordinates(f, axes, grid, per_member, draws);
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c)
    f.write("/asperities/" + std::string(column_info(static_cast<AsperityColumn>(c)).name), t.asperities[c]);
}

//! [[ensemble.draw]] values, one row per realisation in /realisations order.
void write_draws(Hdf5Writer& f, const StudyFile& base, const std::vector<GridPoint>& grid) {
  const auto& draws = base.ensemble->draws;
  if (draws.empty()) return;
  std::vector<std::string> names;
  for (const DrawAxis& d : draws) names.push_back(d.parameter);
  f.write("/draws/parameter", names);
  f.write("/draws/values", tabulate_draws(draws, grid));
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

//! The target's half-width is in the target statistic's unit, which only the settings know.
void write_summary(Hdf5Writer& f, const std::vector<GridPoint>& grid, std::optional<Scalar> target,
                   const EnsembleAxes& axes) {
  std::map<std::string, std::vector<std::string>> groups;  // each group's variables, for its coordinates
  for (const SummaryColumn& c : tabulate_summary(grid))
    std::visit(
        [&](const auto& values) {
          const std::string path = "/summary/" + c.group + "/" + c.name;
          groups["/summary/" + c.group].push_back(path);
          if constexpr (std::is_same_v<std::decay_t<decltype(values)>, std::vector<double>>)
            if (target && path == "/summary/target/half_width")
              return f.write_with_units(path, values, scalar_info(*target).unit);
          f.write(path, values);
        },
        c.values);
  for (const auto& [group, variables] : groups) write_grid_coordinates(f, group, axes, grid, variables);
}

}  // namespace

void write_ensemble_file(const std::string& path, const StudyFile& base, const std::vector<GridPoint>& grid) {
  const EnsembleAxes axes = ensemble_axes(*base.ensemble, grid);
  Hdf5Writer file(path, describe_ensemble_output(axes));
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
  // Only a file merged from an unfinished run carries these (merge --partial): every other
  // file keeps the attributes it always had.
  if (std::any_of(grid.begin(), grid.end(), [](const GridPoint& p) { return p.run.partial; })) {
    file.attribute("/", "partial", std::int64_t{1});
    file.attribute("/", "realisations_expected", static_cast<std::int64_t>(e.realisations * grid.size()));
    file.attribute("/", "realisations_present", static_cast<std::int64_t>(run));
  }
  write_grid(file, base, grid, axes);
  write_realisations(file, grid, axes, !e.draws.empty());
  write_draws(file, base, grid);
  write_traces(file, grid);
  write_summary(file, grid, e.target, axes);
  file.commit();
}

}  // namespace stengmc
