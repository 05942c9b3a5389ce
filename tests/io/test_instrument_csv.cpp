// Records exported by oscilloscopes (io/instrument_csv.hpp): each shipped example of
// tests/data/instruments/ (make_examples.py wrote them from one record) reads to the samples
// of its plain `t,V` CSV, and what cannot be read is named by line and column.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "io/instrument_csv.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

std::string example(const std::string& name) { return std::string(STENGMC_SOURCE_DIR) + "/tests/data/instruments/" + name; }

//! The InputError message of reading `path`, or "" when it reads.
std::string error_of(const std::string& path, const RecordReadOptions& options = {}) {
  try {
    (void)read_record_text(path, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct Example {
  const char* file;
  RecordFormat format;
};

//! The file's name in test output, not the object's bytes.
void PrintTo(const Example& e, std::ostream* out) { *out << e.file; }

class InstrumentRecords : public ::testing::TestWithParam<Example> {};

TEST_P(InstrumentRecords, ReadToTheSamplesOfThePlainCsv) {
  // Times: the plain CSV holds k * 1e-8 s to 17 digits; an export prints them rounded (to
  // 8 digits at worst) and the reader puts them back on the grid from the first to the last,
  // so they agree to rounding of that arithmetic, well inside 1e-12 of the 2 us record.
  // Voltages: every file prints the same 7 digits; PicoScope's in mV, scaled by 1e-3, which
  // is exact to a few ulp.
  const SignalInput plain = read_record_text(example("plain.csv"), {});
  ASSERT_EQ(plain.times_s.size(), 200u);
  for (const RecordFormat format : {RecordFormat::automatic, GetParam().format}) {
    const SignalInput record = read_record_text(example(GetParam().file), {format, "", {}});
    ASSERT_EQ(record.times_s.size(), plain.times_s.size()) << GetParam().file;
    for (std::size_t k = 0; k < plain.times_s.size(); ++k) {
      EXPECT_NEAR(record.times_s[k], plain.times_s[k], 1e-12 * plain.times_s.back()) << GetParam().file << " sample " << k;
      EXPECT_NEAR(record.voltage_v[k], plain.voltage_v[k], 1e-12 * std::abs(plain.voltage_v[k])) << GetParam().file << " sample " << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Vendors, InstrumentRecords,
                         ::testing::Values(Example{"tektronix_tds.csv", RecordFormat::tektronix},
                                           Example{"tektronix_mso.csv", RecordFormat::tektronix},
                                           Example{"keysight.csv", RecordFormat::keysight},
                                           Example{"rigol.csv", RecordFormat::rigol},
                                           Example{"lecroy.csv", RecordFormat::lecroy},
                                           Example{"picoscope.csv", RecordFormat::picoscope},
                                           Example{"picoscope_tab.txt", RecordFormat::picoscope}),
                         [](const auto& test) {
                           std::string name = test.param.file;
                           std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                           return name;
                         });

TEST(InstrumentRecord, ColumnPicksAnotherChannel) {
  const SignalInput second = read_record_text(example("keysight.csv"), {RecordFormat::automatic, "2", {}});
  EXPECT_TRUE(std::all_of(second.voltage_v.begin(), second.voltage_v.end(), [](double v) { return v == 0.0; }));
  EXPECT_NE(error_of(example("keysight.csv"), {RecordFormat::automatic, "CH3", {}})
                .find("keysight.csv: --column CH3 is not a voltage column of this record (its columns: 1, 2)"),
            std::string::npos);
}

TEST(InstrumentRecord, ReadsSemicolonsWithDecimalCommas) {
  ScratchDir scratch("instrument-semicolon");
  const std::string path = scratch.write("k.csv", "x-axis;1\nsecond;Volt\n0,0E+00;1,5\n1,0E-08;-2,25\n");
  const SignalInput record = read_record_text(path, {});
  EXPECT_EQ(record.times_s, (std::vector<double>{0.0, 1e-8}));
  EXPECT_EQ(record.voltage_v, (std::vector<double>{1.5, -2.25}));
}

TEST(InstrumentRecord, NamesTheLineAndColumnOfANonNumber) {
  ScratchDir scratch("instrument-nan");
  const std::string path = scratch.write("p.csv", "Time,Channel A\n(us),(mV)\n\n0.00,1.0\n0.01,abc\n");
  EXPECT_NE(error_of(path).find("p.csv:5: column 2 ('Channel A') = 'abc' is not a number"), std::string::npos) << error_of(path);
}

TEST(InstrumentRecord, RejectsTimesOffAUniformGrid) {
  // 3e-9 s off a 1e-8 s step, printed to 1e-15 s: not rounding.
  ScratchDir scratch("instrument-jitter");
  const std::string path = scratch.write("l.csv", "LECROYWR64Xi,1,Waveform\nSegments,1,SegmentSize,4\nTime,Ampl\n"
                                                  "0.000000e+00,1\n1.000000e-08,2\n2.300000e-08,3\n3.000000e-08,4\n");
  EXPECT_NE(error_of(path).find("l.csv:6: column 1 ('Time'): t = 2.3e-08 s is off the uniform grid"), std::string::npos)
      << error_of(path);
}

TEST(InstrumentRecord, RejectsAUnitThatIsNotAVoltageAndAnUnknownLayout) {
  ScratchDir scratch("instrument-unit");
  const std::string amps = scratch.write("a.csv", "Time,Channel A\n(us),(A)\n0,1\n1,2\n");
  EXPECT_NE(error_of(amps).find("a.csv:2: column 2 ('Channel A') is in '(A)', not a unit of voltage"), std::string::npos)
      << error_of(amps);
  const std::string other = scratch.write("o.csv", "Time (s),Voltage (V)\n0,1\n");
  EXPECT_NE(error_of(other).find("o.csv:1: header must be `t,V`"), std::string::npos) << error_of(other);
  EXPECT_NE(error_of(example("keysight.csv"), {RecordFormat::rigol, "", {}}).find("keysight.csv:1: a Rigol header is"),
            std::string::npos);
}

TEST(InstrumentRecord, SpectrumReadsAnExportAndRefusesAnUnknownFormat) {
  ScratchDir scratch("instrument-cli");
  auto r = run_cli("spectrum " + example("rigol.csv") + " --out " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("spectrum " + example("rigol.csv") + " --format yokogawa --out " + scratch.file("s.h5"), scratch);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--format"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("yokogawa"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace stengmc
