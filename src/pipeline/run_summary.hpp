#pragma once
//! The few numbers a person wants after a run (printed, and written to the run file).
#include <string>
#include <vector>

#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"

namespace stengmc {

struct AsperitySummary {
  double natural_frequency_hz = 0.0;  //!< damped natural frequency (Model 2 damping; undamped for Model 1) [Hz]
  double slip_fraction = 0.0;         //!< fraction of samples sliding: x' != 0 (Model 1), |v_b - x'| > 1/s (Model 2)
  double max_x_over_l = 0.0;          //!< max x / l over the run
  double rms_velocity_m_per_s = 0.0;  //!< root mean square of x' [m/s]
};

struct RunSummary {
  std::vector<AsperitySummary> asperities;
  double voltage_rms_v = 0.0;   //!< over the valid circuit samples [V]
  double voltage_peak_v = 0.0;  //!< max |V| [V]
  double final_charge_c = 0.0;  //!< Q at the last valid sample [C]
};

RunSummary summarise(const Study& study, const RunResult& result);

//! The summary as a table for the terminal.
std::string format_summary(const Study& study, const RunResult& result, const RunSummary& summary);

}  // namespace stengmc
