#include "ensemble/ensemble_settings.hpp"

#include <boost/random/uniform_int_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "core/format.hpp"

namespace stengmc {

namespace {
// Realisation ids are written as int64 everywhere.
constexpr long long MAX_REALISATIONS = std::numeric_limits<std::int64_t>::max();

//! The `parameter` of a sweep axis or a draw: a dotted study key, not one of the ensemble's
//! own (`verb`: "vary" / "draw"; `participle`: "swept" / "drawn").
std::string read_parameter(TomlTable& entry, const std::string& verb, const std::string& participle, const std::string& example) {
  std::string parameter = entry.string("parameter", "");
  if (parameter.empty()) entry.fail("parameter", "is missing: the dotted key to " + verb + ", e.g. \"" + example + "\"");
  if (parameter.rfind("ensemble.", 0) == 0 || parameter == "seed")
    entry.fail("parameter", "= \"" + parameter + "\" cannot be " + participle + " (it defines the ensemble itself)");
  return parameter;
}

}  // namespace

EnsembleSettings read_ensemble_settings(TomlTable& t) {
  EnsembleSettings s;
  if (!t.has("realisations"))
    t.fail("realisations", "is missing: the number of realisations (with a target: the most that may be drawn)");
  s.realisations = static_cast<std::uint64_t>(t.integer("realisations", 0, 1));
  if (t.has("target_statistic")) {
    const std::string name = t.string("target_statistic", "");
    Scalar scalar{};
    if (!scalar_by_name(name, scalar))
      t.fail("target_statistic", "= \"" + name + "\" is not a per-realisation scalar; expected one of " + scalar_names());
    s.target = scalar;
    if (!t.has("target_half_width"))
      t.fail("target_half_width", "is missing: target_statistic needs the 95 % CI half-width to stop at");
    s.target_half_width = t.positive("target_half_width", 0.0);
  } else if (t.has("target_half_width")) {
    t.fail("target_half_width", "needs target_statistic = \"...\" (which statistic's mean to converge)");
  }
  s.batch = static_cast<std::uint64_t>(t.integer("batch", static_cast<long long>(s.batch), 1));
  if (t.has("trace_realisations")) {
    s.trace_realisations.clear();
    for (double v : t.number_list("trace_realisations")) {
      if (v < 0.0 || v != std::floor(v) || v > static_cast<double>(MAX_REALISATIONS))
        t.fail("trace_realisations", "entry " + format_number(v) + " is not a realisation id (an integer >= 0)");
      s.trace_realisations.push_back(static_cast<std::uint64_t>(v));
    }
  }
  s.trace_all = t.boolean("trace_all", false);
  for (TomlTable& entry : t.table_array("draw")) {
    DrawAxis d;
    d.parameter = read_parameter(entry, "draw", "drawn", "noise.snr_db");
    for (const DrawAxis& other : s.draws)
      if (other.parameter == d.parameter) entry.fail("parameter", "= \"" + d.parameter + "\" is drawn twice");
    const std::string kind = entry.choice("kind", "uniform", {"uniform", "integer", "choice"});
    if (kind == "choice") {
      d.kind = DrawAxis::Kind::choice;
      d.values = entry.number_list("values");
      if (d.values.empty()) entry.fail("values", "is missing or empty: the values a choice draws from");
    } else {
      d.kind = kind == "uniform" ? DrawAxis::Kind::uniform : DrawAxis::Kind::integer;
      if (!entry.has("min") || !entry.has("max")) entry.fail("min", "and max are required for a " + kind + " draw");
      d.min = entry.number("min", 0.0);
      d.max = entry.number("max", 0.0);
      if (!(d.min <= d.max)) entry.fail("max", "= " + format_number(d.max) + " must be >= min = " + format_number(d.min));
      if (d.kind == DrawAxis::Kind::integer && (d.min != std::floor(d.min) || d.max != std::floor(d.max)))
        entry.fail("min", "and max of an integer draw must be whole numbers");
    }
    s.draws.push_back(std::move(d));
  }
  std::size_t grid = 1;
  for (TomlTable& axis : t.table_array("sweep")) {
    SweepAxis a;
    a.parameter = read_parameter(axis, "vary", "swept", "model.belt_velocity_m_per_s");
    a.values = axis.number_list("values");
    if (a.values.empty()) axis.fail("values", "is missing or empty: the values the parameter takes");
    for (const SweepAxis& other : s.sweep)
      if (other.parameter == a.parameter) axis.fail("parameter", "= \"" + a.parameter + "\" is swept twice");
    grid *= a.values.size();
    if (grid > MAX_GRID_POINTS)
      axis.fail("values", "makes the grid " + std::to_string(grid) + " points, above the limit of " +
                              std::to_string(MAX_GRID_POINTS));
    s.sweep.push_back(std::move(a));
  }
  for (TomlTable& entry : t.table_array("draw"))
    for (const SweepAxis& axis : s.sweep)
      if (entry.string("parameter", "") == axis.parameter)
        entry.fail("parameter", "= \"" + axis.parameter + "\" is both swept and drawn: choose one");
  return s;
}

std::size_t EnsembleSettings::grid_size() const {
  std::size_t size = 1;
  for (const SweepAxis& axis : sweep) size *= axis.values.size();
  return size;
}

std::vector<double> EnsembleSettings::grid_values(std::size_t point) const {
  std::vector<double> values(sweep.size());
  for (std::size_t a = sweep.size(); a-- > 0;) {
    values[a] = sweep[a].values[point % sweep[a].values.size()];
    point /= sweep[a].values.size();
  }
  return values;
}

double DrawAxis::draw(RandomEngine& engine) const {
  switch (kind) {
    case Kind::uniform:
      return min == max ? min : boost::random::uniform_real_distribution<double>(min, max)(engine);
    case Kind::integer:
      return static_cast<double>(
          boost::random::uniform_int_distribution<long long>(static_cast<long long>(min), static_cast<long long>(max))(engine));
    case Kind::choice:
      return values[boost::random::uniform_int_distribution<std::size_t>(0, values.size() - 1)(engine)];
  }
  return min;
}


}  // namespace stengmc
