#include "circuit/netlist_key.hpp"

#include <filesystem>
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
  // A study reads its netlist, and what that includes, from its own folder only: a study
  // someone shared must not make stengmc read (and record in its outputs) other files.
  std::filesystem::path study_dir = std::filesystem::path(study_file).parent_path();
  if (study_dir.empty()) study_dir = ".";
  const std::filesystem::path path =
      (std::filesystem::path(name).is_absolute() ? std::filesystem::path(name) : study_dir / name).lexically_normal();
  return std::make_shared<const NetlistLoad>(read_netlist_load(
      path.string(), study_dir.string(), circuit.location("netlist") + ": " + circuit.qualified("netlist") + " = \"" + name + "\""));
}

}  // namespace stengmc
