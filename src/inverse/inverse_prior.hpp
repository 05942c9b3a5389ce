#pragma once
//! The `[inverse]` table of a study: what an inversion assumes before it sees a record (the
//! prior the calibration simulates), and how large a calibration to make (README: inverse
//! estimation, study keys).
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/toml_reader.hpp"
#include "surface/distribution.hpp"

namespace stengmc {

//! The family of the sliding asperities' stiffness law.
enum class StiffnessFamily { lognormal, gamma, weibull };
//! `[inverse] stiffness_law`; the names are also the surface file's distribution kinds.
inline constexpr NameTable STIFFNESS_FAMILY_NAMES{
    std::array{NamedValue<StiffnessFamily>{StiffnessFamily::lognormal, "lognormal"},
               NamedValue<StiffnessFamily>{StiffnessFamily::gamma, "gamma"},
               NamedValue<StiffnessFamily>{StiffnessFamily::weibull, "weibull"}}};

inline std::string_view stiffness_family_name(StiffnessFamily family) { return STIFFNESS_FAMILY_NAMES.name(family); }

//! What the prior says of the measurement noise's spectrum.
enum class NoiseColour {
  white,     //!< white Gaussian noise
  coloured,  //!< white plus a 1/f^alpha part of any share, alpha in [0.5, 2]
};
inline constexpr NameTable NOISE_COLOUR_NAMES{std::array{NamedValue<NoiseColour>{NoiseColour::white, "white"},
                                                         NamedValue<NoiseColour>{NoiseColour::coloured, "coloured"}}};

//! The coloured part's exponent alpha a `coloured` prior draws from, uniformly (MODEL.md §3.6).
inline constexpr std::array<double, 2> COLOURED_EXPONENT_RANGE{0.5, 2.0};

struct InversePrior {
  std::size_t count_min = 1;   //!< fewest sliding asperities a record may hold
  std::size_t count_max = 16;  //!< most
  StiffnessFamily family = StiffnessFamily::lognormal;
  //! Ranges of the law's parameters, each drawn uniformly per record: lognormal (median
  //! [N/m], sigma_log [-]); gamma and weibull (shape [-], scale [N/m]).
  std::array<double, 2> first{40.0, 120.0};
  std::array<double, 2> second{0.2, 0.6};
  std::array<double, 2> snr_db{20.0, 40.0};  //!< signal-to-noise range, 10 log10(var V / sigma^2) [dB]
  //! Range of the coefficient of variation of the per-asperity loads around the device's
  //! normal_load_n, drawn uniformly per record (Greenwood–Williamson, MODEL.md §4.4); [0, 0]:
  //! every asperity carries the device's load [-]
  std::array<double, 2> load_cv{0.0, 0.0};
  //! Contact onsets, each asperity's uniform on this range [s]; [0, 0]: all at t = 0
  std::array<double, 2> onset_s{0.0, 0.0};
  //! mu_s, mu_k, c, the mean normal load, sigma and d0 each within +-this (relative,
  //! uniform) of the device's values, one draw per record shared by its asperities [-]
  double parameter_tolerance = 0.0;
  NoiseColour noise = NoiseColour::white;  //!< the noise's spectrum
  bool offset = false;                     //!< the record may carry a constant offset
  std::size_t calibration_records = 2000;    //!< records a calibration bank simulates
  std::uint64_t seed = 1;                    //!< the calibration's master seed

  //! The law at parameters (p1, p2) of the family.
  [[nodiscard]] Distribution law(double first_parameter, double second_parameter) const;
  //! Names of the two parameters as study keys ("median_n_per_m", "sigma_log", ...).
  [[nodiscard]] std::pair<std::string, std::string> parameter_keys() const;
  //! [k_low, k_high]: the tail-quantiles `tail` and 1 - tail of the laws over the parameter
  //! box (checked on a 5 x 5 grid of it) [N/m].
  [[nodiscard]] std::pair<double, double> support(double tail = 1e-4) const;
  //! The prior's marginal density of ln k (a law drawn from the box, then k from it),
  //! tabulated on `points` values of ln k over `support(1e-6)`.
  [[nodiscard]] std::vector<std::pair<double, double>> log_stiffness_density(std::size_t points = 256) const;
  //! The prior as "key = value" lines (provenance, bank identity).
  [[nodiscard]] std::string describe() const;
  //! True when the prior is today's ideal device: equal loads, all in contact at t = 0, the
  //! known parameters exact, white noise, no offset.
  [[nodiscard]] bool ideal_device() const;
  //! The largest load ratio N_i / N the prior lets an asperity carry, over its load spread and
  //! tolerance: the spread law's 1 - tail quantile at the largest CV, times 1 + tolerance [-].
  [[nodiscard]] double largest_load_ratio(double tail = 1e-4) const;
};

//! The largest parameter_tolerance a prior accepts: beyond it the "known" device is not known.
inline constexpr double MAX_PARAMETER_TOLERANCE = 0.5;

//! Reads `[inverse]`, checking every key (docs/inverse.md). Ranges are arrays
//! [min, max] (equal ends fix the value).
InversePrior read_inverse_prior(TomlTable& table);

//! The `[inverse]` table of a study file's text, or the defaults when it has none; unknown
//! keys in it are errors naming the file and line.
InversePrior inverse_prior_of_study(const std::string& study_text, const std::string& study_file);

//! The prior's marginal log-density of ln k, interpolated from a table.
class LogStiffnessDensity {
 public:
  explicit LogStiffnessDensity(const InversePrior& prior);
  //! ln p(ln k) (density per unit ln k); far below the table's end beyond it.
  [[nodiscard]] double operator()(double stiffness_n_per_m) const;

 private:
  std::vector<double> x_, log_density_;
};

}  // namespace stengmc
