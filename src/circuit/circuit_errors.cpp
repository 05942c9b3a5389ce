#include "circuit/circuit_errors.hpp"

#include <sstream>

#include "core/error.hpp"

namespace stengmc {

void throw_capacitance_not_positive(double t_s, double capacitance_f) {
  std::ostringstream msg;
  msg.precision(10);
  msg << "circuit: element capacitance not positive at t = " << t_s << " s (sum C_i + C_L = " << capacitance_f
      << " F): x reached l; the S-TENG element formulas (MODEL.md §2) hold only for x < l";
  throw ModelError(msg.str());
}

void throw_non_finite(const std::string& what, double t_s) {
  std::ostringstream msg;
  msg.precision(10);
  msg << "circuit: the circuit produced a non-finite " << what << " at t = " << t_s
      << " s: check the load resistance, load capacitance, sigma, d0, w and l (and the displacements) for "
         "physically plausible values";
  throw ModelError(msg.str());
}

}  // namespace stengmc
