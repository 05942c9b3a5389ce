#pragma once
//! A random surface: the statistical description of a rough contact from which every
//! realisation draws its asperity population (MODEL.md §4). Read from a surface file with
//! `kind = "random"` (docs/study-files.md, surface files); sampled by sample_population.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/toml_reader.hpp"
#include "model/asperity.hpp"
#include "surface/copula.hpp"
#include "surface/distribution.hpp"
#include "surface/interaction.hpp"
#include "surface/load_spread.hpp"
#include "surface/materials.hpp"

namespace stengmc {

//! How many summits a realisation has.
enum class CountRule {
  poisson,  //!< Poisson with mean density x A0 (summits scattered independently)
  fixed,    //!< exactly `summit_count`
};
//! Where the summits sit on the nominal area.
enum class PositionRule {
  uniform,  //!< independently uniform on a square of area A0, [0, sqrt(A0))^2
  given,    //!< the listed (x, y); the count is the list's length
};
//! Where each asperity's normal load comes from.
enum class LoadRule {
  fixed,  //!< every summit carries `normal_load_n` (the paper)
  hertz,  //!< a rigid flat at separation d, solved so the Hertz loads sum to W
  spread, //!< Greenwood–Williamson loads of a given mean and CV (load_spread.hpp)
};
//! Where each asperity's shear stiffness comes from.
enum class StiffnessRule {
  sampled,  //!< drawn from the `[stiffness]` distribution
  mindlin,  //!< k = 8 G* a from the contact patch (then heights set the stiffnesses)
};
//! The S-TENG element's length and width.
enum class GeometryRule {
  fixed,  //!< `length_m`, `width_m` for every element
  patch,  //!< a square of the patch area: l = w = sqrt(pi) a
};
//! The asperity's mass.
enum class MassRule {
  fixed,    //!< `mass_kg` for every asperity
  density,  //!< rho l w h, with h the summit height and l, w the element's
};
//! The Model 1 drive phase.
enum class PhaseRule {
  fixed,    //!< `phase_rad` for every asperity
  uniform,  //!< independently uniform on [0, 2 pi) (the phases stream)
};
//! What the Goryacheva interaction estimate is used for.
enum class InteractionMode {
  report,  //!< estimated and reported; the loads stay independent (the paper's picture)
  apply,   //!< interacting mode: the loads are solved with the interaction (load `hertz`)
};

//! Elastic data of the pair and the summit radius, shared by every contact formula.
struct ContactMaterials {
  ElasticBody body_1;            //!< the asperities' body (the polymer)
  ElasticBody body_2;            //!< the counter-body (steel)
  double summit_radius_m = 0.0;  //!< R_s [m]
  [[nodiscard]] double effective_modulus_pa() const { return effective_modulus(body_1, body_2); }
  [[nodiscard]] double effective_shear_modulus_pa() const { return effective_shear_modulus(body_1, body_2); }
};

//! The statistical description of one surface (docs/study-files.md, surface files).
struct RandomSurface {
  std::string title;
  double nominal_area_m2 = 0.0;             //!< A0 [m^2]

  CountRule count_rule = CountRule::poisson;
  double summit_density_per_m2 = 0.0;       //!< Poisson: mean summits per m^2
  std::size_t summit_count = 0;             //!< fixed: summits per realisation
  PositionRule position_rule = PositionRule::uniform;
  std::vector<double> given_x_m, given_y_m; //!< given positions [m]

  Distribution heights = Distribution::fixed({110e-6});  //!< summit heights z = asperity height h [m]
  StiffnessRule stiffness_rule = StiffnessRule::sampled;
  std::optional<Distribution> stiffness;    //!< sampled: stiffness law [N/m]
  std::optional<GaussianCopula> correlation;//!< height-stiffness copula (sampled stiffness only)

  std::optional<ContactMaterials> materials;//!< needed by hertz, mindlin, patch and the contact report

  LoadRule load_rule = LoadRule::fixed;
  double normal_load_n = 1e-3;              //!< fixed: N per asperity [N]
  double nominal_load_n = 0.0;              //!< hertz: W on the nominal area [N]
  //! spread: the load law (mean N̄ = `mean_load_n`, CV = `load_cv`); the summits are those in
  //! contact, their heights drawn from the normal [heights] law above the separation
  std::optional<LoadSpread> load_spread;

  InteractionMode interaction_mode = InteractionMode::report;
  InteractionSettings interaction;

  GeometryRule geometry_rule = GeometryRule::fixed;
  StengElement element;                     //!< sigma, d0 always; l, w under `fixed`
  MassRule mass_rule = MassRule::fixed;
  double mass_kg = 1e-12;                   //!< fixed mass [kg]
  double density_kg_per_m3 = 0.0;           //!< density rule: rho [kg/m^3]
  PhaseRule phase_rule = PhaseRule::fixed;
  double phase_rad = 0.0;                   //!< fixed drive phase [rad]
  //! Model 2 contact onsets [s], one draw per summit (the onsets stream); none: all at t = 0.
  std::optional<Distribution> onset;
  //! Model 2 contact lifetimes t_off - t_on [s], one draw per summit (the lifetimes stream);
  //! none: never released (docs/model.md §1.4).
  std::optional<Distribution> lifetime;
  //! Model 2 wear rates w [1/ms], one draw per summit (the wear stream); none: no wear.
  std::optional<Distribution> wear_rate;
  //! Model 2 stiffness steps ([steps]): each summit has one with this probability, its
  //! delay after the onset [s] and its factor (k after / k before) drawn from these laws (the
  //! steps stream); none: no steps.
  struct StepLaws {
    double probability = 0.0;
    Distribution after_onset_s;
    Distribution factor;
  };
  std::optional<StepLaws> steps;

  //! Mean number of summits per realisation (Poisson mean or the fixed count).
  [[nodiscard]] double mean_summit_count() const;
};

//! Largest mean number of summits a surface may ask for per realisation: beyond it a
//! realisation's arrays (and its contact solve) no longer fit comfortably in memory.
inline constexpr double MAX_MEAN_SUMMITS = 1e6;

//! Reads a `kind = "random"` surface table (the root of a surface file, or a study's
//! [surface] table); histogram files are resolved against `base_dir`. Every bad or
//! inconsistent value throws InputError naming file:line and the key.
RandomSurface read_random_surface(TomlTable& table, const std::filesystem::path& base_dir);

}  // namespace stengmc
