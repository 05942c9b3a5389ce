// Reading distributions from surface files: the TOML table and empirical histograms.
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/format.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/text_excerpt.hpp"
#include "core/toml_reader.hpp"
#include "surface/distribution.hpp"

namespace stengmc {

namespace {

}  // namespace

// ---------------------------------------------------------------- input

namespace {

double required_positive(TomlTable& t, std::string_view key) {
  const double v = t.required_number(key);
  if (!(v > 0.0)) t.fail(key, "= " + format_number(v) + " must be > 0");
  return v;
}

//! `values = [...]` of a fixed distribution: at least one number.
std::vector<double> read_values(TomlTable& t, std::string_view key) {
  if (!t.has(key)) t.fail(key, "is missing; the fixed distribution needs an array of numbers");
  std::vector<double> values = t.number_list(key);
  if (values.empty()) t.fail(key, "is empty; the fixed distribution needs at least one number");
  return values;
}

bool parse_double(std::string_view text, double& out) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  const auto value = parse_number(text);
  if (value) out = *value;
  return value.has_value();
}

}  // namespace

std::vector<Distribution::Bin> Distribution::read_histogram(const std::filesystem::path& file) {
  std::istringstream in(read_text_file(file.string(), "the histogram file"));
  std::vector<Bin> bins;
  std::string line;
  bool first_content = true;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = file.string() + ":" + std::to_string(number) + ": ";
    const auto start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    std::string_view rest(line);
    std::vector<std::string_view> fields;
    for (std::size_t comma; (comma = rest.find(',')) != std::string_view::npos; rest.remove_prefix(comma + 1))
      fields.push_back(rest.substr(0, comma));
    fields.push_back(rest);
    Bin b{};
    const bool numeric = fields.size() == 3 && parse_double(fields[0], b.lower) && parse_double(fields[1], b.upper) &&
                         parse_double(fields[2], b.weight);
    const bool header = first_content && line.find("lower") != std::string::npos;
    first_content = false;
    if (header) continue;
    if (!numeric) throw InputError(where + "expected three numbers 'lower,upper,weight', got '" + text_excerpt(line) + "'");
    if (!(b.upper > b.lower)) throw InputError(where + "upper = " + format_number(b.upper) + " must be > lower = " + format_number(b.lower));
    if (!std::isfinite(b.upper - b.lower))
      throw InputError(where + "the bin [" + format_number(b.lower) + ", " + format_number(b.upper) +
                       ") is wider than a double can hold (its width overflows)");
    if (b.weight < 0.0) throw InputError(where + "weight = " + format_number(b.weight) + " must be >= 0");
    if (!bins.empty() && b.lower < bins.back().upper)
      throw InputError(where + "lower = " + format_number(b.lower) + " overlaps the previous bin, which ends at " +
                       format_number(bins.back().upper) + " (bins must be increasing)");
    bins.push_back(b);
  }
  if (bins.empty()) throw InputError(file.string() + ": the histogram has no bins");
  double total = 0.0;
  for (const Bin& b : bins) total += b.weight;
  if (!(total > 0.0)) throw InputError(file.string() + ": the histogram's weights sum to zero");
  if (!std::isfinite(total)) throw InputError(file.string() + ": the histogram's weights sum beyond a double; scale them down");
  return bins;
}

Distribution Distribution::from_toml(TomlTable& t, const std::filesystem::path& base_dir) {
  std::vector<std::string_view> kinds;
  for (const ContinuousFamily& f : continuous_families()) kinds.push_back(f.name);
  kinds.insert(kinds.end(), {"uniform", "fixed", "empirical"});
  if (!t.has("kind")) {
    std::string allowed;
    for (std::string_view k : kinds) allowed += (allowed.empty() ? "" : ", ") + std::string(k);
    t.fail("kind", "is missing; expected one of " + allowed);
  }
  const std::string kind = t.choice("kind", "", kinds);
  if (kind == "uniform") {
    const double lo = t.required_number("min"), hi = t.required_number("max");
    if (!(hi > lo)) t.fail("max", "= " + format_number(hi) + " must be > min = " + format_number(lo));
    return uniform(lo, hi);
  }
  if (kind == "fixed") return fixed(read_values(t, "values"));
  if (kind == "empirical") {
    const std::string name = t.string("file", "");
    if (name.empty()) t.fail("file", "is missing; the empirical distribution needs a histogram file");
    const std::filesystem::path path = base_dir / name;  // an absolute name replaces base_dir
    try {
      Distribution law = empirical(read_histogram(path));
      std::ifstream in(path, std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      law.source_ = path.string() + "\n" + text.str();
      return law;
    } catch (const InputError& e) {
      t.fail("file", "= \"" + name + "\": " + e.what());
    }
  }
  // The continuous families: two parameters and an optional truncation.
  const ContinuousFamily& family = *find_continuous_family(kind);
  const double first = family.first_may_be_negative ? t.required_number(family.first_key)
                                                    : required_positive(t, family.first_key);
  const double second = required_positive(t, family.second_key);
  const double lo = t.number("min", family.support_lower);
  const double hi = t.number("max", INFINITY);
  if (!(hi > lo)) t.fail("max", "= " + format_number(hi) + " must be > min = " + format_number(lo));
  try {
    return continuous(kind, first, second, lo, hi);
  } catch (const InputError& e) {  // only the truncation can still be wrong here
    const char* key = t.has("max") ? "max" : "min";
    t.fail(key, "= " + format_number(key[1] == 'a' ? hi : lo) + ": " + e.what() + " under the " + kind + " law; widen it");
  }
}

}  // namespace stengmc
