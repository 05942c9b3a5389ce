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
  std::vector<std::vector<double>> velocity_m_per_s;  //!< [asperity][sample], when the file has them
  bool model1 = true;                           //!< /model@kind (for the sliding rule)
  double belt_velocity_m_per_s = 0.0;           //!< /model@belt_velocity_m_per_s (Model 2)
  double sharpness_s_per_m = 1.0;               //!< /model@atan_sharpness_s_per_m (Model 2)
};

//! Reads /time, /circuit/voltage (the circuit may be shorter than /time: an invalid run),
//! /asperity/current, /asperity/natural_frequency, /asperity/v and the /model attributes
//! that say when an asperity slides.
SignalInput read_signal_hdf5(const std::string& path);

//! Reads a CSV with header `t,V` (SI units).
SignalInput read_signal_csv(const std::string& path);

}  // namespace stengmc
