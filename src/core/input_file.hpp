#pragma once
//! Opening what a user names as an input: a regular file of bounded size, or a named
//! error (docs/faults.md). A device such as /dev/zero would be read
//! until memory ran out, a FIFO would block forever.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>

namespace stengmc {

//! Text files (studies, surface files, histograms) are kilobytes; this bounds what a
//! mistaken path can make us read into memory.
inline constexpr std::uint64_t MAX_TEXT_INPUT_BYTES = 64ull << 20;

//! "a folder", "a character device", "a FIFO", ... for messages.
std::string describe_file_type(std::filesystem::file_type type);

//! Throws InputError naming `path` unless it exists and is a regular file (links
//! followed); returns its size [bytes]. `what` names it in messages ("the histogram file").
std::uint64_t check_input_file(const std::string& path, const std::string& what);

//! The whole text of a regular file of at most `max_bytes`; InputError otherwise.
std::string read_text_file(const std::string& path, const std::string& what,
                           std::uint64_t max_bytes = MAX_TEXT_INPUT_BYTES);

//! An input stream on a checked regular file (CSV data of any size).
std::ifstream open_input_file(const std::string& path, const std::string& what);

//! `text` without leading and trailing blanks (spaces, tabs, a CR of a CRLF line end).
std::string trim_blanks(std::string_view text);

//! A number in a text file (CSV): decimal, locale-independent, optional sign; subnormal
//! values are numbers like any other. Nothing when the text is not a number, and `why` then
//! says what is wrong with it ("is not a number", "is not finite", "is beyond the range
//! of a double").
std::optional<double> parse_number(std::string_view text, std::string* why = nullptr);

}  // namespace stengmc
