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

//! A redraw that wraps prints a new line each time (a 135-character bar at 120 columns gave
//! 128 lines for a 20 s run): every redraw must fit in one column short of the width, at any
//! width, whatever the status says; the UTF-8 of a status is never cut inside a character.
TEST(Progress, ATerminalBarFitsTheTerminalWidth) {
  for (const int columns : {20, 40, 80, 120}) {
    SCOPED_TRACE(columns);
    ProgressOutput terminal;
    terminal.terminal = true;
    terminal.redraw_period = std::chrono::milliseconds(0);
    terminal.columns = columns;
    std::FILE* file = std::tmpfile();
    ASSERT_NE(file, nullptr);
    terminal.stream = file;
    terminal.silent_period = std::chrono::milliseconds(0);
    {
      Progress progress("point 12/14", 5, terminal);
      progress.set_status("valid 5/5  V_rms 1.23e-3 V [1.1e-3, 1.4e-3]  ratio 0.93 ± 0.02 µ" + std::string(80, 'x'));
      progress.set_job_share(std::chrono::steady_clock::now(), 11.0 / 14.0, 1.0 / 14.0);
      for (int i = 0; i < 5; ++i) progress.advance();
    }
    std::string text(static_cast<std::size_t>(std::ftell(file)), '\0');
    std::rewind(file);
    text.resize(std::fread(text.data(), 1, text.size(), file));
    std::fclose(file);
    std::size_t redraws = 0;
    for (std::size_t at = text.find('\r'); at != std::string::npos; at = text.find('\r', at + 1)) {
      const std::size_t end = text.find('\033', at);
      ASSERT_NE(end, std::string::npos) << text;
      std::size_t characters = 0;
      for (std::size_t j = at + 1; j < end; ++j) characters += (static_cast<unsigned char>(text[j]) & 0xC0) != 0x80;
      EXPECT_LE(characters, static_cast<std::size_t>(columns - 1)) << text.substr(at, end - at);
      ++redraws;
    }
    EXPECT_EQ(redraws, 6u) << "one redraw per advance and the final one";
  }
}

//! A sweep's grid point gives the whole job's ETA beside its own: at its end with 11 of 14
//! points before it, the job is 12/14 done, so the job's ETA is 2/12 of its elapsed time.
TEST(Progress, APartOfAJobGivesTheWholeJobsEta) {
  ProgressOutput log;
  log.terminal = false;
  log.line_period = std::chrono::milliseconds(0);
  log.silent_period = std::chrono::milliseconds(0);
  std::FILE* file = std::tmpfile();
  ASSERT_NE(file, nullptr);
  log.stream = file;
  {
    Progress progress("point 12/14", 1, log);
    // The job started 1200 s ago: 12/14 done then leaves 200 s.
    progress.set_job_share(std::chrono::steady_clock::now() - std::chrono::seconds(1200), 11.0 / 14.0, 1.0 / 14.0);
    progress.advance();
  }
  std::string text(static_cast<std::size_t>(std::ftell(file)), '\0');
  std::rewind(file);
  text.resize(std::fread(text.data(), 1, text.size(), file));
  std::fclose(file);
  EXPECT_NE(text.find("(whole job 3.3 min)"), std::string::npos) << text;
}

TEST(Progress, DurationsReadAsAPersonWouldSayThem) {
  EXPECT_EQ(format_duration(42.0), "42.0 s");
  EXPECT_EQ(format_duration(750.0), "12.5 min");
  EXPECT_EQ(format_duration(11520.0), "3.2 h");
}

}  // namespace
}  // namespace stengmc
