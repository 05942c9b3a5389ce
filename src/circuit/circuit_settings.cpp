#include "circuit/circuit_settings.hpp"

#include <string>

namespace stengmc {

CircuitParams read_circuit_params(TomlTable& circuit) {
  CircuitParams c;
  c.load_resistance_ohm = circuit.positive("load_resistance_ohm", c.load_resistance_ohm);
  c.load_capacitance_f = circuit.non_negative("load_capacitance_f", c.load_capacitance_f);
  c.substeps = static_cast<std::size_t>(circuit.integer("substeps", static_cast<long long>(c.substeps), 1));
  if (c.substeps > 1000) circuit.fail("substeps", "= " + std::to_string(c.substeps) + " must be <= 1000");
  return c;
}

std::vector<Setting> circuit_settings(const CircuitParams& c) {
  return {{"load_resistance_ohm", c.load_resistance_ohm},
          {"load_capacitance_f", c.load_capacitance_f},
          {"substeps", static_cast<std::int64_t>(c.substeps)}};
}

}  // namespace stengmc
