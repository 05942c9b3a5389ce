#pragma once
//! Numbers in messages: %g style (6 significant digits), so 2.8e9 Pa and 1e-3 stay readable.
#include <sstream>
#include <string>

namespace stengmc {

inline std::string format_number(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

}  // namespace stengmc
