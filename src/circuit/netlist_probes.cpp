#include "circuit/netlist_probes.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "core/error.hpp"

namespace stengmc {

namespace {

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool plain_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

//! The whitespace-separated tokens of a card, lower case.
std::vector<std::string> tokens(const std::string& card) {
  std::istringstream in(lower(card));
  std::vector<std::string> out;
  for (std::string token; in >> token;) out.push_back(token);
  return out;
}

//! Devices whose current ngspice reports as a branch of the circuit's equations.
bool has_branch(char kind) { return kind == 'v' || kind == 'e' || kind == 'h' || kind == 'l'; }

//! The ngspice device parameter holding the current of an R, C or D (its manual, ch. 31).
const char* current_parameter(char kind) {
  switch (kind) {
    case 'r': return "i";
    case 'c': return "i";
    case 'd': return "id";
    default: return nullptr;
  }
}

}  // namespace

NetlistProbe parse_netlist_probe(const std::string& text, const NetlistLoad& load,
                                 const std::function<void(const std::string&)>& fail) {
  const std::string probe = lower(text);
  const bool voltage = probe.rfind("v(", 0) == 0, current = probe.rfind("i(", 0) == 0;
  const std::string inner = probe.size() > 3 && probe.back() == ')' ? probe.substr(2, probe.size() - 3) : "";
  if (!(voltage || current) || !plain_name(inner))
    fail("\"" + text + "\" is not a probe: write v(node) for a node's voltage or i(device) for a device's current "
         "(names of letters, digits and _)");
  // Every card's first token is its device; nodes follow it.
  const auto cards = [&] {
    std::vector<std::vector<std::string>> out;
    for (const std::string& line : load.lines)
      if (!line.empty() && line[0] != '.') out.push_back(tokens(line));
    return out;
  }();
  NetlistProbe p{.name = probe, .vector = probe, .dataset = (voltage ? "v_" : "i_") + inner, .units = voltage ? "V" : "A"};
  if (voltage) {
    const bool named = inner == "0" || inner == STENG_PORT_NODE ||
                       std::any_of(cards.begin(), cards.end(), [&](const std::vector<std::string>& card) {
                         return std::find(card.begin() + 1, card.end(), inner) != card.end();
                       });
    if (!named) fail("\"" + text + "\": no card of " + load.file + " names a node '" + inner + "'");
    return p;
  }
  const bool named = std::any_of(cards.begin(), cards.end(),
                                 [&](const std::vector<std::string>& card) { return card.front() == inner; });
  if (!named) fail("\"" + text + "\": " + load.file + " has no device '" + inner + "' (a subcircuit's devices cannot be probed)");
  const char kind = inner.front();
  if (has_branch(kind)) {
    p.vector = inner + "#branch";
  } else if (const char* parameter = current_parameter(kind)) {
    p.vector = "@" + inner + "[" + parameter + "]";
  } else {
    fail("\"" + text + "\": currents are recorded for V, E, H, L, R, C and D devices; put a 0 V source in series "
         "with '" + inner + "' and probe its current");
  }
  return p;
}

std::vector<NetlistProbe> read_probes_key(TomlTable& circuit, const NetlistLoad* load) {
  if (!circuit.has("probes")) return {};
  const auto fail = [&](const std::string& what) { circuit.fail("probes", what); };
  if (load == nullptr) fail("records quantities of a load netlist: it needs [circuit] netlist");
  std::vector<NetlistProbe> probes;
  for (const std::string& text : circuit.string_list("probes", {})) {
    NetlistProbe p = parse_netlist_probe(text, *load, fail);
    if (std::any_of(probes.begin(), probes.end(), [&](const NetlistProbe& q) { return q.name == p.name; }))
      fail("\"" + text + "\" is listed twice");
    probes.push_back(std::move(p));
  }
  return probes;
}

}  // namespace stengmc
