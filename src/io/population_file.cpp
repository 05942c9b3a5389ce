#include "io/population_file.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <numeric>
#include <vector>

#include "core/error.hpp"

namespace stengmc {

namespace {

std::string prefix_of(const std::string& group) { return group == "/" ? "" : group; }

//! One value per realisation.
template <typename T, typename Field>
std::vector<T> per_realisation(std::span<const Population> pops, std::span<const ValidityReport> reports, Field field) {
  std::vector<T> out;
  out.reserve(pops.size());
  for (std::size_t j = 0; j < pops.size(); ++j) out.push_back(static_cast<T>(field(pops[j], reports[j])));
  return out;
}

//! Concatenation of a per-summit array over realisations (zeros where a realisation lacks it).
std::vector<double> concatenated(std::span<const Population> pops,
                                 const std::function<const std::vector<double>*(const Population&)>& array) {
  std::vector<double> out;
  for (const Population& p : pops) {
    const std::vector<double>* values = array(p);
    if (values && values->size() == p.height_m.size()) out.insert(out.end(), values->begin(), values->end());
    else out.insert(out.end(), p.height_m.size(), 0.0);
  }
  return out;
}

//! 0 .. count-1: the rows of a flat array.
std::vector<std::int64_t> indices(std::int64_t count) {
  std::vector<std::int64_t> out(static_cast<std::size_t>(count));
  std::iota(out.begin(), out.end(), std::int64_t{0});
  return out;
}

std::vector<double> asperity_column(std::span<const Population> pops, const std::function<double(const Asperity&)>& field) {
  std::vector<double> out;
  for (const Population& p : pops)
    for (const Asperity& a : p.asperities) out.push_back(field(a));
  return out;
}

void write_realisations(Hdf5Writer& f, const std::string& g, std::span<const Population> pops,
                        std::span<const ValidityReport> reports, bool contact) {
  using P = const Population&;
  using R = const ValidityReport&;
  f.write(g + "/realisations/realisation", per_realisation<std::int64_t>(pops, reports, [](P p, R) { return p.realisation; }));
  f.write(g + "/realisations/summit_count", per_realisation<std::int64_t>(pops, reports, [](P p, R) { return p.height_m.size(); }));
  f.write(g + "/realisations/asperity_count", per_realisation<std::int64_t>(pops, reports, [](P p, R) { return p.asperities.size(); }));
  f.write(g + "/realisations/cannot_slip_model1_count",
          per_realisation<std::int64_t>(pops, reports, [](P, R r) { return r.cannot_slip_count; }));
  f.write(g + "/realisations/near_length_model2_count",
          per_realisation<std::int64_t>(pops, reports, [](P, R r) { return r.near_length_count; }));
  std::vector<std::string> warnings;
  for (const ValidityReport& r : reports) warnings.push_back(joined_warnings(r));
  f.write(g + "/realisations/warnings", warnings);
  std::vector<std::int64_t> summit_offset{0}, asperity_offset{0};
  for (const Population& p : pops) {
    summit_offset.push_back(summit_offset.back() + static_cast<std::int64_t>(p.height_m.size()));
    asperity_offset.push_back(asperity_offset.back() + static_cast<std::int64_t>(p.asperities.size()));
  }
  f.write(g + "/realisations/summit_offset", summit_offset);
  f.write(g + "/realisations/asperity_offset", asperity_offset);
  // CF contiguous ragged arrays (CF 1.10, 9.3.3): each count names the dimension it splits,
  // whose coordinate sits in G so that /realisations, /summits and /asperities all see it.
  f.attribute(g + "/realisations/summit_count", "sample_dimension", "summit");
  f.attribute(g + "/realisations/asperity_count", "sample_dimension", "asperity");
  f.write(g + "/summit", indices(summit_offset.back()));
  f.write(g + "/asperity", indices(asperity_offset.back()));
  if (!contact) return;
  auto c = [](P p) -> const PopulationContact& { return *p.contact; };
  f.write(g + "/realisations/separation_m", per_realisation<double>(pops, reports, [&](P p, R) { return c(p).separation_m; }));
  f.write(g + "/realisations/total_load_n", per_realisation<double>(pops, reports, [&](P p, R) { return c(p).total_load_n; }));
  f.write(g + "/realisations/real_area_m2", per_realisation<double>(pops, reports, [&](P p, R) { return c(p).real_area_m2; }));
  f.write(g + "/realisations/contact_density", per_realisation<double>(pops, reports, [](P, R r) { return r.contact_density; }));
  f.write(g + "/realisations/screening_estimate", per_realisation<double>(pops, reports, [](P, R r) { return r.screening_estimate; }));
  f.write(g + "/realisations/load_redistribution", per_realisation<double>(pops, reports, [](P, R r) { return r.load_redistribution; }));
  f.write(g + "/realisations/interaction_rms_relative",
          per_realisation<double>(pops, reports, [&](P p, R) { return c(p).interaction.rms_relative; }));
  f.write(g + "/realisations/interaction_max_relative",
          per_realisation<double>(pops, reports, [](P, R r) { return r.interaction_max_relative; }));
  f.write(g + "/realisations/overlapping_pairs", per_realisation<std::int64_t>(pops, reports, [](P, R r) { return r.overlapping_pairs; }));
  f.write(g + "/realisations/independence_holds", per_realisation<std::int64_t>(pops, reports, [](P, R r) { return r.independence_holds; }));
  f.write(g + "/realisations/interacting_iterations",
          per_realisation<std::int64_t>(pops, reports, [&](P p, R) { return c(p).interacting_iterations; }));
  f.write(g + "/realisations/interacting_converged",
          per_realisation<std::int64_t>(pops, reports, [&](P p, R) { return c(p).interacting_converged; }));
  f.write(g + "/realisations/load_carried",
          per_realisation<std::int64_t>(pops, reports, [&](P p, R) { return c(p).load_carried; }));
  f.write(g + "/realisations/localisation_radius_m",
          per_realisation<double>(pops, reports, [&](P p, R) { return c(p).interaction.localisation_radius_m; }));
  f.write(g + "/realisations/far_field_m",
          per_realisation<double>(pops, reports, [&](P p, R) { return c(p).interaction.far_field_m; }));
}

void write_summits(Hdf5Writer& f, const std::string& g, std::span<const Population> pops, bool contact, bool sampled) {
  f.write(g + "/summits/height_m", concatenated(pops, [](const Population& p) { return &p.height_m; }));
  f.write(g + "/summits/x_m", concatenated(pops, [](const Population& p) { return &p.x_m; }));
  f.write(g + "/summits/y_m", concatenated(pops, [](const Population& p) { return &p.y_m; }));
  f.write(g + "/summits/drive_phase_rad", concatenated(pops, [](const Population& p) { return &p.drive_phase_rad; }));
  f.write(g + "/summits/normal_load_n", concatenated(pops, [](const Population& p) { return &p.load_n; }));
  // Only where a surface draws onsets ([onset]): other files stay as they were.
  const auto has_onset = [](const Population& p) {
    return std::any_of(p.onset_s.begin(), p.onset_s.end(), [](double t) { return t != 0.0; });
  };
  if (std::any_of(pops.begin(), pops.end(), has_onset))
    f.write(g + "/summits/onset_s", concatenated(pops, [](const Population& p) { return &p.onset_s; }));
  // Likewise the evolving contact's draws ([lifetime], [wear]).
  if (!pops.empty() && !pops.front().lifetime_s.empty())
    f.write(g + "/summits/lifetime_s", concatenated(pops, [](const Population& p) { return &p.lifetime_s; }));
  if (!pops.empty() && !pops.front().wear_rate_per_ms.empty())
    f.write(g + "/summits/wear_rate_per_ms", concatenated(pops, [](const Population& p) { return &p.wear_rate_per_ms; }));
  if (!pops.empty() && !pops.front().step_factor.empty()) {
    f.write(g + "/summits/step_time_s", concatenated(pops, [](const Population& p) { return &p.step_time_s; }));
    f.write(g + "/summits/step_factor", concatenated(pops, [](const Population& p) { return &p.step_factor; }));
  }
  if (sampled)
    f.write(g + "/summits/sampled_stiffness_n_per_m",
            concatenated(pops, [](const Population& p) { return &p.sampled_stiffness_n_per_m; }));
  if (!contact) return;
  f.write(g + "/summits/interference_m", concatenated(pops, [](const Population& p) { return &p.contact->interference_m; }));
  f.write(g + "/summits/patch_radius_m", concatenated(pops, [](const Population& p) { return &p.contact->patch_radius_m; }));
  f.write(g + "/summits/extra_displacement_m",
          concatenated(pops, [](const Population& p) { return &p.contact->interaction.extra_displacement_m; }));
  f.write(g + "/summits/interaction_relative",
          concatenated(pops, [](const Population& p) { return &p.contact->interaction.relative; }));
}

void write_asperities(Hdf5Writer& f, const std::string& g, std::span<const Population> pops,
                      std::span<const ValidityReport> reports) {
  std::vector<std::int64_t> summit_index, cannot_slip, near_length;
  std::vector<double> deflection;
  for (std::size_t j = 0; j < pops.size(); ++j) {
    for (std::size_t i = 0; i < pops[j].asperities.size(); ++i) {
      summit_index.push_back(i < pops[j].summit_of_asperity.size() ? static_cast<std::int64_t>(pops[j].summit_of_asperity[i])
                                                                   : std::int64_t{-1});
      cannot_slip.push_back(reports[j].cannot_slip_model1[i]);
      near_length.push_back(reports[j].near_length_model2[i]);
      deflection.push_back(reports[j].static_deflection_over_length[i]);
    }
  }
  f.write(g + "/asperities/summit_index", summit_index);
  f.write(g + "/asperities/stiffness_n_per_m", asperity_column(pops, [](const Asperity& a) { return a.stiffness_n_per_m; }));
  f.write(g + "/asperities/mass_kg", asperity_column(pops, [](const Asperity& a) { return a.mass_kg; }));
  f.write(g + "/asperities/normal_load_n", asperity_column(pops, [](const Asperity& a) { return a.normal_load_n; }));
  f.write(g + "/asperities/height_m", asperity_column(pops, [](const Asperity& a) { return a.height_m; }));
  f.write(g + "/asperities/element_length_m", asperity_column(pops, [](const Asperity& a) { return a.element.length_m; }));
  f.write(g + "/asperities/element_width_m", asperity_column(pops, [](const Asperity& a) { return a.element.width_m; }));
  f.write(g + "/asperities/drive_phase_rad", asperity_column(pops, [](const Asperity& a) { return a.drive_phase_rad; }));
  if (std::any_of(pops.begin(), pops.end(), [](const Population& p) {
        return std::any_of(p.asperities.begin(), p.asperities.end(), [](const Asperity& a) { return a.onset_s != 0.0; });
      }))
    f.write(g + "/asperities/onset_s", asperity_column(pops, [](const Asperity& a) { return a.onset_s; }));
  f.write(g + "/asperities/cannot_slip_model1", cannot_slip);
  f.write(g + "/asperities/static_deflection_over_length", deflection);
  f.write(g + "/asperities/near_length_model2", near_length);
}

}  // namespace

std::string joined_warnings(const ValidityReport& report) {
  std::string out;
  for (const auto* list : {&report.contact_warnings, &report.model1_warnings, &report.model2_warnings})
    for (const std::string& w : *list) out += (out.empty() ? "" : "; ") + w;
  return out;
}

void write_populations(Hdf5Writer& file, const std::string& group, const RandomSurface* surface,
                       std::span<const Population> populations, std::span<const ValidityReport> reports) {
  if (populations.size() != reports.size())
    throw Error("write_populations: " + std::to_string(populations.size()) + " populations but " +
                std::to_string(reports.size()) + " reports");
  const std::string g = prefix_of(group);
  const bool contact = surface && surface->materials.has_value();
  const bool sampled = surface && surface->stiffness_rule == StiffnessRule::sampled;
  write_realisations(file, g, populations, reports, contact);
  if (contact)
    file.attribute(g.empty() ? "/realisations" : g + "/realisations", "kernel",
                   surface->interaction.kernel == InteractionKernel::point_load ? "point_load" : "hertz_pressure");
  write_summits(file, g, populations, contact, sampled);
  write_asperities(file, g, populations, reports);
}

}  // namespace stengmc
