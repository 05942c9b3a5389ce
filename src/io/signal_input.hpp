#pragma once
//! A voltage signal to analyse without re-simulating: a stengmc output file, or a CSV `t,V`.
#include <string>
#include <vector>

namespace stengmc {

struct SignalInput {
  std::vector<double> times_s;                  //!< uniform grid
  std::vector<double> voltage_v;                //!< V at those times
  std::vector<std::vector<double>> currents_a;  //!< [element][sample], when the file has them
  std::vector<double> expected_frequency_hz;    //!< per asperity, when the file has them
  std::vector<double> slip_fraction;            //!< per asperity over the whole run, when the file has them
};

//! Reads /time, /circuit/voltage (the circuit may be shorter than /time: an invalid run),
//! /asperity/current, /asperity/natural_frequency and /asperity/slip_fraction.
SignalInput read_signal_hdf5(const std::string& path);

//! Reads a CSV with header `t,V` (SI units).
SignalInput read_signal_csv(const std::string& path);

}  // namespace stengmc
