#include "pipeline/study_realisation.hpp"

#include <cmath>
#include <string>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "tribology/evolving_contact.hpp"

namespace stengmc {

namespace {

//! Draws the study's realisation into `population` and `asperities`. Everything that can
//! go wrong here belongs to the realisation, not to the file: a ModelError naming both,
//! which an ensemble counts as an invalid realisation.
void draw_population(Study& study) {
  study.population = study.surface->sample(study.seed, study.realisation);
  study.asperities = study.population.asperities;
  const std::string which = study.file + ": realisation " + std::to_string(study.realisation);
  const std::string seed = "seed " + std::to_string(study.seed);
  const auto& contact = study.population.contact;
  if (contact && !contact->load_carried)
    throw ModelError(which + " drew no summits (" + seed + "): no separation can carry the nominal load W; nothing to simulate");
  // A fixed count of 0 summits asks for a record with nothing sliding (the measurement
  // chain alone); any other empty population is a realisation with nothing to simulate.
  const RandomSurface* random = study.surface->random_surface();
  const bool none_asked = random && random->count_rule == CountRule::fixed && random->summit_count == 0;
  if (study.asperities.empty() && !none_asked)
    throw ModelError(which + " has no asperity in contact (" + std::to_string(study.population.height_m.size()) +
                     " summits drawn, " + seed + "): nothing to simulate");
}

}  // namespace

void check_sample_rate(const Study& study, TomlTable* root) {
  double highest_hz = 0.0;
  std::size_t which = 0;
  for (std::size_t i = 0; i < study.asperities.size(); ++i) {
    const Asperity& a = study.asperities[i];
    // Its highest line: a stiffness step may raise k above k0 (docs/model.md §1.4).
    const double f = std::sqrt(largest_stiffness_n_per_m(a) / a.mass_kg) / (2.0 * PI);
    if (f > highest_hz) {
      highest_hz = f;
      which = i;
    }
  }
  if (study.sample_rate_hz >= 2.0 * highest_hz) return;
  const std::string what = "= " + format_number(study.sample_rate_hz) + " Hz is below twice the highest natural frequency (" +
                           format_number(highest_hz) + " Hz, asperity " + std::to_string(which + 1) +
                           "): use at least " + format_number(2.0 * highest_hz) + " Hz";
  if (study.surface->random_surface())
    throw ModelError(study.file + ": realisation " + std::to_string(study.realisation) + ": sample_rate_hz " + what);
  if (root) root->fail("sample_rate_hz", what);
  throw InputError(study.file + ": sample_rate_hz " + what);
}

void draw_realisation(Study& study, std::uint64_t realisation, TomlTable* root) {
  study.realisation = realisation;
  draw_population(study);
  check_sample_rate(study, root);
}

Study study_for_realisation(const Study& base, std::uint64_t realisation) {
  Study study = base;
  draw_realisation(study, realisation, nullptr);
  return study;
}

}  // namespace stengmc
