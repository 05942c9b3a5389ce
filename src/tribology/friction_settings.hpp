#pragma once
//! The couple's friction coefficients as [model] keys (`static_friction`,
//! `kinetic_friction`), shared by both models' settings.
#include <vector>

#include "core/setting.hpp"
#include "core/toml_reader.hpp"
#include "tribology/friction.hpp"

namespace stengmc {

//! mu_s and mu_k from `model`: mu_s >= mu_k >= 0, mu_s at most 1e3; InputError names the key.
FrictionCoefficients read_friction_coefficients(TomlTable& model);

std::vector<Setting> friction_settings(const FrictionCoefficients& friction);

}  // namespace stengmc
