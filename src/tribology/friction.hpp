#pragma once

namespace stengmc {

//! Coulomb friction coefficients of the tribological couple (paper Table 1: PET on steel).
struct FrictionCoefficients {
  double static_coefficient = 0.28;   //!< mu_s
  double kinetic_coefficient = 0.22;  //!< mu_k
};

}  // namespace stengmc
