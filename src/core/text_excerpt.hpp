#pragma once
//! Text from an input file quoted in a message, kept short: a CSV line of 10 MB echoed whole
//! would bury the message (and fill a log) with what the user already has.
#include <string>
#include <string_view>

namespace stengmc {

//! Characters of an input line a message quotes before it cuts the rest.
inline constexpr std::size_t EXCERPT_CHARACTERS = 80;

//! `text` as it is when short; else its first EXCERPT_CHARACTERS characters, "...", and how
//! long it was.
inline std::string text_excerpt(std::string_view text) {
  if (text.size() <= EXCERPT_CHARACTERS) return std::string(text);
  return std::string(text.substr(0, EXCERPT_CHARACTERS)) + "... (" + std::to_string(text.size()) + " characters)";
}

}  // namespace stengmc
