#include "core/format.hpp"
#include "surface/materials.hpp"

#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace stengmc {

namespace {
}  // namespace

void validate_elastic_body(const ElasticBody& body, const std::string& name) {
  if (!std::isfinite(body.youngs_modulus_pa) || body.youngs_modulus_pa <= 0.0)
    throw InputError(name + ": youngs_modulus_pa = " + format_number(body.youngs_modulus_pa) +
                     " must be a finite number > 0");
  // nu = 0.5 (incompressible) is physical but 1 - nu^2 and 2 - nu stay finite there;
  // the brief keeps the open interval so a typo such as 5 instead of 0.5 is caught
  // together with the thermodynamic bound nu > -1.
  if (!std::isfinite(body.poisson_ratio) || body.poisson_ratio <= -1.0 || body.poisson_ratio >= 0.5)
    throw InputError(name + ": poisson_ratio = " + format_number(body.poisson_ratio) +
                     " must satisfy -1 < nu < 0.5");
}

double shear_modulus(const ElasticBody& body) {
  return body.youngs_modulus_pa / (2.0 * (1.0 + body.poisson_ratio));
}

double effective_modulus(const ElasticBody& body_1, const ElasticBody& body_2) {
  validate_elastic_body(body_1, "body 1");
  validate_elastic_body(body_2, "body 2");
  const double c1 = (1.0 - body_1.poisson_ratio * body_1.poisson_ratio) / body_1.youngs_modulus_pa;
  const double c2 = (1.0 - body_2.poisson_ratio * body_2.poisson_ratio) / body_2.youngs_modulus_pa;
  return 1.0 / (c1 + c2);
}

double effective_shear_modulus(const ElasticBody& body_1, const ElasticBody& body_2) {
  validate_elastic_body(body_1, "body 1");
  validate_elastic_body(body_2, "body 2");
  const double c1 = (2.0 - body_1.poisson_ratio) / shear_modulus(body_1);
  const double c2 = (2.0 - body_2.poisson_ratio) / shear_modulus(body_2);
  return 1.0 / (c1 + c2);
}

double mindlin_stiffness(double effective_shear_modulus_pa, double patch_radius_m) {
  if (!std::isfinite(effective_shear_modulus_pa) || effective_shear_modulus_pa <= 0.0)
    throw InputError("mindlin stiffness: effective shear modulus G* = " +
                     format_number(effective_shear_modulus_pa) + " Pa must be > 0");
  if (!std::isfinite(patch_radius_m) || patch_radius_m < 0.0)
    throw InputError("mindlin stiffness: patch radius a = " + format_number(patch_radius_m) +
                     " m must be >= 0");
  return 8.0 * effective_shear_modulus_pa * patch_radius_m;
}

}  // namespace stengmc
