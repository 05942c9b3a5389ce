#pragma once
//! The text layouts of a measured record that `spectrum` and `invert` read: stengmc's own
//! CSV `t,V` and the CSV/TSV exports of common oscilloscopes (docs/records.md).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stengmc {

enum class RecordFormat { automatic, plain, tektronix, keysight, rigol, lecroy, picoscope };

//! The names `--format` takes, for help and messages.
inline constexpr std::string_view RECORD_FORMAT_NAMES = "auto, plain, tektronix, keysight, rigol, lecroy, picoscope";

//! The format called `name` ("auto", "plain", "tektronix", ...), or nothing.
std::optional<RecordFormat> record_format_named(std::string_view name);

//! "auto", "plain", "tektronix", ...
std::string record_format_name(RecordFormat format);

//! The layout whose signature the first lines of a file carry (each line split into trimmed
//! fields); nothing when none does.
std::optional<RecordFormat> detect_record_format(const std::vector<std::vector<std::string>>& head);

}  // namespace stengmc
