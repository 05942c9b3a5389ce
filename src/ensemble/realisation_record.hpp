#pragma once
//! What an ensemble keeps of one realisation: its scalars, its per-asperity table and,
//! for a chosen few, its traces. A record depends on the study and the realisation id
//! alone, so it can be computed anywhere (thread, process, machine) and merged by id.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace stengmc {

//! The per-realisation scalars, in file order (docs/ensembles.md, ensemble output). The numeric
//! order is part of the journal format: append new ones at the end, never reorder.
enum class Scalar : std::size_t {
  summit_count,         //!< summits drawn [-]
  asperity_count,       //!< summits in contact: the asperities simulated [-]
  contact_density,      //!< A_r / A0 [-] (0 without material data)
  load_redistribution,  //!< fraction of W the spots' interaction moves [-]
  n_sliding,            //!< asperities expected to show a line [-]
  voltage_rms_v,        //!< rms of the clean V over the valid samples [V]
  voltage_peak_v,       //!< max |V| [V]
  final_charge_c,       //!< Q at the last valid sample [C]
  mean_charging_rate_a, //!< final charge / simulated time [A]
  fft_detected,         //!< FFT peaks detected [-]
  fft_identifiable,     //!< asperities identified by FFT peaks [-]
  fft_ratio,            //!< fft_identifiable / n_sliding [-]
  hr_detected,          //!< ESPRIT lines [-]
  hr_identifiable,      //!< asperities identified by ESPRIT lines [-]
  hr_ratio,             //!< hr_identifiable / n_sliding [-]
  cannot_slip_count,    //!< Model 1 asperities that cannot slip [-]
  near_length_count,    //!< Model 2 asperities breaking away near l [-]
  independence_holds,   //!< 1 when the interaction stays below its threshold [-]
  count_,               // number of scalars (not a scalar)
};

inline constexpr std::size_t SCALAR_COUNT = static_cast<std::size_t>(Scalar::count_);

//! Name (as in files and [ensemble] target_statistic), unit and meaning (the files'
//! `long_name`) of each scalar.
struct ScalarInfo {
  std::string_view name;
  std::string_view unit;
  std::string_view long_name;
};
const ScalarInfo& scalar_info(Scalar scalar);
//! The scalar called `name`, or false.
bool scalar_by_name(std::string_view name, Scalar& out);
//! Every scalar name, comma-separated (for messages).
std::string scalar_names();

//! Per-asperity columns, same rules as Scalar.
enum class AsperityColumn : std::size_t {
  stiffness_n_per_m,
  normal_load_n,
  mass_kg,
  natural_frequency_hz,
  slip_fraction,
  max_x_over_l,
  rms_velocity_m_per_s,
  fft_identified,        //!< 0/1
  fft_frequency_error_hz,
  hr_identified,         //!< 0/1
  hr_frequency_error_hz,
  count_,
};
inline constexpr std::size_t ASPERITY_COLUMN_COUNT = static_cast<std::size_t>(AsperityColumn::count_);
const ScalarInfo& column_info(AsperityColumn column);

//! A named list of numbers a record carries besides its scalars and columns: the values an
//! [[ensemble.draw]] gave it ("draw:<parameter>"), or what a caller computed from it (the
//! inverse calibration's truths and estimates). Journalled with the record.
struct RecordExtra {
  std::string name;
  std::vector<double> values;
};

struct RealisationRecord {
  std::uint64_t realisation = 0;
  //! false: the model broke (x reached l under `flag`, an integrator or contact failure,
  //! nothing in contact); kept out of the statistics, counted and named in the summary.
  bool valid = true;
  std::string failure;  //!< why not valid ("" when valid)
  std::array<double, SCALAR_COUNT> scalars{};  //!< indexed by Scalar; all finite
  //! [column][asperity], indexed by AsperityColumn; every column the same length.
  std::array<std::vector<double>, ASPERITY_COLUMN_COUNT> asperities;
  //! Traces, only for the study's trace realisations: time, clean voltage, charge.
  std::vector<double> time_s, voltage_v, charge_c;
  //! The voltage with the study's [noise] (what the spectra analysed), with the traces; empty without [noise].
  std::vector<double> measured_voltage_v;
  //! Named extras, in the order they were added.
  std::vector<RecordExtra> extras;

  //! The extra called `name`, or nullptr.
  [[nodiscard]] const RecordExtra* extra(std::string_view name) const {
    for (const RecordExtra& e : extras)
      if (e.name == name) return &e;
    return nullptr;
  }

  [[nodiscard]] double scalar(Scalar s) const { return scalars[static_cast<std::size_t>(s)]; }
  double& scalar(Scalar s) { return scalars[static_cast<std::size_t>(s)]; }
  [[nodiscard]] std::size_t asperity_count() const { return asperities[0].size(); }
};

}  // namespace stengmc
