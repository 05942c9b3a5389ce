// toml++ compiled into stengmc (core/toml_library.hpp), with its Unicode look-ups fixed:
// compared against the ranges toml++'s own table generator lists, over every code point,
// and through the study reader on the characters that reached the undefined behaviour.
// Under the sanitizer build, toml++ 3.3's unfixed table stops at its
// __builtin_unreachable() on U+00E9 (it did: Fuzz.surface found it).
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "core/error.hpp"
#include "core/toml_library.hpp"
#include "core/toml_reader.hpp"

namespace {

//! toml++ 3.3's definition of non-ASCII horizontal whitespace, from its generator's comment
//! ("20 code units from 8 ranges"): the Unicode space separators and the byte-order mark.
bool listed_as_horizontal_whitespace(char32_t c) {
  return c == U'\u00A0' || c == U'\u1680' || c == U'\u180E' || (c >= U'\u2000' && c <= U'\u200B') || c == U'\u202F' ||
         (c >= U'\u205F' && c <= U'\u2060') || c == U'\u3000' || c == U'\uFEFF';
}

}  // namespace

TEST(TomlLibrary, NonAsciiHorizontalWhitespaceIsExactlyWhatTomlPlusPlusLists) {
  int members = 0;
  for (char32_t c = 0; c <= 0x10FFFF; ++c) {
    const bool member = toml::impl::is_non_ascii_horizontal_whitespace(c);
    ASSERT_EQ(member, listed_as_horizontal_whitespace(c)) << "U+" << std::hex << static_cast<unsigned>(c);
    members += member ? 1 : 0;
  }
  EXPECT_EQ(members, 20);
}

TEST(TomlLibrary, AccentedLettersReadInCommentsStringsAndQuotedKeysAndAreRefusedWhereWhitespaceMayStand) {
  const std::string text = "# résumé of a study\n[t]\nname = \"café\"  # é after a value\n\"clé\" = 1.5\n";
  const auto document = stengmc::TomlDocument::from_string(text, "accents.toml");
  std::optional<stengmc::TomlTable> table = document->root().table("t");
  ASSERT_TRUE(table.has_value());
  EXPECT_EQ(table->string("name", ""), "café");
  EXPECT_EQ(table->number("clé", 0.0), 1.5);
  // A bare é where a key or whitespace must stand is a syntax error naming the place.
  try {
    (void)stengmc::TomlDocument::from_string("[t]\nx = 1 é\n", "bare.toml");
    FAIL() << "a bare é after a value was accepted";
  } catch (const stengmc::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bare.toml:2"), std::string::npos) << e.what();
  }
}
