#include "surface/population.hpp"

#include <boost/random/poisson_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>
#include <cmath>
#include <tuple>
#include <string>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/random_stream.hpp"
#include "surface/hertz_contact.hpp"

namespace stengmc {

namespace {

std::size_t draw_count(const RandomSurface& s, std::uint64_t seed, std::uint64_t realisation) {
  if (s.count_rule == CountRule::fixed) return s.summit_count;
  RandomEngine engine = random_stream(seed, realisation, StreamKind::count);
  boost::random::poisson_distribution<long long, double> poisson(s.mean_summit_count());
  return static_cast<std::size_t>(poisson(engine));
}

void draw_heights_and_stiffnesses(const RandomSurface& s, std::uint64_t seed, std::uint64_t realisation, Population& p,
                                  std::size_t n) {
  RandomEngine heights = random_stream(seed, realisation, StreamKind::heights);
  RandomEngine stiffnesses = random_stream(seed, realisation, StreamKind::stiffnesses);
  p.height_m.resize(n);
  if (s.correlation) {
    p.sampled_stiffness_n_per_m.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      std::tie(p.height_m[i], p.sampled_stiffness_n_per_m[i]) =
          s.correlation->sample(s.heights, *s.stiffness, heights, stiffnesses);
    return;
  }
  if (s.load_rule == LoadRule::spread) {
    // Greenwood–Williamson: the summits in contact, drawn above the separation, with their
    // loads (one uniform draw each from the heights stream).
    const double mean = s.heights.mean(), std = std::sqrt(s.heights.variance());
    p.load_n.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const LoadedSummit summit = s.load_spread->draw(heights);
      p.height_m[i] = mean + std * summit.height_score;
      p.load_n[i] = summit.load_n;
    }
  } else {
    for (double& z : p.height_m) z = s.heights.sample(heights);
  }
  if (s.stiffness_rule == StiffnessRule::sampled) {
    p.sampled_stiffness_n_per_m.resize(n);
    for (double& k : p.sampled_stiffness_n_per_m) k = s.stiffness->sample(stiffnesses);
  }
}

void draw_positions(const RandomSurface& s, std::uint64_t seed, std::uint64_t realisation, Population& p, std::size_t n) {
  if (s.position_rule == PositionRule::given) {
    p.x_m = s.given_x_m;
    p.y_m = s.given_y_m;
    return;
  }
  RandomEngine engine = random_stream(seed, realisation, StreamKind::positions);
  boost::random::uniform_real_distribution<double> along(0.0, std::sqrt(s.nominal_area_m2));
  p.x_m.resize(n);
  p.y_m.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.x_m[i] = along(engine);
    p.y_m[i] = along(engine);
  }
}

void draw_onsets(const RandomSurface& s, std::uint64_t seed, std::uint64_t realisation, Population& p, std::size_t n) {
  p.onset_s.assign(n, 0.0);
  if (!s.onset) return;
  RandomEngine engine = random_stream(seed, realisation, StreamKind::onsets);
  for (double& t : p.onset_s) t = s.onset->sample(engine);
}

//! One draw per summit from `law` on its own stream, or nothing without a law.
void draw_per_summit(const std::optional<Distribution>& law, StreamKind kind, std::uint64_t seed,
                     std::uint64_t realisation, std::size_t n, std::vector<double>& out) {
  out.clear();
  if (!law) return;
  RandomEngine engine = random_stream(seed, realisation, kind);
  out.resize(n);
  for (double& v : out) v = law->sample(engine);
}

//! Each summit's stiffness step ([steps]): three draws per summit (whether, when, by how
//! much) whatever the outcome, so one summit's draws never move another's.
void draw_steps(const RandomSurface& s, std::uint64_t seed, std::uint64_t realisation, Population& p, std::size_t n) {
  p.step_time_s.clear();
  p.step_factor.clear();
  if (!s.steps) return;
  RandomEngine engine = random_stream(seed, realisation, StreamKind::steps);
  boost::random::uniform_real_distribution<double> unit(0.0, 1.0);
  p.step_time_s.resize(n);
  p.step_factor.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool stepped = unit(engine) < s.steps->probability;
    p.step_time_s[i] = p.onset_s[i] + s.steps->after_onset_s.sample(engine);
    const double factor = s.steps->factor.sample(engine);
    p.step_factor[i] = stepped ? factor : 1.0;
  }
}

void draw_phases(const RandomSurface& s, std::uint64_t seed, std::uint64_t realisation, Population& p, std::size_t n) {
  p.drive_phase_rad.assign(n, s.phase_rad);
  if (s.phase_rule != PhaseRule::uniform) return;
  RandomEngine engine = random_stream(seed, realisation, StreamKind::phases);
  boost::random::uniform_real_distribution<double> phase(0.0, 2.0 * PI);
  for (double& phi : p.drive_phase_rad) phi = phase(engine);
}

//! Hertz contact under a fixed load N per summit: a = (3 N R_s / 4 E*)^(1/3), delta = a^2 / R_s.
HertzContact fixed_load_contact(std::size_t n, double load_n, double summit_radius_m, double e_star) {
  HertzContact c;
  const double a = std::cbrt(3.0 * load_n * summit_radius_m / (4.0 * e_star));
  c.load_n.assign(n, load_n);
  c.patch_radius_m.assign(n, a);
  c.interference_m.assign(n, a * a / summit_radius_m);
  c.total_load_n = load_n * static_cast<double>(n);
  c.real_area_m2 = PI * a * a * static_cast<double>(n);
  c.contact_count = n;
  return c;
}

//! Hertz contact of each summit under its own drawn load: a_i = (3 N_i R_s / 4 E*)^(1/3).
HertzContact drawn_load_contact(const std::vector<double>& loads_n, double summit_radius_m, double e_star) {
  HertzContact c;
  for (double load : loads_n) {
    const double a = std::cbrt(3.0 * load * summit_radius_m / (4.0 * e_star));
    c.load_n.push_back(load);
    c.patch_radius_m.push_back(a);
    c.interference_m.push_back(a * a / summit_radius_m);
    c.total_load_n += load;
    c.real_area_m2 += PI * a * a;
  }
  c.contact_count = loads_n.size();
  return c;
}

void solve_contact(const RandomSurface& s, Population& p) {
  const std::size_t n = p.height_m.size();
  if (!s.materials) {  // a fixed load (the paper) or a drawn spread, nothing known about the patches
    if (s.load_rule != LoadRule::spread) p.load_n.assign(n, s.normal_load_n);
    return;
  }
  const ContactMaterials& m = *s.materials;
  const double e_star = m.effective_modulus_pa();
  PopulationContact c;
  c.summit_radius_m = m.summit_radius_m;
  HertzContact hertz;
  bool have_interaction = false;
  if (s.load_rule == LoadRule::fixed) {
    hertz = fixed_load_contact(n, s.normal_load_n, m.summit_radius_m, e_star);
  } else if (s.load_rule == LoadRule::spread) {
    hertz = drawn_load_contact(p.load_n, m.summit_radius_m, e_star);
    const double std = std::sqrt(s.heights.variance());
    // cv = 0 has no separation (every summit pressed alike): 0, as under a fixed load.
    const double separation = s.load_spread->separation();
    hertz.separation_m = std::isfinite(separation) ? s.heights.mean() + std * separation : 0.0;
  } else if (n == 0) {
    c.hertz_load = true;
    c.load_carried = false;
    p.contact = std::move(c);
    return;
  } else if (s.interaction_mode == InteractionMode::apply) {
    InteractingContact solved = solve_interacting_contact(p.height_m, p.x_m, p.y_m, m.summit_radius_m, e_star,
                                                          s.nominal_load_n, s.nominal_area_m2, s.interaction);
    hertz = std::move(solved.contact);
    c.interaction = std::move(solved.interaction);
    c.interacting_iterations = solved.iterations;
    c.interacting_converged = solved.converged;
    have_interaction = true;
  } else {
    hertz = solve_hertz_contact(p.height_m, m.summit_radius_m, e_star, s.nominal_load_n);
  }
  if (!have_interaction && hertz.contact_count > 0)
    c.interaction = spot_interaction(p.x_m, p.y_m, hertz.load_n, hertz.patch_radius_m, hertz.interference_m, e_star,
                                     s.nominal_area_m2, s.interaction);
  c.hertz_load = s.load_rule == LoadRule::hertz;
  c.separation_m = hertz.separation_m;
  c.interference_m = std::move(hertz.interference_m);
  c.patch_radius_m = std::move(hertz.patch_radius_m);
  c.total_load_n = hertz.total_load_n;
  c.real_area_m2 = hertz.real_area_m2;
  c.contact_density = hertz.real_area_m2 / s.nominal_area_m2;
  c.screening_estimate = screening_interaction_estimate(c.contact_density);
  p.load_n = std::move(hertz.load_n);
  p.contact = std::move(c);
}

Asperity make_asperity(const RandomSurface& s, const Population& p, std::size_t i) {
  Asperity a;
  a.normal_load_n = p.load_n[i];
  a.height_m = p.height_m[i];
  a.drive_phase_rad = p.drive_phase_rad[i];
  a.onset_s = p.onset_s[i];
  if (!p.lifetime_s.empty()) {
    a.release_s = a.onset_s + p.lifetime_s[i];
    // A lifetime of 0 (a law reaching down to 0, drawn at exactly 0) is no contact at all.
    if (!(a.release_s > a.onset_s))
      throw ModelError("realisation " + std::to_string(p.realisation) + ", summit " + std::to_string(i + 1) +
                       ": contact lifetime " + format_number(p.lifetime_s[i]) + " s leaves no time in contact");
  }
  if (!p.wear_rate_per_ms.empty()) a.wear_rate_per_ms = p.wear_rate_per_ms[i];
  // A step drawn after the release is dropped: the interface changes only in contact.
  if (!p.step_factor.empty() && p.step_factor[i] != 1.0 && p.step_time_s[i] < a.release_s)
    a.stiffness_steps.push_back({p.step_time_s[i], p.step_factor[i]});
  a.element = s.element;
  const double patch = p.contact ? p.contact->patch_radius_m[i] : 0.0;
  if (s.geometry_rule == GeometryRule::patch) a.element.length_m = a.element.width_m = std::sqrt(PI) * patch;
  a.stiffness_n_per_m = s.stiffness_rule == StiffnessRule::sampled
                            ? p.sampled_stiffness_n_per_m[i]
                            : mindlin_stiffness(s.materials->effective_shear_modulus_pa(), patch);
  a.mass_kg = s.mass_rule == MassRule::fixed ? s.mass_kg
                                              : s.density_kg_per_m3 * a.element.length_m * a.element.width_m * a.height_m;
  if (!(a.stiffness_n_per_m > 0.0) || !(a.mass_kg > 0.0) || !(a.element.length_m > 0.0))
    throw ModelError("realisation " + std::to_string(p.realisation) + ", summit " + std::to_string(i + 1) +
                     ": in contact but k = " + format_number(a.stiffness_n_per_m) + " N/m, m = " + format_number(a.mass_kg) +
                     " kg, l = " + format_number(a.element.length_m) + " m (each must be > 0)");
  return a;
}

}  // namespace

Population sample_population(const RandomSurface& surface, std::uint64_t seed, std::uint64_t realisation) {
  Population p;
  p.realisation = realisation;
  const std::size_t n = draw_count(surface, seed, realisation);
  draw_heights_and_stiffnesses(surface, seed, realisation, p, n);
  draw_positions(surface, seed, realisation, p, n);
  draw_phases(surface, seed, realisation, p, n);
  draw_onsets(surface, seed, realisation, p, n);
  draw_per_summit(surface.lifetime, StreamKind::lifetimes, seed, realisation, n, p.lifetime_s);
  draw_per_summit(surface.wear_rate, StreamKind::wear, seed, realisation, n, p.wear_rate_per_ms);
  draw_steps(surface, seed, realisation, p, n);
  solve_contact(surface, p);
  for (std::size_t i = 0; i < n; ++i) {
    if (!(p.load_n[i] > 0.0)) continue;
    p.asperities.push_back(make_asperity(surface, p, i));
    p.summit_of_asperity.push_back(i);
  }
  return p;
}

}  // namespace stengmc
