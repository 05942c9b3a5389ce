#pragma once
//! Elastic data of the two bodies in contact and the moduli the contact formulas use
//! (MODEL.md §4; Johnson 1985, "Contact Mechanics", §4.2 and §7.2).
#include <string>

namespace stengmc {

//! One isotropic linear-elastic body.
struct ElasticBody {
  double youngs_modulus_pa;  //!< E [Pa]
  double poisson_ratio;      //!< nu [-]
};

//! Throws InputError unless E > 0 (finite) and -1 < nu < 0.5; `name` labels the body
//! in the message (e.g. "surface.body_1").
void validate_elastic_body(const ElasticBody& body, const std::string& name);

//! Shear modulus G = E / (2 (1 + nu)) [Pa].
double shear_modulus(const ElasticBody& body);

//! Effective (contact) modulus E*, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 [Pa]
//! (Johnson 1985, §4.2). Validates both bodies.
double effective_modulus(const ElasticBody& body_1, const ElasticBody& body_2);

//! Effective shear modulus G*, 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2 [Pa]
//! (Johnson 1985, §7.2, Mindlin's tangential compliance). Validates both bodies.
double effective_shear_modulus(const ElasticBody& body_1, const ElasticBody& body_2);

//! Mindlin's initial tangential stiffness of a circular patch, k = 8 G* a [N/m]
//! (Mindlin 1949; Johnson 1985, §7.2, both bodies).
//! @param effective_shear_modulus_pa G* [Pa], > 0
//! @param patch_radius_m contact radius a [m], >= 0 (a = 0 gives k = 0: no contact)
double mindlin_stiffness(double effective_shear_modulus_pa, double patch_radius_m);

}  // namespace stengmc
