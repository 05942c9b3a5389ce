#pragma once
//! One simulated record of a calibration: what was true and what the raw estimator said
//! (docs/inverse.md, "calibration"). Carried through the ensemble's journal as
//! named extras of the realisation's record, so an interrupted calibration resumes.
#include <cstdint>
#include <vector>

#include "ensemble/realisation_record.hpp"
#include "inverse/record_estimator.hpp"

namespace stengmc {

struct CalibrationSample {
  std::uint64_t realisation = 0;
  bool valid = false;                     //!< the forward model ran (no asperity reached l)
  std::vector<double> true_stiffness;     //!< the sliding asperities' k [N/m]
  double snr_db = 0.0;                    //!< the drawn SNR [dB]
  double law_first = 0.0, law_second = 0.0;  //!< the drawn law parameters
  std::size_t count = 0;                  //!< n-hat
  std::vector<double> counts;             //!< orders in the raw posterior
  std::vector<double> log_evidence;       //!< their log evidence
  std::vector<double> stiffness;          //!< identified k [N/m]
  std::vector<double> log_stiffness_se;   //!< their standard errors in ln k
  double median = 0.0, sd_log = 0.0;      //!< of the identified k
  double noise_sigma_v = 0.0, residual_sigma_v = 0.0, band_power_ratio = 1.0, snr_estimate_db = 0.0;
  double seconds = 0.0;                   //!< estimation time [s]
  std::vector<double> naive_counts;       //!< FFT peak counts at naive_count_thresholds()

  [[nodiscard]] std::size_t true_count() const { return true_stiffness.size(); }
  [[nodiscard]] double true_median() const;
  [[nodiscard]] double true_sd_log() const;   //!< n - 1 denominator; 0 below 2
  //! The raw estimate as far as the sample keeps it (posterior, count, lines, population):
  //! what calibrate_estimate needs, so held-out samples can be calibrated like a record.
  [[nodiscard]] RecordEstimate raw_estimate() const;
};

//! Stores the estimate and the naive counts in `record`'s extras.
void store_estimate(RealisationRecord& record, const RecordEstimate& estimate, const std::vector<double>& naive_counts);

//! Reads a record back; `first_key`/`second_key` name the law's drawn parameters
//! ("surface.stiffness.median", ...).
CalibrationSample calibration_sample(const RealisationRecord& record, const std::string& first_key,
                                     const std::string& second_key);

}  // namespace stengmc
