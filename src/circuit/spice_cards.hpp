#pragma once
//! SPICE text split into the logical cards ngspice reads from it, the way ngspice's
//! front end does (inpcom.c: inp_stripcomments_line, inp_stitch_continuation_lines):
//! whole-line comments (a first non-blank '*', '#' or '$') and blank lines dropped,
//! end-of-line comments (';', '//', and '$' after a blank or a comma) cut, '+' lines joined
//! to the card before them with a blank. What comes out holds no comment and no
//! continuation, so the card stengmc checks is the card ngspice runs
//! (circuit/netlist_policy.hpp).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace stengmc {

struct SpiceCard {
  std::string text;   //!< the card, without comments, continuations joined, blanks trimmed
  std::string file;   //!< where it was read from
  std::size_t line;   //!< its first line in that file (1-based)

  //! "file:line", for messages.
  [[nodiscard]] std::string origin() const { return file + ":" + std::to_string(line); }
};

//! The cards of `text`, read from `file`. With `has_title` the first line is the title
//! (a netlist's; an included file has none) and is not a card.
//! @throws InputError naming file and line for a control character (a NUL would end the
//!         line for ngspice but not for this reader) or a continuation of nothing
std::vector<SpiceCard> split_spice_cards(std::string_view text, const std::string& file, bool has_title);

//! The card's first field, lower case: ".model", "r1", ".controlx".
std::string spice_card_head(std::string_view card);

//! `text` in lower case (ASCII; SPICE is case-insensitive).
std::string spice_lower(std::string_view text);

}  // namespace stengmc
