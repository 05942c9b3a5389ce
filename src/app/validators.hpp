#pragma once
//! Command-line validators with plain messages (CLI11's range checks print 309-digit bounds).
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace stengmc::app {

//! A finite number > 0 (or >= 0 when `allow_zero`).
inline CLI::Validator finite_number(bool allow_zero) {
  return CLI::Validator(
      [allow_zero](std::string& text) -> std::string {
        double value = 0.0;
        std::size_t used = 0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (used != text.size() || !std::isfinite(value)) return "'" + text + "' is not a finite number";
        if (allow_zero ? value < 0.0 : value <= 0.0) return "'" + text + (allow_zero ? "' must be >= 0" : "' must be > 0");
        return "";
      },
      allow_zero ? "NUMBER >= 0" : "NUMBER > 0");
}

//! A path that is not empty: `-o ""` (an unset shell variable) would otherwise mean "the
//! default output", written silently where the user did not ask.
inline CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "an empty path: give the path of the file to write, or leave the option out for the default" : "";
      },
      "PATH");
}

}  // namespace stengmc::app
