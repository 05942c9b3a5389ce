#include "pipeline/study.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "circuit/circuit_settings.hpp"
#include "circuit/netlist_key.hpp"
#include "circuit/netlist_probes.hpp"
#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_reader.hpp"
#include "pipeline/study_realisation.hpp"
#include "surface/surface.hpp"
#include "tribology/model1_settings.hpp"
#include "tribology/model2_settings.hpp"

namespace stengmc {

namespace {

// Drive periods a Model 1 run may span: omega t then still has ~1e-3 rad of precision.
constexpr double MAX_DRIVE_PERIODS = 1e12;

void read_model(TomlTable& root, Study& study) {
  auto model = root.table("model");
  if (!model) root.fail("model", "is missing: a [model] table with kind = \"model1\" or \"model2\" is required");
  if (!model->has("kind")) model->fail("kind", "is missing: \"model1\" (imposed sinusoid) or \"model2\" (moving belt)");
  study.model = MODEL_KIND_NAMES.value(model->choice("kind", "", MODEL_KIND_NAMES.names()));
  if (study.model == ModelKind::model1) study.model1 = read_model1_params(*model);
  else study.model2 = read_model2_params(*model);
}

void read_surface(TomlTable& root, Study& study, const std::vector<ParameterOverride>& surface_overrides) {
  auto surface = root.table("surface");
  if (!surface)
    root.fail("surface", "is missing: a [surface] table with file = \"...\", [[surface.asperity]] entries or kind = \"random\" is required");
  const std::filesystem::path study_dir = std::filesystem::path(study.file).parent_path();
  if (!surface->has("file")) {
    study.surface = std::make_shared<const Surface>(Surface::from_toml(*surface, study_dir));
    return;
  }
  for (const char* inline_key : {"asperity", "defaults", "kind"})
    if (surface->has(inline_key))
      surface->fail("file", "cannot be combined with an inline surface ([surface] " + std::string(inline_key) + "): choose one");
  const std::string name = surface->string("file", "");
  const std::filesystem::path path =
      (std::filesystem::path(name).is_absolute() ? std::filesystem::path(name) : study_dir / name).lexically_normal();
  if (!std::filesystem::exists(path))
    surface->fail("file", "= \"" + name + "\": no such file (looked for " + path.string() + ")");
  std::unique_ptr<TomlDocument> document;
  try {
    document = TomlDocument::from_file(path.string());
  } catch (const InputError& e) {
    surface->fail("file", "= \"" + name + "\": " + e.what());
  }
  for (const ParameterOverride& o : surface_overrides) document->set_number(o.parameter.substr(8), o.value);
  TomlTable table = document->root();
  study.surface = std::make_shared<const Surface>(Surface::from_toml(table, path.parent_path()));
  document->reject_unknown_keys();
  study.surface_file = path.string();
  study.surface_text = document->text();
}

void read_circuit(TomlTable& root, Study& study) {
  auto circuit = root.table("circuit");
  if (!circuit) return;
  study.circuit = read_circuit_params(*circuit);
  study.netlist = read_netlist_key(*circuit, study.file);
  study.probes = read_probes_key(*circuit, study.netlist.get());
  study.circuit_input = circuit->enumeration("input", study.circuit_input, CIRCUIT_INPUT_NAMES);
  if (study.circuit_input == CircuitInput::imposed && study.model != ModelKind::model1)
    circuit->fail("input", "= \"imposed\" needs [model] kind = \"model1\" (only Model 1 imposes a displacement x0)");
}


}  // namespace

Study parse_study_document(TomlDocument& document, std::optional<std::uint64_t> realisation,
                           const std::vector<ParameterOverride>& overrides, const UpperTablesReader& upper_tables) {
  Study study;
  study.overrides = overrides;
  // Swept values are set before anything is read; "surface.*" goes to the surface file
  // when the study names one (the study text itself stays as written: it is recorded).
  std::vector<ParameterOverride> surface_overrides;
  const bool surface_file = document.has_path("surface.file");
  for (const ParameterOverride& o : overrides) {
    if (surface_file && o.parameter.rfind("surface.", 0) == 0) surface_overrides.push_back(o);
    else document.set_number(o.parameter, o.value);
  }
  study.file = document.file();
  study.text = document.text();
  TomlTable root = document.root();
  study.title = root.string("title", "");
  study.seed = static_cast<std::uint64_t>(root.integer("seed", 0, 0));
  if (!root.has("duration_s")) root.fail("duration_s", "is missing: the simulated time in seconds is required");
  if (!root.has("sample_rate_hz")) root.fail("sample_rate_hz", "is missing: the output sample rate in Hz is required");
  study.duration_s = root.positive("duration_s", 0.0);
  study.sample_rate_hz = root.positive("sample_rate_hz", 0.0);
  read_model(root, study);
  if (auto counterface = root.table("counterface")) {
    if (study.model != ModelKind::model2)
      counterface->fail("friction_modulation_rms", "[counterface] modulates Model 2's belt friction; [model] kind is \"model1\"");
    study.model2.counterface = read_counterface(*counterface, study.model2.belt_velocity_m_per_s);
  }
  read_surface(root, study, surface_overrides);
  read_circuit(root, study);
  if (auto domain = root.table("domain")) {
    study.domain_policy = domain->enumeration("policy", study.domain_policy, DOMAIN_POLICY_NAMES);
  }
  if (auto spectrum = root.table("spectrum")) study.spectrum = read_spectrum_settings(*spectrum);
  if (auto noise = root.table("noise")) {
    study.noise = read_noise_settings(*noise);
    if (!study.spectrum) noise->fail("snr_db", "needs a [spectrum] table: the noise is added to the voltage the spectra analyse");
  }
  // [inverse] (the prior of `stengmc calibrate` / `invert`) belongs to the inverse layer,
  // which reads and checks it itself; [ensemble] to the ensemble layer, which reads it
  // here when it opened the document.
  if (root.has("inverse")) document.defer_table("inverse");
  if (upper_tables) upper_tables(root);
  else if (root.has("ensemble")) document.defer_table("ensemble");
  {
    auto output = root.table("output");
    study.output = read_output_settings(output ? &*output : nullptr, study.file);
  }
  document.reject_unknown_keys();

  if (realisation) draw_realisation(study, *realisation, &root);
  // The grid must end at duration_s: a fractional sample count would silently change it.
  const double intervals = study.duration_s * study.sample_rate_hz;
  if (std::abs(intervals - std::round(intervals)) > 1e-6 * std::max(1.0, intervals))
    root.fail("duration_s", "x sample_rate_hz = " + format_number(intervals) +
                                " is not a whole number of sample intervals; adjust duration_s or sample_rate_hz");
  // Model 1's phase omega t is a double: beyond ~1e12 drive periods it keeps no digits, and
  // the slip-end scan's step (1/64 of a period) stops advancing time (the run never ends).
  if (study.model == ModelKind::model1) {
    for (std::size_t i = 0; i < study.asperities.size(); ++i)
      if (study.asperities[i].onset_s != 0.0)
        root.table("model")->fail("kind", "= \"model1\": asperity " + std::to_string(i + 1) + " has onset_s = " +
                                              format_number(study.asperities[i].onset_s) +
                                              " s; a contact onset is a Model 2 key (Model 1's drive acts from t = 0)");
    for (std::size_t i = 0; i < study.asperities.size(); ++i) {
      const Asperity& a = study.asperities[i];
      if (std::isfinite(a.release_s) || a.wear_rate_per_ms != 0.0 || !a.stiffness_steps.empty())
        root.table("model")->fail("kind", "= \"model1\": asperity " + std::to_string(i + 1) +
                                              " has release_s, wear_rate_per_ms or stiffness_steps; an evolving "
                                              "contact is a Model 2 key (docs/model.md §1.4)");
    }
    const double periods = study.model1.drive_angular_frequency_rad_per_s / (2.0 * PI) * study.duration_s;
    if (!(periods <= MAX_DRIVE_PERIODS))
      root.table("model")->fail("drive_frequency_hz",
                                "= " + format_number(study.model1.drive_angular_frequency_rad_per_s / (2.0 * PI)) +
                                    " Hz over duration_s = " + format_number(study.duration_s) + " s is " +
                                    format_number(periods) + " drive periods; the drive phase loses its precision "
                                    "beyond " + format_number(MAX_DRIVE_PERIODS));
  }
  const double samples = std::round(intervals) + 1.0;
  if (samples < 2.0)
    root.fail("duration_s", "x sample_rate_hz gives fewer than 2 samples; lengthen duration_s or raise sample_rate_hz");
  // What the run will cost is estimated, against limits the command line sets, by every
  // command before it starts (pipeline/work_estimate.hpp), not here.
  return study;
}

ModelParameters read_model_parameters(const std::string& file) {
  auto document = TomlDocument::from_file(file);
  TomlTable root = document->root();
  Study study;
  read_model(root, study);
  document->reject_unknown_keys("model");
  return {study.model, study.model1, study.model2};
}

Study read_study(const std::string& file, std::optional<std::uint64_t> realisation,
                 const std::vector<ParameterOverride>& overrides) {
  auto document = TomlDocument::from_file(file);
  return parse_study_document(*document, realisation, overrides, {});
}

Study parse_study(const std::string& text, const std::string& file, std::optional<std::uint64_t> realisation,
                  const std::vector<ParameterOverride>& overrides) {
  auto document = TomlDocument::from_string(text, file);
  return parse_study_document(*document, realisation, overrides, {});
}

}  // namespace stengmc
