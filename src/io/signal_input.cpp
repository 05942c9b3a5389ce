#include "io/signal_input.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/guarded_read.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "core/text_excerpt.hpp"
#include "io/run_file.hpp"
#include "spectral/analysed_voltage.hpp"

namespace stengmc {

namespace {

//! The analysis squares and sums voltages (power, noise floor, ESPRIT): keep those finite.
void check_voltages(const SignalInput& input, const std::string& path) {
  for (std::size_t j = 0; j < input.voltage_v.size(); ++j)
    if (!(std::abs(input.voltage_v[j]) <= MAX_ANALYSED_VOLTAGE_V))
      throw InputError(path + ": /circuit/voltage sample " + std::to_string(j) + " = " + format_number(input.voltage_v[j]) +
                       " V is beyond what the analysis can square and sum (|V| <= 1e100 V)");
}

SignalInput read_hdf5(const std::string& path) {
  Hdf5Reader file(path);
  check_format_version(file, path, RUN_FILE_FORMAT_VERSION);
  SignalInput input;
  input.voltage_v = file.vector("/circuit/voltage");
  input.times_s = file.vector("/time");
  if (input.times_s.size() < input.voltage_v.size())
    throw InputError(path + ": /time (" + std::to_string(input.times_s.size()) + ") is shorter than /circuit/voltage (" +
                     std::to_string(input.voltage_v.size()) + ")");
  const std::size_t samples = input.times_s.size();
  input.times_s.resize(input.voltage_v.size());  // an invalid run's circuit stops early
  if (file.has("/asperity/current")) input.currents_a = file.matrix("/asperity/current");
  for (const auto& row : input.currents_a)
    if (row.size() != input.voltage_v.size()) throw InputError(path + ": /asperity/current rows differ in length from /circuit/voltage");
  if (file.has("/asperity/natural_frequency")) input.expected_frequency_hz = file.vector("/asperity/natural_frequency");
  if (file.has("/asperity/v")) input.velocity_m_per_s = file.matrix("/asperity/v");
  if (!input.expected_frequency_hz.empty() && input.velocity_m_per_s.size() != input.expected_frequency_hz.size())
    throw InputError(path + ": identifiability needs /asperity/v with one row per /asperity/natural_frequency");
  // Sliding is judged on /asperity/v over the analysis interval, in samples of /time.
  for (std::size_t i = 0; i < input.velocity_m_per_s.size(); ++i)
    if (input.velocity_m_per_s[i].size() != samples)
      throw InputError(path + ": /asperity/v row " + std::to_string(i + 1) + " has " +
                       std::to_string(input.velocity_m_per_s[i].size()) + " samples; /time has " + std::to_string(samples));
  if (file.has("/model")) {
    input.model1 = file.string_attribute("/model", "kind") == "model1";
    input.belt_velocity_m_per_s = file.number_attribute("/model", "belt_velocity_m_per_s").value_or(0.0);
    input.sharpness_s_per_m = file.number_attribute("/model", "atan_sharpness_s_per_m").value_or(1.0);
  }
  check_voltages(input, path);
  return input;
}

}  // namespace

SignalInput read_signal_hdf5(const std::string& path) {
  check_input_file(path, "an HDF5 file");
  read_in_child_first(path, [&] { (void)read_hdf5(path); });
  return read_hdf5(path);
}

SignalInput read_signal_csv(const std::string& path) {
  std::ifstream in = open_input_file(path, "the signal CSV file");
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
    const auto t = parse_number(trim_blanks(t_text)), v = parse_number(trim_blanks(v_text));
    if (!t || !v) throw InputError(path + ":" + std::to_string(number) + ": '" + text_excerpt(line) + "' is not two finite numbers");
    if (std::abs(*v) > MAX_ANALYSED_VOLTAGE_V)
      throw InputError(path + ":" + std::to_string(number) + ": V = " + text_excerpt(trim_blanks(v_text)) +
                       " is beyond what the analysis can square "
                       "and sum (|V| <= 1e100 V)");
    input.times_s.push_back(*t);
    input.voltage_v.push_back(*v);
  }
  return input;
}

}  // namespace stengmc
