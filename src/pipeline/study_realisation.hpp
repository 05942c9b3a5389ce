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

//! Sampling below twice the highest natural frequency sqrt(k/m) / 2 pi of the study's
//! asperities aliases their lines. For a fixed list that is the file's fault (InputError, at
//! sample_rate_hz's line when the study's `root` table is given); for a random surface, the
//! realisation's (ModelError). The inverse commands apply it to the runs they make of a
//! known device (inverse/device_checks.hpp).
void check_sample_rate(const Study& study, TomlTable* root = nullptr);

}  // namespace stengmc
