#include "circuit/netlist_structure.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace stengmc {

namespace {

[[noreturn]] void refuse(const SpiceCard& card, const std::string& why) {
  throw InputError(card.origin() + ": " + why + " (docs/faults.md, \"Netlists are data\")");
}

std::vector<std::string> fields(std::string_view card) {
  std::vector<std::string> out;
  std::size_t k = 0;
  while (k < card.size()) {
    while (k < card.size() && (card[k] == ' ' || card[k] == '\t')) ++k;
    const std::size_t start = k;
    while (k < card.size() && card[k] != ' ' && card[k] != '\t') ++k;
    if (k > start) out.push_back(spice_lower(card.substr(start, k - start)));
  }
  return out;
}

//! The subcircuit an X card instances: its last field before `params:` and name=value pairs.
std::string instanced_subcircuit(std::string_view card) {
  std::string name;
  const std::vector<std::string> all = fields(card);
  for (std::size_t k = 1; k < all.size(); ++k) {
    if (all[k] == "params:") break;
    if (all[k].find('=') == std::string::npos) name = all[k];
  }
  return name;
}

bool is_identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

//! A subcircuit's contents (or the top level's): its own devices and what it instances.
struct Definition {
  const SpiceCard* card = nullptr;  //!< its .subckt card (none for the top level)
  double devices = 0.0;
  std::vector<std::pair<std::string, const SpiceCard*>> instances;
};

//! A directed graph walked without recursion (a chain of 100 000 subcircuits must not
//! overflow stengmc's own stack): `value(node)` = own + max or sum over its edges.
template <typename Edges, typename Combine>
double walk(std::size_t root, std::vector<int>& state, std::vector<double>& value, const Edges& edges,
            const Combine& combine, const std::function<void(std::size_t from, std::size_t to)>& on_cycle) {
  std::vector<std::pair<std::size_t, std::size_t>> stack{{root, 0}};  // node, next edge
  if (state[root] == 2) return value[root];
  state[root] = 1;
  while (!stack.empty()) {
    auto& [node, next] = stack.back();
    const auto& out = edges(node);
    if (next < out.size()) {
      const std::size_t to = out[next++];
      if (state[to] == 1) on_cycle(node, to);
      if (state[to] == 0) {
        state[to] = 1;
        stack.push_back({to, 0});
      }
      continue;
    }
    value[node] = combine(node);
    state[node] = 2;
    stack.pop_back();
  }
  return value[root];
}

}  // namespace

NetlistStructure examine_netlist_structure(const std::vector<SpiceCard>& cards) {
  std::vector<Definition> definitions(1);  // [0]: the top level
  std::map<std::string, std::size_t> subcircuits;
  std::vector<std::size_t> open{0};
  std::map<std::string, std::size_t> function_index;
  std::vector<const SpiceCard*> function_cards;
  std::vector<std::string> function_bodies;

  for (const SpiceCard& card : cards) {
    if (card.text.size() > MAX_CARD_CHARACTERS)
      refuse(card, "the card is " + std::to_string(card.text.size()) + " characters long; at most " +
                       std::to_string(MAX_CARD_CHARACTERS) + " are accepted");
    std::size_t depth = 0, deepest = 0;
    for (const char c : card.text) {
      if (c == '(' || c == '{' || c == '[') deepest = std::max(deepest, ++depth);
      else if ((c == ')' || c == '}' || c == ']') && depth > 0) --depth;
    }
    if (deepest > MAX_BRACKET_DEPTH)
      refuse(card, "brackets nest " + std::to_string(deepest) + " deep; ngspice's expression parser recurses and at most " +
                       std::to_string(MAX_BRACKET_DEPTH) + " are accepted");
    const std::string head = spice_card_head(card.text);
    if (head == ".subckt") {
      const std::vector<std::string> all = fields(card.text);
      if (all.size() < 2) refuse(card, "'.subckt' without a name");
      definitions.push_back({&card, 0.0, {}});
      subcircuits.emplace(all[1], definitions.size() - 1);
      open.push_back(definitions.size() - 1);
    } else if (head == ".ends") {
      if (open.size() == 1) refuse(card, "'.ends' without a '.subckt' before it");
      open.pop_back();
    } else if (head == ".func") {
      const std::string text = spice_lower(card.text);
      std::size_t k = head.size();
      while (k < text.size() && (text[k] == ' ' || text[k] == '\t')) ++k;
      const std::size_t start = k;
      while (k < text.size() && is_identifier_char(text[k])) ++k;
      if (k == start) refuse(card, "'.func' without a function name");
      const std::size_t arguments_end = text.find(')', k);
      function_index.emplace(text.substr(start, k - start), function_cards.size());
      function_cards.push_back(&card);
      function_bodies.push_back(arguments_end == std::string::npos ? "" : text.substr(arguments_end + 1));
    } else if (!head.empty() && head.front() != '.') {
      Definition& here = definitions[open.back()];
      if (head.front() == 'x') here.instances.emplace_back(instanced_subcircuit(card.text), &card);
      else here.devices += 1.0;
    }
  }
  if (open.size() > 1) refuse(*definitions[open.back()].card, "this '.subckt' has no '.ends'");

  // Devices after expansion: own devices plus each instance's expansion. An instance of a
  // name no .subckt defines counts as one device (ngspice refuses it anyway).
  std::vector<std::vector<std::size_t>> instance_edges(definitions.size());
  for (std::size_t d = 0; d < definitions.size(); ++d)
    for (const auto& [name, card] : definitions[d].instances)
      if (const auto it = subcircuits.find(name); it != subcircuits.end()) instance_edges[d].push_back(it->second);
  std::vector<int> state(definitions.size(), 0);
  std::vector<double> devices(definitions.size(), 0.0);
  const double total = walk(
      0, state, devices, [&](std::size_t d) -> const std::vector<std::size_t>& { return instance_edges[d]; },
      [&](std::size_t d) {
        double sum = definitions[d].devices;
        for (const auto& [name, card] : definitions[d].instances) {
          const auto it = subcircuits.find(name);
          sum += it == subcircuits.end() ? 1.0 : devices[it->second];
        }
        return std::min(sum, 1e300);
      },
      [&](std::size_t from, std::size_t to) {
        const SpiceCard* at = definitions[to].card;
        for (const auto& [name, card] : definitions[from].instances)
          if (const auto it = subcircuits.find(name); it != subcircuits.end() && it->second == to) at = card;
        refuse(*at, "subcircuit '" + fields(definitions[to].card->text)[1] +
                        "' is instanced inside itself (directly or through others): ngspice would expand it for ever");
      });
  if (total > MAX_EXPANDED_DEVICES) {
    char amount[32];
    std::snprintf(amount, sizeof amount, "%.3g", total);
    refuse(cards.front(), std::string("the netlist expands to ") + amount +
                              " devices (subcircuits inside subcircuits multiply); at most " +
                              std::to_string(static_cast<long long>(MAX_EXPANDED_DEVICES)) + " are accepted");
  }

  // .func call depth: each call is a recursion in ngspice's evaluator.
  std::vector<std::vector<std::size_t>> calls(function_cards.size());
  for (std::size_t f = 0; f < function_cards.size(); ++f) {
    const std::string& body = function_bodies[f];
    for (std::size_t k = 0; k < body.size();) {
      if (!is_identifier_start(body[k]) || (k > 0 && is_identifier_char(body[k - 1]))) {
        ++k;
        continue;
      }
      const std::size_t start = k;
      while (k < body.size() && is_identifier_char(body[k])) ++k;
      std::size_t after = k;
      while (after < body.size() && (body[after] == ' ' || body[after] == '\t')) ++after;
      if (after < body.size() && body[after] == '(')
        if (const auto it = function_index.find(body.substr(start, k - start)); it != function_index.end())
          calls[f].push_back(it->second);
    }
  }
  std::vector<int> visited(function_cards.size(), 0);
  std::vector<double> depth(function_cards.size(), 0.0);
  for (std::size_t f = 0; f < function_cards.size(); ++f) {
    const double chain = walk(
        f, visited, depth, [&](std::size_t g) -> const std::vector<std::size_t>& { return calls[g]; },
        [&](std::size_t g) {
          double deepest = 0.0;
          for (const std::size_t callee : calls[g]) deepest = std::max(deepest, depth[callee]);
          return 1.0 + deepest;
        },
        [&](std::size_t, std::size_t to) {
          refuse(*function_cards[to], "this .func calls itself (directly or through others): ngspice would recurse "
                                        "until its stack overflows");
        });
    if (chain > static_cast<double>(MAX_FUNCTION_DEPTH))
      refuse(*function_cards[f], "this .func starts a chain of " + std::to_string(static_cast<long long>(chain)) +
                                     " nested .func calls; at most " + std::to_string(MAX_FUNCTION_DEPTH) +
                                     " are accepted (ngspice evaluates each call recursively)");
  }
  return {total};
}

}  // namespace stengmc
