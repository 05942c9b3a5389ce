#pragma once
//! The circuit's two model errors, one wording for both solvers (circuit_solver.hpp,
//! element_sums.hpp).
#include <string>

namespace stengmc {

//! Sum C_i + C_L <= 0 at t: an element's x reached its l (MODEL.md §2). Throws ModelError.
[[noreturn]] void throw_capacitance_not_positive(double t_s, double capacitance_f);

//! The circuit produced a non-finite `what` (voltage, charge) at t. Throws ModelError.
[[noreturn]] void throw_non_finite(const std::string& what, double t_s);

}  // namespace stengmc
