#include "circuit/netlist_load.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <sstream>

#include "core/error.hpp"

namespace stengmc {

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

//! Dot cards that would run or end something: stengmc writes the analysis itself.
constexpr std::array<std::string_view, 13> REJECTED_CARDS{".tran", ".op", ".ac", ".dc", ".noise", ".tf", ".pz",
                                                          ".sens", ".disto", ".four", ".control", ".endc", ".meas"};

//! Whether a card (already lower case) names the port node as one of its fields. A field
//! is split at blanks, parentheses, commas and '='; good enough to catch a netlist that
//! forgot the port, while ngspice itself judges everything else.
bool names_port(const std::string& card) {
  std::string field;
  for (std::size_t k = 0; k <= card.size(); ++k) {
    const char c = k < card.size() ? card[k] : ' ';
    if (std::isspace(static_cast<unsigned char>(c)) || c == '(' || c == ')' || c == ',' || c == '=') {
      if (field == STENG_PORT_NODE) return true;
      field.clear();
    } else {
      field += c;
    }
  }
  return false;
}

}  // namespace

NetlistLoad parse_netlist_load(const std::string& text, const std::string& file) {
  NetlistLoad load{file, text, {}, {}};
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  bool port = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) continue;  // the title line, as in every SPICE file
    const std::string card = lower(line);
    const std::size_t first = card.find_first_not_of(" \t");
    if (first == std::string::npos || card[first] == '*') continue;
    const std::string head = card.substr(first, card.find_first_of(" \t", first) - first);
    if (head == ".end") break;
    if (std::find(REJECTED_CARDS.begin(), REJECTED_CARDS.end(), head) != REJECTED_CARDS.end())
      throw InputError(file + ":" + std::to_string(number) + ": '" + head +
                       "': a load netlist describes the circuit only; stengmc sets the transient analysis itself "
                       "(remove the line)");
    if (head == ".include" || head == ".inc" || head == ".lib")
      throw InputError(file + ":" + std::to_string(number) + ": '" + head +
                       "' is not supported in a load netlist: copy the models it would read into the file, so the "
                       "netlist recorded in the output is complete");
    port = port || names_port(card);
    load.lines.push_back(line);
    load.line_numbers.push_back(number);
  }
  if (!port)
    throw InputError(file + ": no element connects to the S-TENG port node '" + std::string(STENG_PORT_NODE) +
                     "': the load must sit between node " + std::string(STENG_PORT_NODE) + " and ground 0");
  return load;
}

}  // namespace stengmc
