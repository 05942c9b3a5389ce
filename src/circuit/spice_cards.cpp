#include "circuit/spice_cards.hpp"

#include <algorithm>
#include <cctype>

#include "core/error.hpp"

namespace stengmc {

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }

//! The line up to its end-of-line comment, as ngspice cuts it outside a control section:
//! ';' and '//' anywhere, '$' after a blank or a comma.
std::string_view without_comment(std::string_view line) {
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (c == ';') return line.substr(0, k);
    if (c == '/' && k + 1 < line.size() && line[k + 1] == '/') return line.substr(0, k);
    if (c == '$' && (k == 0 || is_blank(line[k - 1]) || line[k - 1] == ',')) return line.substr(0, k);
  }
  return line;
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

}  // namespace

std::string spice_lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string spice_card_head(std::string_view card) {
  const std::size_t end = std::min(card.find_first_of(" \t"), card.size());
  return spice_lower(card.substr(0, end));
}

std::vector<SpiceCard> split_spice_cards(std::string_view text, const std::string& file, bool has_title) {
  std::vector<SpiceCard> cards;
  std::size_t number = 0;
  while (!text.empty()) {
    ++number;
    const std::size_t end = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, end);
    text.remove_prefix(std::min(end + 1, text.size()));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (number == 1 && has_title) continue;
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
        throw InputError(file + ":" + std::to_string(number) + ": the line holds a control character (byte " +
                         std::to_string(static_cast<unsigned char>(c)) +
                         "): a netlist is text; ngspice and stengmc would not read the same line");
    const std::string_view first = trimmed(line);
    // ngspice runs a `*#` line as a command even outside a control section (inp.c): refused
    // like one, so that no netlist line is silently not what its author meant.
    if (first.substr(0, 2) == "*#")
      throw InputError(file + ":" + std::to_string(number) +
                       ": a '*#' line is a command to ngspice (it runs even outside a control section): a load "
                       "netlist is data only (remove the line; docs/faults.md, \"Netlists are data\")");
    if (first.empty() || first.front() == '*' || first.front() == '#' || first.front() == '$') continue;
    const std::string_view card = trimmed(without_comment(first));
    if (card.empty()) continue;
    if (card.front() == '+') {
      if (cards.empty())
        throw InputError(file + ":" + std::to_string(number) + ": a continuation line ('+') with no card before it");
      const std::string_view rest = trimmed(card.substr(1));
      if (!rest.empty()) cards.back().text.append(" ").append(rest);
      continue;
    }
    cards.push_back({std::string(card), file, number});
  }
  return cards;
}

}  // namespace stengmc
