#pragma once
//! Drawing a study's realisation: the population of its surface for (seed, realisation),
//! checked for what a run needs. The pipeline draws it, not the reader, so that an
//! ensemble draws every realisation from one study read once.
#include <cstdint>

#include "core/toml_reader.hpp"
#include "pipeline/study.hpp"

namespace stengmc {

//! `base` (read without a realisation, or with another) at realisation `realisation`:
//! population and asperities drawn from (seed, realisation) alone.
//! @throws ModelError when the realisation has nothing to simulate or aliases its lines.
Study study_for_realisation(const Study& base, std::uint64_t realisation);

//! Draws realisation `realisation` into `study` (population, asperities). With the
//! study's `root` table, a sample rate that aliases a fixed list's lines is reported at
//! its line (InputError); without, or for a random surface, it belongs to the realisation.
//! @throws ModelError when the realisation has nothing to simulate or aliases its lines.
void draw_realisation(Study& study, std::uint64_t realisation, TomlTable* root);

}  // namespace stengmc
