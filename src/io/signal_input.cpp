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
  if (file.has("/asperity/slip_fraction")) input.slip_fraction = file.vector("/asperity/slip_fraction");
  if (input.slip_fraction.size() != input.expected_frequency_hz.size())
    throw InputError(path + ": /asperity/natural_frequency and /asperity/slip_fraction differ in length");
  return input;
}

SignalInput read_signal_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file for reading");
  std::string line;
  if (!std::getline(in, line) || line.rfind("t,V", 0) != 0)
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
