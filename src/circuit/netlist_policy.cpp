#include "circuit/netlist_policy.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>

#include "core/error.hpp"

namespace stengmc {

namespace {

//! ngspice's built-in device model types (spicelib/parser/inpdomod.c). Everything else a
//! `.model` names is an XSPICE code model or a numerical (CIDER) or network device.
constexpr std::array<std::string_view, 23> BUILT_IN_MODEL_TYPES{
    "r",   "c",   "l",     "sw",    "csw",  "urc",  "ltra", "txl",  "cpl",  "d",    "npn", "pnp",
    "njf", "pjf", "nmf",   "pmf",   "nhfet", "phfet", "nmos", "pmos", "nsoi", "psoi", "vdmos"};

//! Element letters of every SPICE device but XSPICE (A) and OSDI (N).
constexpr std::string_view ELEMENT_LETTERS = "bcdefghijklmopqrstuvwxyz";

//! Analyses and outputs: stengmc writes its own transient and reads the vectors itself.
constexpr std::array<std::string_view, 19> ANALYSIS_CARDS{
    ".tran", ".op", ".ac", ".dc", ".noise", ".tf", ".pz", ".sens", ".disto", ".four", ".meas", ".measure",
    ".sp", ".pss", ".print", ".plot", ".save", ".probe", ".width"};

[[noreturn]] void refuse(const SpiceCard& card, const std::string& what, const std::string& why) {
  throw InputError(card.origin() + ": " + what + ": " + why + " (remove the line; docs/faults.md, \"Netlists are data\")");
}

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

//! The type a `.model NAME TYPE(...)` card names, lower case ("" when none).
std::string model_type(const std::string& card) {
  std::size_t k = std::min(card.find_first_of(" \t"), card.size());  // after ".model"
  auto skip_blanks = [&] {
    while (k < card.size() && (card[k] == ' ' || card[k] == '\t')) ++k;
  };
  skip_blanks();
  while (k < card.size() && card[k] != ' ' && card[k] != '\t' && card[k] != '(') ++k;  // the name
  skip_blanks();
  const std::size_t start = k;
  while (k < card.size() && card[k] != ' ' && card[k] != '\t' && card[k] != '(') ++k;
  return spice_lower(std::string_view(card).substr(start, k - start));
}

CardKind classify_dot_card(const SpiceCard& card, const std::string& head) {
  if (head == ".model") {
    const std::string type = model_type(card.text);
    if (type.empty()) refuse(card, "'.model' without a device type", "write .model NAME TYPE(PARAMETERS)");
    if (std::find(BUILT_IN_MODEL_TYPES.begin(), BUILT_IN_MODEL_TYPES.end(), type) == BUILT_IN_MODEL_TYPES.end())
      refuse(card, "model type '" + type + "'",
             "only ngspice's built-in device models are accepted (r c l sw csw urc ltra txl cpl d npn pnp njf pjf "
             "nmf pmf nhfet phfet nmos pmos nsoi psoi vdmos); XSPICE code models such as filesource, d_source or "
             "d_state read files, numerical and network devices (numd, nbjt, numos, ndev) read and open what they "
             "are told");
    return CardKind::model;
  }
  if (head == ".subckt") return CardKind::subcircuit;
  if (head == ".ends") return CardKind::ends;
  if (head == ".param") return CardKind::parameter;
  if (head == ".func") return CardKind::function;
  if (head == ".include" || head == ".inc") return CardKind::include;
  if (head == ".lib") return CardKind::library;
  if (head == ".endl") return CardKind::library_end;
  if (head == ".end") return CardKind::end;
  // Refused: say why in the terms of what ngspice would make of it (by prefix, as it does).
  if (starts_with(head, ".control") || starts_with(head, ".endc"))
    refuse(card, "'" + head + "'",
           "ngspice reads it as a control section, whose commands it runs (shell, file writes): a load netlist is "
           "data only");
  if (starts_with(head, ".option") || starts_with(head, ".opt"))
    refuse(card, "'" + head + "'", "stengmc sets the simulator options itself (tolerances scaled to the elements)");
  if (starts_with(head, ".inc") || starts_with(head, ".lib"))
    refuse(card, "'" + head + "'", "write .include FILE or .lib FILE ENTRY");
  if (std::any_of(ANALYSIS_CARDS.begin(), ANALYSIS_CARDS.end(), [&](std::string_view a) { return starts_with(head, a); }))
    refuse(card, "'" + head + "'", "a load netlist describes the circuit only; stengmc sets the transient analysis itself");
  refuse(card, "'" + head + "'",
         "not accepted in a load netlist; accepted are elements, .model, .subckt/.ends, .param, .func, "
         ".include/.lib of files in the study's folder and .end");
}

}  // namespace

CardKind classify_card(const SpiceCard& card) {
  const std::string head = spice_card_head(card.text);
  if (head.empty()) refuse(card, "an empty card", "");
  if (head.front() == '.') return classify_dot_card(card, head);
  const char letter = head.front();
  if (letter == 'a')
    refuse(card, "XSPICE instance '" + head + "'",
           "XSPICE code models are not accepted in a load netlist: some read files (filesource, d_source, d_state, "
           "table2D/3D); use SPICE elements and behavioural sources (B, E, G)");
  if (letter == 'n')
    refuse(card, "device '" + head + "'",
           "OSDI (Verilog-A) and network devices load compiled code or open connections; not accepted in a load "
           "netlist");
  if (ELEMENT_LETTERS.find(letter) == std::string_view::npos)
    refuse(card, "'" + head + "'", "a card starts with an element letter (R, C, L, D, V, X, ...) or a dot card");
  return CardKind::element;
}

}  // namespace stengmc
