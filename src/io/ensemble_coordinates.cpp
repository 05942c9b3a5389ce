#include "io/ensemble_coordinates.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <optional>

#include "io/output_vocabulary.hpp"

namespace stengmc {

namespace {

constexpr const char* MEMBER = "member";
constexpr const char* GRID_POINT = "grid_point";

std::vector<std::int64_t> indices(std::size_t count) {
  std::vector<std::int64_t> out(count);
  std::iota(out.begin(), out.end(), std::int64_t{0});
  return out;
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

bool in_grid_group(const std::string& path) { return path.starts_with("/grid/") || path.starts_with("/summary/"); }

std::string base_name(const std::string& path) { return path.substr(path.rfind('/') + 1); }

//! The coordinates this file adds, which the shared vocabulary does not know.
std::optional<DatasetDescription> describe_coordinate(const EnsembleAxes& axes, const std::string& path) {
  const std::string name = base_name(path);
  if (in_grid_group(path)) {
    if (name == GRID_POINT)
      return DatasetDescription{"1", "grid point (the first swept parameter varying slowest)", {GRID_POINT}};
    for (std::size_t a = 0; a < axes.variables.size(); ++a)
      if (name == axes.variables[a])  // a product grid's axis, else a value per grid point
        return DatasetDescription{"", "swept parameter " + axes.parameters[a],
                                  {axes.product() ? axes.variables[a] : axes.grid_dimension},
                                  "in the unit of the study key " + axes.parameters[a]};
  }
  if (path.starts_with("/realisations/"))
    for (std::size_t a = 0; a < axes.variables.size(); ++a)
      if (name == axes.variables[a])
        return DatasetDescription{"", "swept parameter " + axes.parameters[a] + " at the member's grid point", {MEMBER},
                                  "in the unit of the study key " + axes.parameters[a]};
  if (path == "/realisations/member" || path == "/draws/member" || path == "/asperities/member")
    return DatasetDescription{"1", "ensemble member: row of /realisations (by grid point, then realisation id)", {MEMBER}};
  if (path == "/realisations/realisation_boundary")
    return DatasetDescription{"1", "boundary between members in /realisations/asperity_offset", {"realisation_boundary"}};
  if (path == "/asperities/asperity")
    return DatasetDescription{"1", "row of /asperities (every member's asperities in turn)", {"asperity"}};
  if (path == "/asperities/asperity_count")
    return DatasetDescription{"1", "asperities of each member (count of the contiguous ragged array)", {MEMBER}};
  return std::nullopt;
}

}  // namespace

namespace {

//! Each parameter's values in the order of first appearance, if `grid` is their product
//! with the first parameter varying slowest (so /summary's flat columns reshape to them in
//! C order); nothing otherwise (a repeated value).
std::vector<std::vector<double>> product_axes(std::size_t parameters, const std::vector<GridPoint>& grid) {
  if (parameters == 0) return {};
  std::vector<std::vector<double>> values(parameters);
  for (const GridPoint& point : grid)
    for (std::size_t a = 0; a < parameters; ++a)
      if (std::find(values[a].begin(), values[a].end(), point.overrides[a].value) == values[a].end())
        values[a].push_back(point.overrides[a].value);
  std::size_t size = 1;
  for (const std::vector<double>& v : values) size *= v.size();
  if (size != grid.size()) return {};
  for (std::size_t g = 0; g < grid.size(); ++g) {
    std::size_t rest = g;  // g's digits in the mixed radix of the axes' lengths, last fastest
    for (std::size_t a = parameters; a-- > 0;) {
      if (grid[g].overrides[a].value != values[a][rest % values[a].size()]) return {};
      rest /= values[a].size();
    }
  }
  return values;
}

}  // namespace

EnsembleAxes ensemble_axes(const EnsembleSettings& settings, const std::vector<GridPoint>& grid) {
  EnsembleAxes axes;
  for (const SweepAxis& axis : settings.sweep) {
    axes.parameters.push_back(axis.parameter);
    std::string variable = axis.parameter;
    std::replace(variable.begin(), variable.end(), '.', '_');  // a Python name: .sel(name=value)
    axes.variables.push_back(variable);
  }
  axes.values = product_axes(axes.variables.size(), grid);
  axes.grid_dimension = axes.product() && axes.variables.size() == 1 ? axes.variables.front() : GRID_POINT;
  axes.summary_dimensions = axes.product() ? axes.variables : std::vector<std::string>{axes.grid_dimension};
  return axes;
}

Hdf5Writer::Describer describe_ensemble_output(const EnsembleAxes& axes) {
  return [axes](const std::string& path) {
    if (auto coordinate = describe_coordinate(axes, path)) return *coordinate;
    DatasetDescription d = describe_output(path);
    if (path.starts_with("/summary/") && d.dimensions == std::vector<std::string>{GRID_POINT}) {
      // One axis per swept parameter of a product grid: the flat column, reshaped.
      d.dimensions = axes.summary_dimensions;
      for (const std::vector<double>& v : axes.values) d.shape.push_back(v.size());
      return d;
    }
    const bool per_member = path.starts_with("/realisations/") || path.starts_with("/draws/");
    for (std::string& dimension : d.dimensions) {
      if (dimension == GRID_POINT) dimension = axes.grid_dimension;
      if (dimension == "realisation" && per_member) dimension = MEMBER;
    }
    return d;
  };
}

void write_grid_coordinates(Hdf5Writer& f, const std::string& group, const EnsembleAxes& axes,
                            const std::vector<GridPoint>& grid, const std::vector<std::string>& variables) {
  const std::vector<std::string>& dimensions =
      group.starts_with("/summary") ? axes.summary_dimensions : std::vector<std::string>{axes.grid_dimension};
  if (dimensions == std::vector<std::string>{GRID_POINT}) f.write(group + "/" + GRID_POINT, indices(grid.size()));
  if (axes.product()) {  // each parameter is its own dimension's coordinate
    for (std::size_t a = 0; a < axes.variables.size(); ++a) f.write(group + "/" + axes.variables[a], axes.values[a]);
    return;
  }
  for (std::size_t a = 0; a < axes.variables.size(); ++a) {
    std::vector<double> values;
    for (const GridPoint& point : grid) values.push_back(point.overrides[a].value);
    f.write(group + "/" + axes.variables[a], values);
  }
  // Not a product: the parameters are auxiliary coordinates of grid_point.
  if (!axes.variables.empty())
    for (const std::string& variable : variables) f.attribute(variable, "coordinates", joined(axes.variables));
}

void write_member_coordinates(Hdf5Writer& f, const EnsembleAxes& axes, const std::vector<GridPoint>& grid,
                              const std::vector<std::string>& realisation_variables, bool draws) {
  std::vector<std::int64_t> counts;
  std::vector<std::vector<double>> swept(axes.variables.size());  // each member's grid point's values
  for (const GridPoint& point : grid)
    for (const RealisationRecord& r : point.run.records) {
      counts.push_back(static_cast<std::int64_t>(r.asperity_count()));
      for (std::size_t a = 0; a < swept.size(); ++a) swept[a].push_back(point.overrides[a].value);
    }
  const std::size_t members = counts.size();
  f.write("/realisations/member", indices(members));
  f.write("/realisations/realisation_boundary", indices(members + 1));
  for (std::size_t a = 0; a < swept.size(); ++a) f.write("/realisations/" + axes.variables[a], swept[a]);
  // set_index(member=[<swept>, "realisation"]) then .sel(<swept>=value) picks a grid point's rows.
  const std::string coordinates = joined(axes.variables) + (axes.variables.empty() ? "" : " ") + "grid_point realisation";
  for (const std::string& variable : realisation_variables) f.attribute(variable, "coordinates", coordinates);
  if (draws) f.write("/draws/member", indices(members));
  f.write("/asperities/member", indices(members));
  f.write("/asperities/asperity_count", counts);
  f.attribute("/asperities/asperity_count", "sample_dimension", "asperity");
  f.write("/asperities/asperity", indices(static_cast<std::size_t>(std::accumulate(counts.begin(), counts.end(), std::int64_t{0}))));
}

}  // namespace stengmc
