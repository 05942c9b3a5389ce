#include "io/signal_input.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/hdf5_file.hpp"

namespace stengmc {

SignalInput read_signal_hdf5(const std::string& path) {
  Hdf5Reader file(path);
  SignalInput input;
  input.voltage_v = file.vector("/circuit/voltage");
  input.times_s = file.vector("/time");
  if (input.times_s.size() < input.voltage_v.size())
    throw InputError(path + ": /time (" + std::to_string(input.times_s.size()) + ") is shorter than /circuit/voltage (" +
                     std::to_string(input.voltage_v.size()) + ")");
  input.times_s.resize(input.voltage_v.size());  // an invalid run's circuit stops early
  if (file.has("/asperity/current")) input.currents_a = file.matrix("/asperity/current");
  for (const auto& row : input.currents_a)
    if (row.size() != input.voltage_v.size()) throw InputError(path + ": /asperity/current rows differ in length from /circuit/voltage");
  if (file.has("/asperity/natural_frequency")) input.expected_frequency_hz = file.vector("/asperity/natural_frequency");
  if (file.has("/asperity/v")) input.velocity_m_per_s = file.matrix("/asperity/v");
  if (!input.expected_frequency_hz.empty() && input.velocity_m_per_s.size() != input.expected_frequency_hz.size())
    throw InputError(path + ": identifiability needs /asperity/v with one row per /asperity/natural_frequency");
  if (file.has("/model")) {
    input.model1 = file.string_attribute("/model", "kind") == "model1";
    input.belt_velocity_m_per_s = file.number_attribute("/model", "belt_velocity_m_per_s").value_or(0.0);
    input.sharpness_s_per_m = file.number_attribute("/model", "atan_sharpness_s_per_m").value_or(1.0);
  }
  return input;
}

SignalInput read_signal_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file for reading");
  std::string line;
  if (!std::getline(in, line) || (line != "t,V" && line != "t,V\r"))
    throw InputError(path + ":1: header must be `t,V` (time in s, voltage in V)");
  SignalInput input;
  std::size_t number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::stringstream fields(line);
    std::string t_text, v_text, extra;
    std::getline(fields, t_text, ',');
    std::getline(fields, v_text, ',');
    if (std::getline(fields, extra, ',') || v_text.empty())
      throw InputError(path + ":" + std::to_string(number) + ": expected two fields `t,V`");
    try {
      std::size_t used_t = 0, used_v = 0;
      const double t = std::stod(t_text, &used_t);
      const double v = std::stod(v_text, &used_v);
      const auto end_of = [](const std::string& text) { return text.find_last_not_of(" \t\r") + 1; };
      if (used_t != end_of(t_text) || used_v != end_of(v_text)) throw std::invalid_argument("trailing text");
      if (!std::isfinite(t) || !std::isfinite(v)) throw std::invalid_argument("not finite");
      input.times_s.push_back(t);
      input.voltage_v.push_back(v);
    } catch (const std::exception&) {
      throw InputError(path + ":" + std::to_string(number) + ": '" + line + "' is not two finite numbers");
    }
  }
  return input;
}

}  // namespace stengmc
