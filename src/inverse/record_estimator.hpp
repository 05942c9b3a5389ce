#pragma once
//! One record in, the raw estimate out: noise level and spectrum, fits of every plausible
//! count, the count's posterior, the identified lines (stiffness, load, onset) with their
//! uncertainty, the device's fitted parameters, the realised population's median and spread,
//! and the checks the verdict speaks from (docs/inverse.md). Calibration
//! (calibration_maps.hpp) turns the raw posterior and spreads into calibrated ones; this class
//! knows nothing of banks.
#include <optional>
#include <span>
#include <vector>

#include "inverse/atom_library.hpp"
#include "inverse/count_posterior.hpp"
#include "inverse/fit_layout.hpp"
#include "inverse/inverse_prior.hpp"
#include "inverse/line_proposals.hpp"
#include "inverse/line_search.hpp"
#include "inverse/load_prior.hpp"
#include "inverse/nested_search.hpp"
#include "inverse/noise_level.hpp"
#include "inverse/noise_whitening.hpp"
#include "inverse/record_model.hpp"

namespace stengmc {

struct EstimatedLine {
  double stiffness_n_per_m = 0.0;
  double log_stiffness_se = 0.0;        //!< standard error of ln k (Laplace) [-]
  double se_inflation = 1.0;            //!< that error over its value were the other lines known (se_inflation.hpp) [-]
  double frequency_hz = 0.0;            //!< its tail's frequency [Hz]
  double amplitude_v = 0.0;             //!< the line's amplitude at breakaway [V]
  double nearest_separation_hz = 0.0;   //!< to the nearest other identified line (0 alone) [Hz]
  double load_n = 0.0;                  //!< its load (at the device's friction coefficients) [N]
  double log_load_se = 0.0;             //!< standard error of ln N (0: not fitted) [-]
  double onset_s = 0.0;                 //!< its contact onset [s]
  double onset_se_s = 0.0;              //!< standard error of the onset (0: not fitted) [s]
  double breakaway_s = 0.0;             //!< when it left the belt [s]
};

//! What the residual of the chosen fit says about the model's assumptions (the verdict's
//! words): each a ratio that is ~1 when the model fits to the noise.
struct ResidualChecks {
  double misfit = 1.0;              //!< whitened RSS / (M sigma^2) [-]
  double line_band = 1.0;           //!< residual power in the lines' band over its expectation [-]
  double low_band = 1.0;            //!< residual power below the lines' band over its expectation [-]
  double early = 1.0;               //!< residual power over the breakaways' span over its expectation [-]
  double late = 1.0;                //!< residual power over the last third of the record over its expectation [-]
};

//! A fit started from a population given beside the record, refined in full (a development
//! check, the "oracle": on a simulated record, started from the truth, it says whether a wrong
//! answer is the search's failure, the truth explaining the record better than what was
//! found, or the model's, the truth itself not explaining it to the noise). Misfits are
//! whitened RSS / (M sigma^2) with the estimate's final noise model.
struct ReferenceFit {
  double start_misfit = 0.0;         //!< at the given population, shared parameters as given [-]
  double misfit = 0.0;               //!< refined in full (atoms and shared parameters) [-]
  double penalty = 0.0;              //!< its loads' prior term, -2 ln p [-]
  std::size_t iterations = 0;        //!< Levenberg–Marquardt steps the refinement took
  //! The search's fit with as many atoms, as the estimator left it (-1: the search made none).
  //! Under coloured noise an order below the chosen count - 1 was fitted against white noise
  //! and only re-weighed whitened, not refitted, so it may lie a little above its optimum [-].
  double found_misfit = -1.0;
  double found_penalty = 0.0;        //!< its loads' prior term [-]
};

struct RecordEstimate {
  NoiseLevel noise;                     //!< white level from the band above the prior's lines
  NoiseSpectrum spectrum;               //!< the fitted noise spectrum (coloured prior only)
  double sigma_v = 0.0;                 //!< the (whitened) noise level the evidence used [V]
  double residual_sigma_v = 0.0;        //!< rms of the chosen fit's whitened residual [V]
  std::vector<double> fit_residual_v2;  //!< whitened RSS of the best fit with n atoms, index n [V^2]
  CountPosterior posterior;             //!< raw (uncalibrated)
  std::size_t count = 0;                //!< the most probable count
  std::vector<EstimatedLine> lines;     //!< at that count, ascending in k
  FitState state;                       //!< the chosen fit's parameters (device's shared ones included)
  double median_stiffness_n_per_m = 0.0;  //!< median of the identified k
  double sd_log_stiffness = 0.0;        //!< sample sd of ln k (n - 1 denominator; 0 below 2 lines)
  double in_band_power_ratio = 1.0;     //!< residual power in the lines' band over the noise band's (1: white)
  ResidualChecks checks;                //!< the chosen fit's residual against the noise model
  std::size_t lines_outside_prior = 0;  //!< identified k beyond the prior's 1e-4 / 1 - 1e-4 quantiles
  std::size_t onset_steps = 0;          //!< contact onsets seen as steps (inverse/onset_steps.hpp; onsets free only)
  bool more_than_prior_allows = false;  //!< one atom more than the prior's largest count still explains much
  double signal_to_noise_db = 0.0;      //!< 10 log10(var(model) / sigma^2) of the chosen fit [dB]
  double seconds = 0.0;                 //!< CPU time of the estimate (its thread's) [s]
  std::optional<ReferenceFit> reference;  //!< with a reference population only
};

class RecordEstimator {
 public:
  //! Holds FFT plans: one estimator per thread.
  RecordEstimator(const AtomLibrary& atoms, const InversePrior& prior, const LineSearchOptions& options = {});

  //! With `reference` (atoms and shared parameters to start from), its refit is reported
  //! beside the estimate (ReferenceFit), which it does not change.
  RecordEstimate estimate(std::span<const double> voltage, const FitState* reference = nullptr);

  [[nodiscard]] const AtomLibrary& atoms() const { return *atoms_; }
  [[nodiscard]] const InversePrior& prior() const { return prior_; }
  [[nodiscard]] const FitLayout& layout() const { return layout_; }
  [[nodiscard]] const RecordModel& model() const { return model_; }
  //! The frequency band the prior's lines fall in [Hz].
  [[nodiscard]] double line_band_low_hz() const { return band_low_hz_; }
  [[nodiscard]] double line_band_high_hz() const { return band_high_hz_; }

 private:
  ResidualChecks residual_checks(const RecordFit& fit, FitState state) const;

  const AtomLibrary* atoms_;
  InversePrior prior_;
  LoadPrior loads_;
  FitLayout layout_;
  LogStiffnessDensity density_;
  RecordModel model_;
  LineProposals proposals_;
  LineSearchOptions options_;
  NestedSearch nested_;
  double band_low_hz_ = 0.0, band_high_hz_ = 0.0;
  double support_low_ = 0.0, support_high_ = 0.0;
  NoiseEstimator noise_;
};

//! The relative accuracy the record model is trusted to (atoms ~1e-3 at v_b = 1 m/s, 5e-4
//! above; the circuit coupling ~5e-4 at 16 asperities: docs/inverse.md, "atoms"); added to the
//! noise as a floor so a noise-free record does not get a zero-width answer from model error.
inline constexpr double MODEL_RELATIVE_ACCURACY = 1e-3;

//! The smallest noise level the evidence uses, relative to one atom's amplitude R sigma w v_b
//! [-]. A record scaled far below the device's amplitude (by 1e-200) squares to a noise of 0,
//! and the evidence then divides by it. 1e-12 is far below the atoms' own accuracy (~1e-4)
//! and any real record's noise, so it binds on such records only.
inline constexpr double MIN_RELATIVE_NOISE = 1e-12;

}  // namespace stengmc
