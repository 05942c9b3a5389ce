// Progress reports: a terminal gets a bar redrawn in place, anything else (CI logs, Slurm
// output files) plain lines with no carriage return or escape code (issue 14).
#include "core/progress.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace stengmc {
namespace {

//! What a Progress of `total` units, advanced one by one, writes with `output` (immediate,
//! no silent period), into a temporary file.
std::string report(ProgressOutput output, std::size_t total) {
  std::FILE* file = std::tmpfile();
  EXPECT_NE(file, nullptr);
  output.stream = file;
  output.silent_period = std::chrono::milliseconds(0);
  {
    Progress progress("ensemble", total, output);
    progress.set_status("valid 3/3");
    for (std::size_t i = 0; i < total; ++i) progress.advance();
  }
  std::string text(static_cast<std::size_t>(std::ftell(file)), '\0');
  std::rewind(file);
  const std::size_t read = std::fread(text.data(), 1, text.size(), file);
  std::fclose(file);
  text.resize(read);
  return text;
}

TEST(Progress, ALogGetsPlainLinesWithoutCarriageReturnsOrEscapes) {
  ProgressOutput log;
  log.terminal = false;
  log.line_period = std::chrono::milliseconds(0);  // a line at every advance
  const std::string text = report(log, 3);
  EXPECT_EQ(text.find('\r'), std::string::npos) << text;
  EXPECT_EQ(text.find('\033'), std::string::npos) << text;
  // One line per advance before the last, then the destructor's final line: 1/3, 2/3, 3/3.
  EXPECT_NE(text.find("ensemble: 1/3 (33.3%)"), std::string::npos) << text;
  EXPECT_NE(text.find("ensemble: 3/3 (100.0%)"), std::string::npos) << text;
  EXPECT_NE(text.find("valid 3/3\n"), std::string::npos) << text;
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 3u) << text;
}

TEST(Progress, ALogIsNotFloodedWithinItsLinePeriod) {
  ProgressOutput log;
  log.terminal = false;
  log.line_period = std::chrono::hours(1);
  const std::string text = report(log, 1000);
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 2u) << "the first line and the final one, nothing between: " << text;
}

TEST(Progress, ATerminalGetsOneBarRedrawnInPlace) {
  ProgressOutput terminal;
  terminal.terminal = true;
  terminal.redraw_period = std::chrono::milliseconds(0);
  const std::string text = report(terminal, 3);
  EXPECT_NE(text.find("\rensemble"), std::string::npos) << text;
  EXPECT_NE(text.find("100.0%"), std::string::npos) << text;
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 1u) << "a bar ends its line only when done";
}

}  // namespace
}  // namespace stengmc
