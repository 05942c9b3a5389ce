#include "surface/continuous_law.hpp"

namespace stengmc {

// The registration: one line per family, each defined in its own file.
ContinuousFamily normal_family();
ContinuousFamily lognormal_family();
ContinuousFamily gamma_family();
ContinuousFamily weibull_family();

const std::vector<ContinuousFamily>& continuous_families() {
  static const std::vector<ContinuousFamily> families{normal_family(), lognormal_family(), gamma_family(),
                                                      weibull_family()};
  return families;
}

const ContinuousFamily* find_continuous_family(std::string_view name) {
  for (const ContinuousFamily& f : continuous_families())
    if (f.name == name) return &f;
  return nullptr;
}

}  // namespace stengmc
