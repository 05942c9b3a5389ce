#include "tribology/friction_law.hpp"

namespace stengmc {

// The registration: one line per law, each defined in its own file.
FrictionLaw consistent_friction_law();
FrictionLaw literal_friction_law();

const std::vector<FrictionLaw>& friction_laws() {
  static const std::vector<FrictionLaw> laws{consistent_friction_law(), literal_friction_law()};
  return laws;
}

const FrictionLaw* find_friction_law(std::string_view name) {
  for (const FrictionLaw& law : friction_laws())
    if (law.name == name) return &law;
  return nullptr;
}

const FrictionLaw& default_friction_law() { return friction_laws().front(); }

std::vector<std::string_view> friction_law_names() {
  std::vector<std::string_view> names;
  for (const FrictionLaw& law : friction_laws()) names.push_back(law.name);
  return names;
}

}  // namespace stengmc
