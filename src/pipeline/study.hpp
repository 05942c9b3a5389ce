#pragma once
//! A study: everything one run (one realisation) needs, read from a TOML study file
//! (docs/study-files.md). The tables of higher layers are theirs: [ensemble] is read by
//! the ensemble layer (ensemble/study_file.hpp), [inverse] by the inverse commands.
#include <cstdint>
#include <string>
#include <vector>

#include <functional>
#include <memory>
#include <optional>

#include "circuit/circuit_solver.hpp"
#include "circuit/netlist_load.hpp"
#include "circuit/netlist_probes.hpp"
#include "spectral/spectrum_settings.hpp"
#include "core/toml_reader.hpp"
#include "model/asperity.hpp"
#include "pipeline/measurement_noise.hpp"
#include "pipeline/output_settings.hpp"
#include "surface/surface.hpp"
#include "tribology/model1.hpp"
#include "tribology/model2.hpp"
#include "tribology/time_grid.hpp"

namespace stengmc {

enum class ModelKind { model1, model2 };
//! `[model] kind` in study and run files.
inline constexpr NameTable MODEL_KIND_NAMES{std::array{NamedValue<ModelKind>{ModelKind::model1, "model1"},
                                                       NamedValue<ModelKind>{ModelKind::model2, "model2"}}};

//! What to do when an asperity's x reaches its element's l (MODEL.md §2).
enum class DomainPolicy {
  error,  //!< stop the run with a message naming the asperity and the time
  flag,   //!< keep the tribology, cut the circuit at the first exit, mark the run invalid
};
//! `[domain] policy`.
inline constexpr NameTable DOMAIN_POLICY_NAMES{std::array{NamedValue<DomainPolicy>{DomainPolicy::error, "error"},
                                                          NamedValue<DomainPolicy>{DomainPolicy::flag, "flag"}}};

//! What drives the S-TENG elements.
enum class CircuitInput {
  actual,   //!< the asperity's own displacement x(t) (the default)
  imposed,  //!< Model 1's imposed x0(t), as in the paper's Fig. 3c
};
//! `[circuit] input`.
inline constexpr NameTable CIRCUIT_INPUT_NAMES{std::array{NamedValue<CircuitInput>{CircuitInput::actual, "actual"},
                                                          NamedValue<CircuitInput>{CircuitInput::imposed, "imposed"}}};

//! A swept or drawn parameter's value (an ensemble's sweep or draws) set before reading.
struct ParameterOverride {
  std::string parameter;  //!< dotted key; "surface.*" reaches into the surface file the study names
  double value = 0.0;
};

struct Study {
  std::string file;           //!< path the study was read from
  std::string text;           //!< the study file, verbatim, recorded in every output
  std::string title;          //!< free text
  std::uint64_t seed = 0;     //!< master seed (recorded; fixed populations draw no numbers)
  double duration_s = 0.0;    //!< simulated time [s]
  double sample_rate_hz = 0;  //!< output sample rate [Hz]
  ModelKind model = ModelKind::model2;
  Model1Params model1;
  Model2Params model2;
  std::string surface_file;   //!< surface file the asperities came from, or "" if inline
  std::string surface_text;   //!< that file, verbatim (recorded beside the study text), or ""
  std::shared_ptr<const Surface> surface;  //!< what every realisation's asperities are drawn from
  std::uint64_t realisation = 0;           //!< the realisation `population` and `asperities` are
  Population population;                   //!< that realisation: summits, contact, asperities
  std::vector<Asperity> asperities;        //!< the asperities a run simulates (= population.asperities)
  CircuitParams circuit;
  std::shared_ptr<const NetlistLoad> netlist;  //!< [circuit] netlist: the load ngspice solves instead of R || C_L
  std::vector<NetlistProbe> probes;            //!< [circuit] probes: the netlist's quantities a run records
  CircuitInput circuit_input = CircuitInput::actual;
  DomainPolicy domain_policy = DomainPolicy::error;
  OutputSettings output;      //!< [output]: what a run writes and where (no number depends on it)
  std::vector<ParameterOverride> overrides;  //!< values set by a sweep before reading (none otherwise)
  std::optional<SpectrumSettings> spectrum;  //!< spectral analysis, when the study has [spectrum]
  std::optional<NoiseSettings> noise;        //!< measurement noise on V before the spectra ([noise])

  //! The output grid.
  [[nodiscard]] TimeGrid grid() const { return TimeGrid::covering(duration_s, sample_rate_hz); }
};

//! Reads and validates a study file and draws realisation `realisation` of its surface
//! (none when nullopt: an ensemble draws each with study_for_realisation); throws
//! InputError naming file, line, key and what was expected (ModelError when the
//! realisation itself cannot be loaded). Relative surface paths are taken from the study
//! file's folder. An [ensemble] table is left unread (and unchecked): read the file with
//! read_study_file (ensemble/study_file.hpp) where an ensemble matters.
Study read_study(const std::string& file, std::optional<std::uint64_t> realisation = 0,
                 const std::vector<ParameterOverride>& overrides = {});

//! The same from text (tests, studies made by the program); `file` is used in messages and
//! to resolve surface paths.
Study parse_study(const std::string& text, const std::string& file, std::optional<std::uint64_t> realisation = 0,
                  const std::vector<ParameterOverride>& overrides = {});

//! Reads the tables a higher layer owns ([ensemble]) from the study's root table, after
//! the pipeline's own and before unknown keys are rejected.
using UpperTablesReader = std::function<void(TomlTable& root)>;

//! The reader behind read_study / parse_study for a document a higher layer has opened:
//! `upper_tables` reads that layer's tables (without it, [ensemble] is left unread).
Study parse_study_document(TomlDocument& document, std::optional<std::uint64_t> realisation,
                           const std::vector<ParameterOverride>& overrides, const UpperTablesReader& upper_tables);

//! The tribology model of a study file alone ([model]; nothing else is read or drawn).
struct ModelParameters {
  ModelKind kind = ModelKind::model2;
  Model1Params model1;
  Model2Params model2;
};
ModelParameters read_model_parameters(const std::string& file);

inline std::string_view model_name(ModelKind kind) { return MODEL_KIND_NAMES.name(kind); }
inline std::string_view domain_policy_name(DomainPolicy policy) { return DOMAIN_POLICY_NAMES.name(policy); }

}  // namespace stengmc
