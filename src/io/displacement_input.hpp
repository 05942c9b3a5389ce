#pragma once
//! Displacements brought from elsewhere (FEM, measurements, another stengmc run) to
//! drive the circuit: an HDF5 file in stengmc's own layout, or a CSV file.
#include <string>
#include <vector>

#include "model/asperity.hpp"

namespace stengmc {

struct DisplacementInput {
  std::vector<double> times_s;               //!< sample times [s], strictly increasing
  std::vector<std::vector<double>> x_m;      //!< [element][sample] displacement [m]
  std::vector<StengElement> elements;        //!< one per row of x_m
};

//! Reads /time (M), /asperity/x (n x M) and /asperity/{sigma,d0,w,l} (n).
DisplacementInput read_displacement_hdf5(const std::string& path);

//! Reads a CSV with header `t,x1,...,xn` (SI units); every element gets `element`.
DisplacementInput read_displacement_csv(const std::string& path, const StengElement& element);

//! Checks sizes, finiteness, increasing times, positive element parameters and x < l at
//! every sample; throws InputError naming `path`.
void validate(const DisplacementInput& input, const std::string& path);

}  // namespace stengmc
