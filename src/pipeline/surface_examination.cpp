#include "pipeline/surface_examination.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/constants.hpp"
#include "surface/hertz_contact.hpp"

namespace stengmc {

namespace {

constexpr std::size_t TARGET_POINTS = 400;
constexpr std::size_t CURVE_POINTS = 200;

std::optional<LoadSeparationCurve> load_separation_curve(const RandomSurface& s, const Population& p) {
  if (s.load_rule != LoadRule::hertz || !p.contact || p.height_m.empty()) return std::nullopt;
  LoadSeparationCurve c;
  c.realisation = p.realisation;
  c.solved_separation_m = p.contact->separation_m;
  c.nominal_load_n = s.nominal_load_n;
  // In interacting mode the flat meets the summits lowered by the interaction of the
  // solved loads: that curve passes through the solved point, the independent one would not.
  std::vector<double> heights = p.height_m;
  if (s.interaction_mode == InteractionMode::apply)
    for (std::size_t i = 0; i < heights.size(); ++i) heights[i] -= p.contact->interaction.extra_displacement_m[i];
  const double top = *std::max_element(heights.begin(), heights.end());
  // From first touch down to half as far again below the solved separation.
  const double bottom = c.solved_separation_m - 0.5 * (top - c.solved_separation_m);
  const double e_star = s.materials->effective_modulus_pa();
  for (std::size_t i = 0; i < CURVE_POINTS; ++i) {
    const double d = top - (top - bottom) * static_cast<double>(i) / static_cast<double>(CURVE_POINTS - 1);
    c.separation_m.push_back(d);
    c.total_load_n.push_back(hertz_contact_at_separation(heights, s.materials->summit_radius_m, e_star, d).total_load_n);
  }
  return c;
}

//! Mean, standard deviation, minimum and maximum of one number over the realisations.
struct Spread {
  double mean = 0.0, std = 0.0, min = 0.0, max = 0.0;
};

Spread spread(const std::vector<double>& v) {
  Spread s;
  if (v.empty()) return s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  if (v.size() > 1) {
    for (double x : v) s.std += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(s.std / static_cast<double>(v.size() - 1));
  }
  return s;
}

//! Empirical quantile (linear interpolation between order statistics, Hyndman & Fan type 7).
double quantile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double h = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

std::vector<double> over_realisations(const SurfaceExamination& e,
                                      const std::function<double(const Population&, const ValidityReport&)>& f) {
  std::vector<double> out;
  for (std::size_t j = 0; j < e.populations.size(); ++j) out.push_back(f(e.populations[j], e.reports[j]));
  return out;
}

std::vector<double> pooled(const SurfaceExamination& e, const std::function<double(const Asperity&)>& f) {
  std::vector<double> out;
  for (const Population& p : e.populations)
    for (const Asperity& a : p.asperities) out.push_back(f(a));
  return out;
}

}  // namespace

TargetLaw target_law(const Distribution& law) {
  TargetLaw t;
  if (law.kind() == Distribution::Kind::fixed) {
    t.discrete = true;
    const auto& values = law.fixed_values();
    const double each = 1.0 / static_cast<double>(values.size());
    for (double v : values) {
      if (!t.value.empty() && t.value.back() == v) {
        t.density.back() += each;
      } else {
        t.value.push_back(v);
        t.density.push_back(each);
      }
    }
    return t;
  }
  const double lo = std::max(law.lower(), law.quantile(1e-4));
  const double hi = std::min(law.upper(), law.quantile(1.0 - 1e-4));
  for (std::size_t i = 0; i < TARGET_POINTS; ++i) {
    // Weighted where hi - lo overflows (a law as wide as a double), as before elsewhere.
    const double u = static_cast<double>(i) / static_cast<double>(TARGET_POINTS - 1);
    const double x = std::isfinite(hi - lo)
                         ? lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(TARGET_POINTS - 1)
                         : (1.0 - u) * lo + u * hi;
    const double density = law.pdf(x);
    // A law too narrow or too wide for its density to be a double (std = 1e-300 squares to
    // 0) has no curve to draw there; the figure shows what is left, the samples are exact.
    if (!std::isfinite(x) || !std::isfinite(density)) continue;
    t.value.push_back(x);
    t.density.push_back(density);
  }
  return t;
}

SurfaceExamination examine_surface(const Surface& surface, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                                   const Model1Params& model1, const Model2Params& model2, Progress* progress,
                                   ModelScope scope) {
  SurfaceExamination e;
  e.seed = seed;
  for (std::uint64_t r = first; r < first + count; ++r) {
    e.populations.push_back(surface.sample(seed, r));
    e.reports.push_back(assess_validity(e.populations.back(), model1, model2, e.thresholds, scope));
    if (progress) progress->advance();
  }
  e.random_surface = surface.random_surface();
  if (const RandomSurface* s = surface.random_surface()) {
    e.heights_target = target_law(s->heights);
    if (s->stiffness) e.stiffness_target = target_law(*s->stiffness);
    if (!e.populations.empty()) e.load_separation = load_separation_curve(*s, e.populations.front());
  }
  return e;
}

std::string format_surface_summary(const SurfaceExamination& e) {
  std::string out;
  char line[256];
  const std::size_t k = e.populations.size();
  std::snprintf(line, sizeof line, "%zu realisation%s (seed %llu); over the realisations:\n", k, k == 1 ? "" : "s",
                static_cast<unsigned long long>(e.seed));
  out += line;
  std::snprintf(line, sizeof line, "  %-34s %11s %11s %11s %11s\n", "quantity", "mean", "std", "min", "max");
  out += line;
  auto row = [&](const char* name, const std::vector<double>& v) {
    const Spread s = spread(v);
    std::snprintf(line, sizeof line, "  %-34s %11.4g %11.4g %11.4g %11.4g\n", name, s.mean, s.std, s.min, s.max);
    out += line;
  };
  row("summits drawn", over_realisations(e, [](const Population& p, const ValidityReport&) { return double(p.height_m.size()); }));
  row("asperities in contact", over_realisations(e, [](const Population& p, const ValidityReport&) { return double(p.asperities.size()); }));
  row("total load [N]", over_realisations(e, [](const Population& p, const ValidityReport&) {
        double w = 0.0;
        for (const Asperity& a : p.asperities) w += a.normal_load_n;
        return w;
      }));
  const bool contact = k > 0 && e.reports.front().contact_known;
  if (contact) {
    if (e.populations.front().contact->hertz_load)
      row("separation d [m]", over_realisations(e, [](const Population& p, const ValidityReport&) { return p.contact->separation_m; }));
    row("contact density A_r/A0 [-]", over_realisations(e, [](const Population&, const ValidityReport& r) { return r.contact_density; }));
    row("interaction: load moved [-]",
        over_realisations(e, [](const Population&, const ValidityReport& r) { return r.load_redistribution; }));
    row("screening estimate [-]", over_realisations(e, [](const Population&, const ValidityReport& r) { return r.screening_estimate; }));
  }
  row("cannot slip, Model 1 (count)", over_realisations(e, [](const Population&, const ValidityReport& r) { return double(r.cannot_slip_count); }));
  row("near l, Model 2 (count)", over_realisations(e, [](const Population&, const ValidityReport& r) { return double(r.near_length_count); }));

  std::snprintf(line, sizeof line, "pooled over all asperities in contact:\n  %-34s %11s %11s %11s %11s\n", "quantity", "5 %",
                "median", "95 %", "max");
  out += line;
  auto quantiles = [&](const char* name, const std::vector<double>& v) {
    if (v.empty()) {
      std::snprintf(line, sizeof line, "  %-34s %11s %11s %11s %11s\n", name, "-", "-", "-", "-");
      out += line;
      return;
    }
    std::snprintf(line, sizeof line, "  %-34s %11.4g %11.4g %11.4g %11.4g\n", name, quantile(v, 0.05), quantile(v, 0.5),
                  quantile(v, 0.95), quantile(v, 1.0));
    out += line;
  };
  quantiles("stiffness k [N/m]", pooled(e, [](const Asperity& a) { return a.stiffness_n_per_m; }));
  quantiles("normal load N [N]", pooled(e, [](const Asperity& a) { return a.normal_load_n; }));
  quantiles("natural frequency [Hz]",
            pooled(e, [](const Asperity& a) { return std::sqrt(a.stiffness_n_per_m / a.mass_kg) / (2.0 * PI); }));

  // How many realisations fail each check, and the first failing one's words.
  struct Check {
    const char* name;
    std::function<bool(const ValidityReport&)> failed;
    std::function<const std::vector<std::string>&(const ValidityReport&)> words;
  };
  const auto contact_words = [](const ValidityReport& r) -> const std::vector<std::string>& { return r.contact_warnings; };
  const Check checks[] = {
      {"no summits to carry W", [](const ValidityReport& r) { return !r.load_carried; }, contact_words},
      {"spots not independent", [](const ValidityReport& r) { return !r.independence_holds; }, contact_words},
      {"interacting mode not converged", [](const ValidityReport& r) { return !r.interacting_converged; }, contact_words},
      {"overlapping patches", [](const ValidityReport& r) { return r.overlapping_pairs > 0; }, contact_words},
      {"patches beyond Hertz's range", [](const ValidityReport& r) { return r.beyond_hertz; }, contact_words},
      {"Model 1: asperities that cannot slip", [](const ValidityReport& r) { return r.cannot_slip_count > 0; },
       [](const ValidityReport& r) -> const std::vector<std::string>& { return r.model1_warnings; }},
      {"Model 2: asperities near l", [](const ValidityReport& r) { return r.near_length_count > 0; },
       [](const ValidityReport& r) -> const std::vector<std::string>& { return r.model2_warnings; }},
  };
  bool any = false;
  for (const Check& check : checks) {
    std::size_t failed = 0;
    const ValidityReport* first = nullptr;
    for (const ValidityReport& r : e.reports)
      if (check.failed(r)) {
        ++failed;
        if (!first) first = &r;
      }
    if (failed == 0) continue;
    if (!any) out += "validity (realisations failing each check):\n";
    any = true;
    std::snprintf(line, sizeof line, "  %-38s %zu of %zu\n", check.name, failed, k);
    out += line;
  }
  if (!any) {
    out += "validity: every check passed\n";
    return out;
  }
  out += "the first failing realisation's words:\n";
  for (const ValidityReport& r : e.reports) {
    if (r.contact_warnings.empty() && r.model1_warnings.empty() && r.model2_warnings.empty()) continue;
    for (const auto* list : {&r.contact_warnings, &r.model1_warnings, &r.model2_warnings})
      for (const std::string& w : *list) out += "  WARNING: " + w + "\n";
    break;
  }
  return out;
}

}  // namespace stengmc
