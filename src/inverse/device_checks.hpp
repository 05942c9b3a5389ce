#pragma once
//! The known device checked as `run` checks a study, at the stiffnesses an inversion
//! simulates (docs/inverse.md; docs/faults.md). `invert` and `calibrate` run the device's
//! forward model for asperities across the prior's stiffness range (the atoms, the
//! calibration's records): what `run` refuses for those runs they refuse too, up front and
//! with run's own checks, and so is what no inversion can use.
#include <span>
#include <string>
#include <utility>

#include "inverse/inverse_prior.hpp"
#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"
#include "pipeline/study.hpp"

namespace stengmc {

//! The atoms reach this far beyond the prior's 1e-4 / 1 - 1e-4 quantiles, so lines just
//! outside the prior are still fitted (and reported as such) [-].
inline constexpr double ATOM_RANGE_MARGIN = 1.25;

//! The stiffnesses an inversion may simulate: the prior's 1e-4 .. 1 - 1e-4 quantiles
//! widened by ATOM_RANGE_MARGIN each way [N/m] (the atoms then drop the soft end where an
//! asperity would reach its element's length).
std::pair<double, double> simulated_stiffness_range(const InversePrior& prior);

//! The study `run` would run for the known device with one asperity of each stiffness, on
//! the record grid: `known` with its asperities replaced, no spectra and no noise. Its
//! `file` says which runs it stands for (messages).
Study device_study_at(const Study& known, const KnownDevice& device, std::span<const double> stiffness_n_per_m,
                      const RecordGrid& grid);

//! Refuses up front, naming `known` and the keys at fault (InputError):
//!  - run's sample-rate check (pipeline/study_realisation.hpp) for the prior's stiffest
//!    asperity: a mass of 1e-300 kg puts its natural frequency at 1e150 Hz;
//!  - a softest asperity that is over-damped (c/2m >= sqrt(k/m)): it has no line to find;
//!  - a record that ends before the stiffest asperity breaks away from the belt (no line);
//!  - every asperity of the prior dragged to its element's length before it breaks away
//!    (run's validity report, pipeline/validity.hpp, at the stiffest asperity);
//!  - a one-asperity voltage R sigma w v_b beyond what the analyses can square and sum.
void check_device_over_prior(const Study& known, const KnownDevice& device, const InversePrior& prior,
                             const RecordGrid& grid);

//! Refuses a prior the device cannot take, naming `known` and the [inverse] key:
//!  - a parameter_tolerance that lets mu_s fall below mu_k (mu_s (1 - tau) < mu_k (1 + tau));
//!  - contact onsets that reach the end of the record (onset_s's max >= the record's last time).
void check_prior_over_device(const Study& known, const KnownDevice& device, const InversePrior& prior,
                             const RecordGrid& grid);

//! Throws InputError for the study key at `dotted_path` ("model.damping_n_s_per_m"), at its
//! line when the study file itself sets it, else naming the file and the key: "`what`" follows
//! the key ("= 1 N s/m over-damps ...").
[[noreturn]] void fail_at_study_key(const Study& known, const std::string& dotted_path, const std::string& what);

}  // namespace stengmc
