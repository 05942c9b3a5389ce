// Reading a random surface (docs/study-files.md, surface files). Every rule that needs data another
// table provides is checked here, so a surface that reads is a surface that samples.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <string>

#include "core/format.hpp"
#include "surface/hertz_contact.hpp"
#include "model/asperity.hpp"
#include "surface/random_surface.hpp"

namespace stengmc {

double RandomSurface::mean_summit_count() const {
  return count_rule == CountRule::poisson ? summit_density_per_m2 * nominal_area_m2 : static_cast<double>(summit_count);
}

namespace {

TomlTable required_table(TomlTable& root, std::string_view key, const std::string& what) {
  auto table = root.table(key);
  if (!table) root.fail(key, "is missing: " + what);
  return *table;
}

void read_summits(TomlTable& root, RandomSurface& s) {
  TomlTable t = required_table(root, "summits", "a [summits] table with count_rule = \"poisson\" or \"fixed\" is required");
  const std::string positions = t.choice("positions", "uniform", {"uniform", "given"});
  s.position_rule = positions == "uniform" ? PositionRule::uniform : PositionRule::given;
  const std::string rule = t.choice("count_rule", s.position_rule == PositionRule::given ? "fixed" : "poisson",
                                    {"poisson", "fixed"});
  s.count_rule = rule == "poisson" ? CountRule::poisson : CountRule::fixed;
  const double side = std::sqrt(s.nominal_area_m2);
  if (s.position_rule == PositionRule::given) {
    if (s.count_rule != CountRule::fixed)
      t.fail("count_rule", "= \"poisson\" cannot be combined with positions = \"given\": the list fixes the count");
    s.given_x_m = t.number_list("x_m");
    s.given_y_m = t.number_list("y_m");
    if (s.given_x_m.empty()) t.fail("x_m", "is missing or empty: positions = \"given\" needs x_m = [...] and y_m = [...]");
    if (s.given_x_m.size() != s.given_y_m.size())
      t.fail("y_m", "has " + std::to_string(s.given_y_m.size()) + " entries but x_m has " +
                        std::to_string(s.given_x_m.size()) + ": one (x, y) per summit");
    for (std::size_t i = 0; i < s.given_x_m.size(); ++i)
      if (s.given_x_m[i] < 0.0 || s.given_x_m[i] > side || s.given_y_m[i] < 0.0 || s.given_y_m[i] > side)
        t.fail("x_m", "entry " + std::to_string(i + 1) + " (" + format_number(s.given_x_m[i]) + ", " +
                          format_number(s.given_y_m[i]) + ") m lies outside the nominal square [0, " + format_number(side) +
                          "] m (side sqrt(nominal_area_m2))");
    // Two summits at one point are one summit (and a singular point-load interaction).
    std::vector<std::size_t> order(s.given_x_m.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return std::tie(s.given_x_m[a], s.given_y_m[a], a) < std::tie(s.given_x_m[b], s.given_y_m[b], b);
    });
    for (std::size_t k = 1; k < order.size(); ++k)
      if (s.given_x_m[order[k]] == s.given_x_m[order[k - 1]] && s.given_y_m[order[k]] == s.given_y_m[order[k - 1]])
        t.fail("x_m", "entries " + std::to_string(std::min(order[k], order[k - 1]) + 1) + " and " +
                          std::to_string(std::max(order[k], order[k - 1]) + 1) + " put two summits at the same point");
    s.summit_count = s.given_x_m.size();
    if (t.has("count") && t.integer("count", 0, 1) != static_cast<long long>(s.summit_count))
      t.fail("count", "disagrees with the " + std::to_string(s.summit_count) + " given positions; leave it out");
    return;
  }
  if (s.count_rule == CountRule::poisson) {
    if (!t.has("density_per_m2")) t.fail("density_per_m2", "is missing: count_rule = \"poisson\" needs the summit density [1/m^2]");
    s.summit_density_per_m2 = t.positive("density_per_m2", 0.0);
  } else {
    if (!t.has("count")) t.fail("count", "is missing: count_rule = \"fixed\" needs the number of summits");
    // 0 is a surface with nothing in contact: its runs give V = 0, a record of the
    // measurement chain alone (MODEL.md §4.1).
    s.summit_count = static_cast<std::size_t>(t.integer("count", 0, 0));
  }
  if (s.mean_summit_count() > MAX_MEAN_SUMMITS)
    t.fail(s.count_rule == CountRule::poisson ? "density_per_m2" : "count",
           "gives " + format_number(s.mean_summit_count()) + " summits per realisation, above the limit of " +
               format_number(MAX_MEAN_SUMMITS) +
               (s.count_rule == CountRule::poisson ? "; use a smaller nominal_area_m2" : "; use a smaller count"));
}

void read_materials(TomlTable& root, RandomSurface& s) {
  auto t = root.table("materials");
  if (!t) return;
  auto body = [&](std::string_view key) {
    auto b = t->table(key);
    if (!b) t->fail(key, "is missing: give { youngs_modulus_pa = ..., poisson_ratio = ... }");
    if (!b->has("youngs_modulus_pa")) b->fail("youngs_modulus_pa", "is missing (Young's modulus [Pa])");
    if (!b->has("poisson_ratio")) b->fail("poisson_ratio", "is missing (Poisson's ratio [-])");
    ElasticBody e{b->positive("youngs_modulus_pa", 0.0), b->number("poisson_ratio", 0.0)};
    if (!(e.poisson_ratio > -1.0 && e.poisson_ratio < 0.5))
      b->fail("poisson_ratio", "= " + format_number(e.poisson_ratio) + " must satisfy -1 < nu < 0.5");
    return e;
  };
  ContactMaterials m;
  m.body_1 = body("body_1");
  m.body_2 = body("body_2");
  if (!t->has("summit_radius_m")) t->fail("summit_radius_m", "is missing: the summit radius R_s [m] is required");
  m.summit_radius_m = t->positive("summit_radius_m", 0.0);
  s.materials = m;
}

//! `what` needs material data: say which rule asked for it.
void require_materials(const RandomSurface& s, TomlTable& t, std::string_view key, const std::string& rule) {
  if (!s.materials)
    t.fail(key, "= \"" + rule + "\" needs a [materials] table (body_1, body_2 with youngs_modulus_pa and poisson_ratio, "
                                "and summit_radius_m)");
}

void read_stiffness(TomlTable& root, RandomSurface& s, const std::filesystem::path& base_dir) {
  TomlTable t = required_table(root, "stiffness", "a [stiffness] table with rule = \"sampled\" (and a distribution) or \"mindlin\"");
  const std::string rule = t.choice("rule", "sampled", {"sampled", "mindlin"});
  if (rule == "mindlin") {
    s.stiffness_rule = StiffnessRule::mindlin;
    require_materials(s, t, "rule", rule);
    if (t.has("kind")) t.fail("kind", "is not used with rule = \"mindlin\" (k = 8 G* a): remove it or use rule = \"sampled\"");
    return;
  }
  s.stiffness_rule = StiffnessRule::sampled;
  s.stiffness = Distribution::from_toml(t, base_dir);
  // Laws of positive quantities (lognormal, gamma, Weibull: support from 0) never draw 0;
  // the others can draw their lower end.
  const double lower = s.stiffness->lower();
  const bool open_at_zero = s.stiffness->family() && s.stiffness->family()->support_lower == 0.0;
  if (lower < 0.0 || (!open_at_zero && lower <= 0.0))
    t.fail(t.has("min") ? "min" : "kind", "lets the law draw stiffness " + format_number(lower) +
                                              " N/m: stiffnesses must be > 0 (truncate with min > 0)");
}

void read_load(TomlTable& root, RandomSurface& s) {
  TomlTable t = required_table(root, "load", "a [load] table with rule = \"fixed\" (normal_load_n), \"hertz\" (nominal_load_n) "
                                             "or \"spread\" (mean_load_n, load_cv)");
  const std::string rule = t.choice("rule", "fixed", {"fixed", "hertz", "spread"});
  if (rule == "fixed") {
    s.load_rule = LoadRule::fixed;
    if (t.has("nominal_load_n")) t.fail("nominal_load_n", "is used by rule = \"hertz\" only; rule = \"fixed\" takes normal_load_n");
    s.normal_load_n = t.positive("normal_load_n", s.normal_load_n);
    return;
  }
  if (rule == "spread") {
    s.load_rule = LoadRule::spread;
    for (const char* key : {"normal_load_n", "nominal_load_n"})
      if (t.has(key)) t.fail(key, "is not used by rule = \"spread\", which takes mean_load_n and load_cv");
    if (!t.has("mean_load_n")) t.fail("mean_load_n", "is missing: rule = \"spread\" needs the loads' mean [N]");
    const double mean = t.positive("mean_load_n", 0.0);
    if (!std::isfinite(mean)) t.fail("mean_load_n", "must be finite");
    const double cv = t.non_negative("load_cv", 0.0);
    if (!(cv <= MAX_LOAD_CV))
      t.fail("load_cv", "= " + format_number(cv) + " must lie in [0, " + format_number(MAX_LOAD_CV) +
                            "] (Greenwood–Williamson loads reach at most 1.55 as the separation rises)");
    // Greenwood–Williamson: the loads follow from Gaussian heights above the separation.
    const Distribution& h = s.heights;
    if (!h.family() || h.family()->name != "normal" || h.truncated())
      t.fail("rule", "= \"spread\" draws the summits in contact from Gaussian heights: give [heights] kind = \"normal\" "
                     "(mean, std) without min or max");
    if (s.correlation)
      t.fail("rule", "= \"spread\" draws the heights conditioned on contact, which a [correlation] copula with the "
                     "stiffness cannot follow: leave out [correlation]");
    s.load_spread.emplace(mean, cv);
    return;
  }
  s.load_rule = LoadRule::hertz;
  require_materials(s, t, "rule", rule);
  if (t.has("normal_load_n")) t.fail("normal_load_n", "is used by rule = \"fixed\" only; rule = \"hertz\" takes nominal_load_n");
  if (!t.has("nominal_load_n")) t.fail("nominal_load_n", "is missing: the total load W [N] the flat presses with");
  s.nominal_load_n = t.number("nominal_load_n", 0.0);
  if (!(s.nominal_load_n > 0.0) || !std::isfinite(s.nominal_load_n))
    t.fail("nominal_load_n", "= " + format_number(s.nominal_load_n) +
                                 ": no separation can carry it; an adhesionless flat carries only a finite load W > 0");
  // The load solve brackets the flat's depth between 0 and the interference the tallest
  // summit alone would need; loads, moduli or radii that put it beyond any physical scale
  // also overflow or underflow the solve's arithmetic, so they are refused here by name.
  const double e_star = s.materials->effective_modulus_pa();
  const double depth = hertz_interference_for_load(s.nominal_load_n, s.materials->summit_radius_m, e_star);
  if (!(depth >= MIN_HERTZ_INTERFERENCE_M && depth <= MAX_HERTZ_INTERFERENCE_M))
    t.fail("nominal_load_n", "= " + format_number(s.nominal_load_n) + " N with E* = " + format_number(e_star) +
                                 " Pa and R_s = " + format_number(s.materials->summit_radius_m) +
                                 " m: the tallest summit alone would need an interference of " + format_number(depth) +
                                 " m to carry it; the contact solve works with interferences in [" +
                                 format_number(MIN_HERTZ_INTERFERENCE_M) + ", " + format_number(MAX_HERTZ_INTERFERENCE_M) +
                                 "] m (check the load, the moduli and summit_radius_m)");
}

void read_interaction(TomlTable& root, RandomSurface& s) {
  auto t = root.table("interaction");
  if (!t) return;
  const std::string mode = t->choice("mode", "report", {"report", "apply"});
  s.interaction_mode = mode == "report" ? InteractionMode::report : InteractionMode::apply;
  if (!s.materials) t->fail("mode", "needs a [materials] table: the interaction is computed from E* and the patch loads");
  if (s.interaction_mode == InteractionMode::apply && s.load_rule != LoadRule::hertz)
    t->fail("mode", "= \"apply\" needs [load] rule = \"hertz\": under a fixed load per asperity nothing can redistribute");
  s.interaction.localisation_radius_m = t->non_negative("localisation_radius_m", s.interaction.localisation_radius_m);
  s.interaction.localisation_spacings = t->positive("localisation_spacings", s.interaction.localisation_spacings);
  const std::string kernel = t->choice("kernel", "hertz_pressure", {"hertz_pressure", "point_load"});
  s.interaction.kernel = kernel == "point_load" ? InteractionKernel::point_load : InteractionKernel::hertz_pressure;
}

void read_element(TomlTable& root, RandomSurface& s) {
  auto t = root.table("element");
  if (!t) return;  // Table 2 defaults, fixed geometry
  StengElement& e = s.element;
  e.charge_density_c_per_m2 = t->number("charge_density_c_per_m2", e.charge_density_c_per_m2);
  e.effective_thickness_m = t->positive("effective_thickness_m", e.effective_thickness_m);
  const std::string geometry = t->choice("geometry", "fixed", {"fixed", "patch"});
  s.geometry_rule = geometry == "fixed" ? GeometryRule::fixed : GeometryRule::patch;
  if (s.geometry_rule == GeometryRule::patch) {
    require_materials(s, *t, "geometry", geometry);
    for (const char* key : {"length_m", "width_m"})
      if (t->has(key)) t->fail(key, "is set by geometry = \"patch\" (l = w = sqrt(pi) a); remove it or use geometry = \"fixed\"");
    return;
  }
  e.length_m = t->positive("length_m", e.length_m);
  e.width_m = t->positive("width_m", e.width_m);
}

void read_mass(TomlTable& root, RandomSurface& s) {
  auto t = root.table("mass");
  if (!t) return;
  const std::string rule = t->choice("rule", "fixed", {"fixed", "density"});
  if (rule == "fixed") {
    s.mass_rule = MassRule::fixed;
    s.mass_kg = t->positive("mass_kg", s.mass_kg);
    return;
  }
  s.mass_rule = MassRule::density;
  if (!t->has("density_kg_per_m3")) t->fail("density_kg_per_m3", "is missing: rule = \"density\" needs rho [kg/m^3]");
  s.density_kg_per_m3 = t->positive("density_kg_per_m3", 0.0);
  if (s.heights.lower() < 0.0)
    t->fail("rule", "= \"density\" uses m = rho l w h with h the summit height, but [heights] can draw " +
                        format_number(s.heights.lower()) + " m: truncate the heights at min = 0 or use rule = \"fixed\"");
}

void read_drive(TomlTable& root, RandomSurface& s) {
  auto t = root.table("drive");
  if (!t) return;
  const std::string rule = t->choice("phase", "fixed", {"fixed", "uniform"});
  s.phase_rule = rule == "fixed" ? PhaseRule::fixed : PhaseRule::uniform;
  if (s.phase_rule == PhaseRule::fixed) s.phase_rad = t->number("phase_rad", s.phase_rad);
  else if (t->has("phase_rad")) t->fail("phase_rad", "is not used with phase = \"uniform\"");
  if (!(std::abs(s.phase_rad) <= MAX_DRIVE_PHASE_RAD)) t->fail("phase_rad", "must lie within +-1e6 rad (an angle)");
}

}  // namespace

RandomSurface read_random_surface(TomlTable& root, const std::filesystem::path& base_dir) {
  RandomSurface s;
  s.title = root.string("title", "");
  if (!root.has("nominal_area_m2")) root.fail("nominal_area_m2", "is missing: the nominal contact area A0 [m^2] is required");
  s.nominal_area_m2 = root.positive("nominal_area_m2", 0.0);
  read_summits(root, s);
  TomlTable heights = required_table(root, "heights", "a [heights] table with the summit-height distribution [m]");
  s.heights = Distribution::from_toml(heights, base_dir);
  read_materials(root, s);
  read_stiffness(root, s, base_dir);
  if (auto correlation = root.table("correlation")) {
    if (s.stiffness_rule != StiffnessRule::sampled)
      correlation->fail("rho", "needs [stiffness] rule = \"sampled\": under \"mindlin\" the stiffness already follows the height");
    s.correlation = GaussianCopula::from_toml(*correlation);
  }
  read_load(root, s);
  read_interaction(root, s);
  read_element(root, s);
  read_mass(root, s);
  read_drive(root, s);
  if (auto onset = root.table("onset")) {
    s.onset = Distribution::from_toml(*onset, base_dir);
    if (!(s.onset->lower() >= 0.0))
      onset->fail("kind", "can draw onsets below 0 s (from " + format_number(s.onset->lower()) +
                              " s): an asperity comes into contact at t >= 0 (truncate with min = 0)");
    if (!std::isfinite(s.onset->upper()) && s.onset->quantile(1.0 - 1e-12) > 1e3)
      onset->fail("kind", "draws onsets beyond 1000 s: give the law in seconds");
  }
  // The evolving contact's laws (docs/model.md §1.4).
  if (auto lifetime = root.table("lifetime")) {
    s.lifetime = Distribution::from_toml(*lifetime, base_dir);
    if (!(s.lifetime->lower() >= 0.0))
      lifetime->fail("kind", "can draw lifetimes below 0 s (from " + format_number(s.lifetime->lower()) +
                                 " s): a contact lasts a time > 0 (truncate with min = 0)");
    if (!std::isfinite(s.lifetime->upper()) && s.lifetime->quantile(1.0 - 1e-12) > 1e3)
      lifetime->fail("kind", "draws lifetimes beyond 1000 s: give the law in seconds");
  }
  if (auto wear = root.table("wear")) {
    s.wear_rate = Distribution::from_toml(*wear, base_dir);
    if (!(s.wear_rate->lower() >= 0.0))
      wear->fail("kind", "can draw wear rates below 0 (from " + format_number(s.wear_rate->lower()) +
                             " per ms): wear only lowers the stiffness (truncate with min = 0)");
    if (!(s.wear_rate->upper() < 1e3))
      wear->fail("kind", "can draw wear rates of 1000 per ms or more (up to " + format_number(s.wear_rate->upper()) +
                             "): give the law in fractions of k per ms, bounded (e.g. kind = \"uniform\", max = 0.3)");
  }
  if (auto steps = root.table("steps")) {
    const double probability = steps->required_number("probability");
    if (!(probability >= 0.0 && probability <= 1.0))
      steps->fail("probability", "= " + format_number(probability) + ": the chance that a summit's stiffness steps, in [0, 1]");
    auto law = [&](std::string_view key) {
      std::optional<TomlTable> table = steps->table(key);
      if (!table) steps->fail(key, "is required: a law table (`kind` and its keys)");
      return std::pair{Distribution::from_toml(*table, base_dir), *table};
    };
    auto [after_onset, after_table] = law("after_onset");
    if (!(after_onset.lower() >= 0.0))
      after_table.fail("kind", "can draw delays below 0 s (from " + format_number(after_onset.lower()) +
                                   " s): a step comes after the onset (truncate with min = 0)");
    auto [factor, factor_table] = law("factor");
    if (!(factor.lower() > 0.0))
      factor_table.fail("kind", "can draw factors down to " + format_number(factor.lower()) +
                                    ": k after / k before must be > 0 (e.g. kind = \"uniform\", min = 0.85, max = 1.15)");
    s.steps = RandomSurface::StepLaws{probability, std::move(after_onset), std::move(factor)};
  }
  return s;
}

}  // namespace stengmc
