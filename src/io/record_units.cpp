#include "io/record_units.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <utility>

namespace stengmc {

namespace {

//! `unit` without the brackets or parentheses vendors write around it ("(us)", "[mV]").
std::string bare(std::string_view unit) {
  while (!unit.empty() && (unit.front() == '(' || unit.front() == '[' || unit.front() == ' ')) unit.remove_prefix(1);
  while (!unit.empty() && (unit.back() == ')' || unit.back() == ']' || unit.back() == ' ')) unit.remove_suffix(1);
  return std::string(unit);
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

//! The factor of an SI prefix written before `base`, or nothing. Prefixes are case-sensitive
//! (m is milli, M would be mega); micro is written u, µ (U+00B5) or μ (U+03BC) in UTF-8, or
//! as the Latin-1 byte 0xB5 some Windows exports write.
std::optional<double> prefixed(const std::string& unit, std::string_view base) {
  if (unit.size() < base.size() || unit.compare(unit.size() - base.size(), base.size(), base) != 0) return std::nullopt;
  const std::string prefix = unit.substr(0, unit.size() - base.size());
  if (prefix.empty()) return 1.0;
  if (prefix == "k") return 1e3;
  if (prefix == "m") return 1e-3;
  if (prefix == "u" || prefix == "\xC2\xB5" || prefix == "\xCE\xBC" || prefix == "\xB5") return 1e-6;
  if (prefix == "n") return 1e-9;
  if (prefix == "p") return 1e-12;
  return std::nullopt;
}

}  // namespace

std::optional<double> time_unit_scale(std::string_view unit) {
  const std::string u = bare(unit);
  const std::string word = lower(u);
  if (u.empty() || word == "second" || word == "seconds" || word == "sec") return 1.0;
  // Spelt out, as CF and UDUNITS write a time coordinate's units ("microseconds since ...").
  for (const auto& [name, scale] : {std::pair{"millisecond", 1e-3}, {"microsecond", 1e-6}, {"nanosecond", 1e-9}, {"picosecond", 1e-12}})
    if (word == name || word == std::string(name) + "s") return scale;
  if (u == "ks") return std::nullopt;  // no oscilloscope writes kiloseconds; more likely a typo
  return prefixed(u, "s");
}

std::optional<double> voltage_unit_scale(std::string_view unit) {
  const std::string u = bare(unit);
  const std::string word = lower(u);
  if (u.empty() || word == "volt" || word == "volts") return 1.0;
  return prefixed(u, "V");
}

}  // namespace stengmc
