#include "circuit/netlist_key.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include "circuit/netlist_load.hpp"
#include "core/error.hpp"

namespace stengmc {

std::shared_ptr<const NetlistLoad> read_netlist_key(TomlTable& circuit, const std::string& study_file) {
  if (!circuit.has("netlist")) return nullptr;
  for (const char* built_in : {"load_resistance_ohm", "load_capacitance_f"})
    if (circuit.has(built_in))
      circuit.fail("netlist", std::string("replaces the built-in load: remove ") + built_in +
                                  " (the netlist describes the whole load)");
  const std::string name = circuit.string("netlist", "");
  if (name.empty()) circuit.fail("netlist", "is empty: give the path of a SPICE netlist of the load");
  const std::filesystem::path study_dir = std::filesystem::path(study_file).parent_path();
  const std::filesystem::path path =
      (std::filesystem::path(name).is_absolute() ? std::filesystem::path(name) : study_dir / name).lexically_normal();
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
    circuit.fail("netlist", "= \"" + name + "\": cannot read it (looked for " + path.string() + ")");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return std::make_shared<const NetlistLoad>(parse_netlist_load(text, path.string()));
}

}  // namespace stengmc
