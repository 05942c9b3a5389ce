#pragma once
//! Inverting records of a known device: the raw estimate, its calibration by a bank, the
//! naive FFT count beside it, the stiffness law, and the verdict in plain words (README:
//! inverse estimation, `stengmc invert`).
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "inverse/atom_library.hpp"
#include "inverse/calibration_maps.hpp"
#include "inverse/calibration_run.hpp"
#include "inverse/naive_count.hpp"
#include "inverse/record_estimator.hpp"
#include "inverse/stiffness_law_fit.hpp"

namespace stengmc {

struct Inversion {
  std::string name;                  //!< which record ("file" or "file#realisation_3")
  RecordEstimate raw;
  CalibratedEstimate calibrated;
  double naive_count = 0.0;          //!< FFT peaks in the prior's band at the bank's threshold
  std::vector<LawFit> laws;          //!< this record's law fits, best AIC first
  std::vector<std::string> verdict;  //!< plain-words lines: what to trust, what limits
  std::vector<std::string> warnings; //!< what makes the answer doubtful
  std::vector<double> model_v;       //!< the fitted record model [V]
};

class Inverter {
 public:
  //! `maps` may be null (no bank: raw posterior, uncalibrated). One Inverter per thread.
  Inverter(const InverseSetup& setup, const AtomLibrary& atoms, const CalibrationMaps* maps);

  Inversion invert(const std::string& name, std::span<const double> voltage);

 private:
  const InverseSetup* setup_;
  const AtomLibrary* atoms_;
  const CalibrationMaps* maps_;
  RecordEstimator estimator_;
  NaiveCounter naive_;
  double atom_rms_v_ = 0.0;  //!< rms of one atom at the prior's central stiffness over the grid [V]
};

//! The laws fitted to every record's identified stiffnesses together (records of one surface).
std::vector<LawFit> pooled_laws(const std::vector<Inversion>& inversions);

}  // namespace stengmc
