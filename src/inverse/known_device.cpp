#include "inverse/known_device.hpp"

#include <cmath>
#include <sstream>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/toml_library.hpp"  // toml++: the [[asperity]] entries, which TomlDocument cannot walk without reading them
#include "core/toml_reader.hpp"

namespace stengmc {

namespace {

// Model and circuit keys, looked up in the study itself.
const std::vector<std::string> MODEL_KEYS = {
    "model.kind",           "model.belt_velocity_m_per_s", "model.static_friction",       "model.kinetic_friction",
    "model.damping_n_s_per_m", "model.stribeck_decay_s_per_m", "model.atan_sharpness_s_per_m", "model.friction_form",
    "circuit.load_resistance_ohm", "circuit.load_capacitance_f"};
// Per-asperity keys: in the defaults table, or in every asperity entry.
const std::vector<std::string> ASPERITY_KEYS = {"mass_kg",  "normal_load_n",        "charge_density_c_per_m2",
                                                "effective_thickness_m", "width_m", "length_m"};

//! True when the per-asperity key is set for every asperity of the fixed list in `document`
//! under `prefix` ("surface." in a study, "" in a surface file).
bool asperity_key_given(const TomlDocument& document, const std::string& prefix, const std::string& key) {
  if (document.has_path(prefix + "defaults." + key)) return true;
  // Without a default, every [[asperity]] entry must set it.
  const toml::table root = toml::parse(document.text());  // cheap: a study is small
  const toml::node* list = nullptr;
  if (prefix.empty()) list = root.get("asperity");
  else if (const auto* surface = root.get_as<toml::table>("surface")) list = surface->get("asperity");
  const auto* array = list ? list->as_array() : nullptr;
  if (!array || array->empty()) return false;
  for (const auto& entry : *array)
    if (!entry.as_table() || !entry.as_table()->contains(key)) return false;
  return true;
}

bool same(double a, double b) { return a == b || std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); }

}  // namespace

const std::vector<std::string>& required_device_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> all = MODEL_KEYS;
    for (const auto& k : ASPERITY_KEYS) all.push_back("surface.defaults." + k);
    return all;
  }();
  return keys;
}

double KnownDevice::angular_frequency(double stiffness_n_per_m) const {
  const double d = damping_rate_per_s();
  const double w2 = stiffness_n_per_m / asperity.mass_kg - d * d;
  return w2 > 0.0 ? std::sqrt(w2) : 0.0;
}

double KnownDevice::stiffness_for(double angular_frequency_rad_per_s) const {
  const double d = damping_rate_per_s();
  return asperity.mass_kg * (angular_frequency_rad_per_s * angular_frequency_rad_per_s + d * d);
}

double KnownDevice::voltage_scale_v() const {
  return circuit.load_resistance_ohm * asperity.element.charge_density_c_per_m2 * asperity.element.width_m *
         model.belt_velocity_m_per_s;
}

double KnownDevice::element_capacitance_f(double displacement_m) const {
  const StengElement& e = asperity.element;
  return EPSILON_0 * e.width_m * (e.length_m - displacement_m) / e.effective_thickness_m;
}

double KnownDevice::sliding_friction_n() const {
  const auto& f = model.friction;
  return asperity.normal_load_n *
         (f.kinetic_coefficient + (f.static_coefficient - f.kinetic_coefficient) *
                                      std::exp(-model.stribeck_decay_s_per_m * model.belt_velocity_m_per_s));
}

std::string KnownDevice::describe() const {
  std::ostringstream out;
  out.precision(17);
  const auto& e = asperity.element;
  out << "model = model2\n"
      << "friction_form = " << model.friction_law->name << "\n"
      << "static_friction = " << model.friction.static_coefficient << "\n"
      << "kinetic_friction = " << model.friction.kinetic_coefficient << "\n"
      << "belt_velocity_m_per_s = " << model.belt_velocity_m_per_s << "\n"
      << "damping_n_s_per_m = " << model.damping_n_s_per_m << "\n"
      << "stribeck_decay_s_per_m = " << model.stribeck_decay_s_per_m << "\n"
      << "atan_sharpness_s_per_m = " << model.atan_sharpness_s_per_m << "\n"
      << "relative_tolerance = " << model.relative_tolerance << "\n"
      << "mass_kg = " << asperity.mass_kg << "\n"
      << "normal_load_n = " << asperity.normal_load_n << "\n"
      << "charge_density_c_per_m2 = " << e.charge_density_c_per_m2 << "\n"
      << "effective_thickness_m = " << e.effective_thickness_m << "\n"
      << "width_m = " << e.width_m << "\n"
      << "length_m = " << e.length_m << "\n"
      << "load_resistance_ohm = " << circuit.load_resistance_ohm << "\n"
      << "load_capacitance_f = " << circuit.load_capacitance_f << "\n"
      << "substeps = " << circuit.substeps << "\n";
  return out.str();
}

KnownDevice known_device_from_study(const Study& study) {
  const std::string& file = study.file;
  if (study.model != ModelKind::model2)
    throw InputError(file + ": [model] kind = \"model1\": inverse estimation needs a Model 2 device (a belt sliding "
                            "at a known velocity); Model 1's imposed sinusoid is not supported");
  if (study.surface->random_surface())
    throw InputError(file + ": [surface] is a random surface: give the known device as a study with a fixed list "
                            "([surface.defaults] and one [[surface.asperity]]; its stiffness is not used)");

  // Every known parameter written out, in the study or in the surface file it names.
  auto study_doc = TomlDocument::from_string(study.text, file);
  std::unique_ptr<TomlDocument> surface_doc;
  if (!study.surface_file.empty()) surface_doc = TomlDocument::from_string(study.surface_text, study.surface_file);
  std::vector<std::string> missing;
  for (const std::string& key : MODEL_KEYS)
    if (!study_doc->has_path(key)) missing.push_back(key);
  for (const std::string& key : ASPERITY_KEYS) {
    const bool given = surface_doc ? asperity_key_given(*surface_doc, "", key) : asperity_key_given(*study_doc, "surface.", key);
    if (!given) missing.push_back((surface_doc ? study.surface_file + ": defaults." : std::string("surface.defaults.")) + key);
  }
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
    throw InputError(file + ": the known device is missing " + list +
                     ". Inverse estimation needs every known parameter written out (MODEL.md's defaults are not "
                     "assumed): a parameter left out by mistake would bias every estimate without a sign");
  }

  KnownDevice device;
  device.study_file = file;
  device.model = study.model2;
  device.circuit = study.circuit;
  device.duration_s = study.duration_s;
  device.sample_rate_hz = study.sample_rate_hz;
  // A fixed list (checked above) is the same in every realisation.
  const std::vector<Asperity> list = study.asperities.empty() ? study.surface->sample(study.seed, 0).asperities : study.asperities;
  if (list.empty()) throw InputError(file + ": the known device study has no asperity to take the shared parameters from");
  device.asperity = list.front();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Asperity& a = list[i];
    const Asperity& b = device.asperity;
    auto differs = [&](const char* what) {
      throw InputError(file + ": asperity " + std::to_string(i + 1) + " has another " + what +
                       " than asperity 1: inverse estimation assumes every asperity shares the known parameters "
                       "(only the stiffness is unknown)");
    };
    if (!same(a.mass_kg, b.mass_kg)) differs("mass_kg");
    if (!same(a.normal_load_n, b.normal_load_n)) differs("normal_load_n");
    if (!same(a.element.charge_density_c_per_m2, b.element.charge_density_c_per_m2)) differs("charge_density_c_per_m2");
    if (!same(a.element.effective_thickness_m, b.element.effective_thickness_m)) differs("effective_thickness_m");
    if (!same(a.element.width_m, b.element.width_m)) differs("width_m");
    if (!same(a.element.length_m, b.element.length_m)) differs("length_m");
    if (a.initial_displacement_m != 0.0 || a.initial_velocity_m_per_s != 0.0)
      throw InputError(file + ": asperity " + std::to_string(i + 1) +
                       " does not start at rest: inverse estimation assumes x(0) = x'(0) = 0 (the record starts "
                       "when the belt starts)");
  }
  if (!(device.model.belt_velocity_m_per_s > 0.0))
    throw InputError(file + ": [model] belt_velocity_m_per_s = " + format_number(device.model.belt_velocity_m_per_s) +
                     " must be > 0 for inverse estimation (the asperities are dragged by the belt)");
  if (!(device.asperity.normal_load_n > 0.0))
    throw InputError(file + ": normal_load_n must be > 0 for inverse estimation (without load nothing slides)");
  if (device.asperity.element.charge_density_c_per_m2 == 0.0)
    throw InputError(file + ": charge_density_c_per_m2 = 0: the device gives no voltage to invert");
  return device;
}

}  // namespace stengmc
