#pragma once
//! A surface file: either a fixed list of asperities (the paper's hand-picked four) or a
//! random surface sampled per realisation (docs/study-files.md, surface files).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/toml_reader.hpp"
#include "model/asperity.hpp"
#include "surface/population.hpp"
#include "surface/random_surface.hpp"

namespace stengmc {

class Surface {
 public:
  //! Reads `kind` ("list", the default, or "random") and the rest of the table.
  static Surface from_toml(TomlTable& table, const std::filesystem::path& base_dir);
  static Surface fixed_list(std::vector<Asperity> asperities);
  static Surface random(RandomSurface surface);

  //! Realisation `realisation`: the list itself, or a sample (see sample_population).
  [[nodiscard]] Population sample(std::uint64_t seed, std::uint64_t realisation) const;

  //! Every file the surface read besides its own (empirical histograms), each as
  //! "<path>\n<text>", for provenance and resume checks; empty for most surfaces.
  [[nodiscard]] std::string auxiliary_inputs() const;
  //! The paths of those files (an output must never replace one).
  [[nodiscard]] std::vector<std::string> auxiliary_input_files() const;

  //! The random description, or nullptr for a fixed list.
  [[nodiscard]] const RandomSurface* random_surface() const { return random_ ? &*random_ : nullptr; }

 private:
  std::vector<Asperity> list_;
  std::optional<RandomSurface> random_;
};

}  // namespace stengmc
