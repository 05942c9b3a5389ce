#pragma once
//! A fixed list of asperities, written out one by one (the paper's hand-picked four).
//! Random populations (MODEL.md §4) will sit beside this as another surface kind.
#include <vector>

#include "core/toml_reader.hpp"
#include "model/asperity.hpp"

namespace stengmc {

//! Reads `[defaults]` (keys every asperity shares unless it sets its own) and the
//! `[[asperity]]` list from a surface table; validates every value.
std::vector<Asperity> read_fixed_population(TomlTable& surface);

}  // namespace stengmc
