#include "io/surface_file.hpp"

#include "io/population_file.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc {

namespace {

void write_target(Hdf5Writer& file, const std::string& group, const TargetLaw& law) {
  file.write(group + "/value", law.value);
  // A discrete law's "density" is a probability per value.
  if (law.discrete) file.write_with_units(group + "/density", law.density, "1");
  else file.write(group + "/density", law.density);
  file.attribute(group, "discrete", static_cast<std::int64_t>(law.discrete ? 1 : 0));
}

}  // namespace

void write_surface_file(const std::string& path, const Provenance& provenance, const SurfaceExamination& e) {
  Hdf5Writer file(path, describe_output);
  write_provenance(file, provenance);
  file.attribute("/", "first_realisation",
                 static_cast<std::int64_t>(e.populations.empty() ? 0 : e.populations.front().realisation));
  file.attribute("/", "realisation_count", static_cast<std::int64_t>(e.populations.size()));
  const ValidityThresholds& thresholds = e.thresholds;
  file.attribute("/", "load_redistribution_threshold", thresholds.load_redistribution);
  file.attribute("/", "near_length_fraction", thresholds.near_length_fraction);
  file.attribute("/", "patch_over_radius_threshold", thresholds.patch_over_radius);
  write_populations(file, "/", e.random_surface, e.populations, e.reports);
  if (e.heights_target) write_target(file, "/target/heights", *e.heights_target);
  if (e.stiffness_target) write_target(file, "/target/stiffness", *e.stiffness_target);
  if (const auto& c = e.load_separation) {
    file.write("/load_separation/separation_m", c->separation_m);
    file.write("/load_separation/total_load_n", c->total_load_n);
    file.attribute("/load_separation", "realisation", static_cast<std::int64_t>(c->realisation));
    file.attribute("/load_separation", "solved_separation_m", c->solved_separation_m);
    file.attribute("/load_separation", "nominal_load_n", c->nominal_load_n);
  }
  file.commit();
}

}  // namespace stengmc
