#pragma once
//! The units an oscilloscope export writes beside its columns, as factors to SI.
#include <optional>
#include <string_view>

namespace stengmc {

//! Seconds per `unit`: "s", "second(s)", "ms", "us", "µs", "ns", "ps", "millisecond(s)" ..
//! "picosecond(s)" (brackets and parentheses around it ignored, "" meaning s); nothing for
//! anything else.
std::optional<double> time_unit_scale(std::string_view unit);

//! Volts per `unit`: "V", "Volt", "mV", "uV", "µV", "kV" (as for time); nothing for anything
//! else (a current probe's "A" is not a voltage).
std::optional<double> voltage_unit_scale(std::string_view unit);

}  // namespace stengmc
