#include "io/record_format.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace stengmc {

namespace {

constexpr std::array<std::pair<std::string_view, RecordFormat>, 7> NAMES{{{"auto", RecordFormat::automatic},
                                                                          {"plain", RecordFormat::plain},
                                                                          {"tektronix", RecordFormat::tektronix},
                                                                          {"keysight", RecordFormat::keysight},
                                                                          {"rigol", RecordFormat::rigol},
                                                                          {"lecroy", RecordFormat::lecroy},
                                                                          {"picoscope", RecordFormat::picoscope}}};

bool same_letters(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

std::optional<RecordFormat> record_format_named(std::string_view name) {
  for (const auto& [text, format] : NAMES)
    if (text == name) return format;
  return std::nullopt;
}

std::string record_format_name(RecordFormat format) {
  for (const auto& [text, f] : NAMES)
    if (f == format) return std::string(text);
  return "?";
}

std::optional<RecordFormat> detect_record_format(const std::vector<std::vector<std::string>>& head) {
  if (head.empty() || head[0].empty()) return std::nullopt;
  const std::vector<std::string>& first = head[0];
  if (first.size() == 2 && first[0] == "t" && first[1] == "V") return RecordFormat::plain;
  // Each signature is the first line the vendor's export always writes (io/instrument_csv.cpp
  // says which document each layout follows).
  if (first[0] == "Record Length" || first[0] == "Model") {
    for (const auto& line : head)
      if (!line.empty() && line[0] == "Record Length") return RecordFormat::tektronix;
  }
  if (same_letters(first[0], "x-axis")) return RecordFormat::keysight;
  if (first[0] == "X" && std::find(first.begin(), first.end(), "Increment") != first.end()) return RecordFormat::rigol;
  if (first[0].rfind("LECROY", 0) == 0) return RecordFormat::lecroy;
  if (same_letters(first[0], "Time") && head.size() > 1 && !head[1].empty() &&
      std::all_of(head[1].begin(), head[1].end(), [](const std::string& f) { return !f.empty() && f.front() == '('; }))
    return RecordFormat::picoscope;
  return std::nullopt;
}

}  // namespace stengmc
