#include "surface/surface.hpp"

#include "surface/fixed_population.hpp"

#include <new>
#include <stdexcept>

#include "core/error.hpp"

namespace stengmc {

Surface Surface::from_toml(TomlTable& table, const std::filesystem::path& base_dir) {
  const std::string kind = table.choice("kind", "list", {"list", "random"});
  if (kind == "list") return fixed_list(read_fixed_population(table));
  return random(read_random_surface(table, base_dir));
}

Surface Surface::fixed_list(std::vector<Asperity> asperities) {
  Surface s;
  s.list_ = std::move(asperities);
  return s;
}

Surface Surface::random(RandomSurface surface) {
  Surface s;
  s.random_ = std::move(surface);
  return s;
}

std::string Surface::auxiliary_inputs() const {
  if (!random_) return "";
  std::string out = random_->heights.source();
  if (random_->stiffness) out += random_->stiffness->source();
  return out;
}

std::vector<std::string> Surface::auxiliary_input_files() const {
  std::vector<std::string> files;
  if (!random_) return files;
  for (const Distribution* law : {&random_->heights, random_->stiffness ? &*random_->stiffness : nullptr})
    if (law && !law->source().empty()) files.push_back(law->source().substr(0, law->source().find('\n')));
  return files;
}

Population Surface::sample(std::uint64_t seed, std::uint64_t realisation) const {
  if (random_) {
    try {
      return sample_population(*random_, seed, realisation);
    } catch (const Error&) {
      throw;
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      // A numerical library's own exception (Boost's root finders, a distribution's domain
      // check) belongs to this realisation: a ModelError, which an ensemble records as an
      // invalid realisation with the reason instead of stopping.
      throw ModelError("realisation " + std::to_string(realisation) + " (seed " + std::to_string(seed) +
                       ") could not be sampled: " + e.what());
    }
  }
  Population p;
  p.realisation = realisation;
  p.asperities = list_;
  return p;
}

}  // namespace stengmc
