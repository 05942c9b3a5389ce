#include "core/setting.hpp"

#include <sstream>

#include "core/hdf5_file.hpp"

namespace stengmc {

void write_settings(Hdf5Writer& file, const std::string& object, std::span<const Setting> settings) {
  for (const Setting& s : settings)
    std::visit([&](const auto& value) { file.attribute(object, std::string(s.key), value); }, s.value);
}

std::string toml_lines(std::span<const Setting> settings) {
  std::ostringstream out;
  out.precision(17);
  for (const Setting& s : settings) {
    out << s.key << " = ";
    if (const auto* text = std::get_if<std::string>(&s.value)) out << '"' << *text << '"';
    else std::visit([&](const auto& number) { out << number; }, s.value);
    out << "\n";
  }
  return out.str();
}

}  // namespace stengmc
