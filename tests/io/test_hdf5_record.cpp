// A record in another program's HDF5 file (io/hdf5_record.hpp, `--dataset`): files written
// here with HDF5's own C API (not stengmc's writer), as an oscilloscope, a lab pipeline or
// xarray's to_netcdf lays them out, read to the samples written, in volts and seconds; and
// what cannot be read is named by file, dataset and what was expected.
#include <hdf5.h>
#include <hdf5_hl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "io/hdf5_record.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

using testing::run_cli;
using testing::ScratchDir;

constexpr std::size_t SAMPLES = 400;
constexpr double STEP_S = 1e-8;

//! A test waveform in volts: two damped lines and an offset.
double volts(std::size_t k) {
  const double t = static_cast<double>(k) * STEP_S;
  return 0.03 + 0.2 * std::exp(-t / 2e-6) * std::sin(2e6 * 2 * M_PI * t) + 0.05 * std::cos(7.5e6 * 2 * M_PI * t);
}

//! An HDF5 file made with the C API alone.
class RawFile {
 public:
  explicit RawFile(const std::string& path) : id_(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)) {}
  ~RawFile() {
    close();
    H5Fclose(id_);
  }
  RawFile(const RawFile&) = delete;
  RawFile& operator=(const RawFile&) = delete;

  //! A 1-D dataset of `values` stored as `type` (native double or float), open.
  hid_t dataset(const std::string& name, const std::vector<double>& values, hid_t type = H5T_NATIVE_DOUBLE) {
    if (name.find('/', 1) != std::string::npos) {
      const std::string group = name.substr(0, name.rfind('/'));
      if (H5Lexists(id_, group.c_str(), H5P_DEFAULT) <= 0) H5Gclose(H5Gcreate2(id_, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    }
    const hsize_t extent = values.size();
    const hid_t space = H5Screate_simple(1, &extent, nullptr);
    const hid_t set = H5Dcreate2(id_, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Sclose(space);
    open_.push_back(set);
    return set;
  }
  static void text(hid_t object, const char* name, const std::string& value) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, value.size());
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, type, value.c_str());
    H5Aclose(attribute), H5Sclose(space), H5Tclose(type);
  }
  static void number(hid_t object, const char* name, double value) {
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(object, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, H5T_NATIVE_DOUBLE, &value);
    H5Aclose(attribute), H5Sclose(space);
  }
  void close() {
    for (hid_t set : open_) H5Dclose(set);
    open_.clear();
  }

 private:
  hid_t id_;
  std::vector<hid_t> open_;
};

std::vector<double> voltages(double scale) {
  std::vector<double> v(SAMPLES);
  for (std::size_t k = 0; k < SAMPLES; ++k) v[k] = volts(k) / scale;
  return v;
}

std::vector<double> times(double start_s, double scale) {
  std::vector<double> t(SAMPLES);
  for (std::size_t k = 0; k < SAMPLES; ++k) t[k] = (start_s + static_cast<double>(k) * STEP_S) / scale;
  return t;
}

void expect_record(const SignalInput& r, double start_s, double time_tolerance_s) {
  ASSERT_EQ(r.voltage_v.size(), SAMPLES);
  ASSERT_EQ(r.times_s.size(), SAMPLES);
  for (std::size_t k = 0; k < SAMPLES; ++k) {
    EXPECT_NEAR(r.voltage_v[k], volts(k), 1e-15) << "sample " << k;
    EXPECT_NEAR(r.times_s[k], start_s + static_cast<double>(k) * STEP_S, time_tolerance_s) << "sample " << k;
  }
  // Put on their grid: equal steps to rounding.
  for (std::size_t k = 1; k < SAMPLES; ++k) EXPECT_NEAR(r.times_s[k] - r.times_s[k - 1], STEP_S, 1e-9 * STEP_S);
}

std::string error_of(const std::string& path, const Hdf5RecordLocation& where) {
  try {
    (void)read_hdf5_record(path, where);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Hdf5Record, SamplingAttributesAndMillivolts) {
  ScratchDir dir("hdf5-record-attributes");
  const std::string path = dir.file("scope.h5");
  {
    RawFile f(path);
    const hid_t set = f.dataset("/scope/ch1", voltages(1e-3));
    RawFile::text(set, "units", "mV");
    RawFile::number(set, "sample_interval_s", STEP_S);
    RawFile::number(set, "start_time_s", -1e-6);
    const hid_t other = f.dataset("/scope/ch2", voltages(1.0));
    RawFile::number(other, "sample_rate_hz", 1.0 / STEP_S);
  }
  expect_record(read_hdf5_record(path, {"/scope/ch1", ""}), -1e-6, 1e-18);
  expect_record(read_hdf5_record(path, {"/scope/ch2", ""}), 0.0, 1e-18);
}

TEST(Hdf5Record, ANetcdfTimeCoordinateInMicrosecondsSinceAnEpoch) {
  // As netCDF-4 and xarray write a coordinate: a dataset made a dimension scale and attached.
  ScratchDir dir("hdf5-record-scale");
  const std::string path = dir.file("xarray.nc");
  {
    RawFile f(path);
    const hid_t time = f.dataset("/time", times(2e-6, 1e-6));
    RawFile::text(time, "units", "microseconds since 2026-11-27 00:00:00");
    H5DSset_scale(time, "time");
    const hid_t v = f.dataset("/v", voltages(1.0));
    RawFile::text(v, "units", "V");
    H5DSattach_scale(v, time, 0);
    f.close();
  }
  expect_record(read_hdf5_record(path, {"/v", ""}), 2e-6, 1e-18);
}

TEST(Hdf5Record, AFloat32TimeDatasetIsPutOnItsGrid) {
  ScratchDir dir("hdf5-record-float32");
  const std::string path = dir.file("lab.h5");
  {
    RawFile f(path);
    RawFile::text(f.dataset("/t_us", times(5e-6, 1e-6), H5T_NATIVE_FLOAT), "units", "us");
    f.dataset("/signal", voltages(1.0), H5T_NATIVE_FLOAT);
  }
  const SignalInput r = read_hdf5_record(path, {"/signal", "/t_us"});
  ASSERT_EQ(r.times_s.size(), SAMPLES);
  // float32 keeps 24 bits: times to ~1e-7 relative, voltages to ~6e-8 of 0.28 V.
  for (std::size_t k = 0; k < SAMPLES; ++k) {
    EXPECT_NEAR(r.times_s[k], 5e-6 + static_cast<double>(k) * STEP_S, 1e-6 * 9e-6);
    EXPECT_NEAR(r.voltage_v[k], volts(k), 1e-7);
  }
}

TEST(Hdf5Record, WhatCannotBeReadIsNamed) {
  ScratchDir dir("hdf5-record-errors");
  const std::string path = dir.file("bad.h5");
  {
    RawFile f(path);
    f.dataset("/untimed", voltages(1.0));
    RawFile::text(f.dataset("/amps", voltages(1.0)), "units", "A");
    const hid_t both = f.dataset("/both", voltages(1.0));
    RawFile::number(both, "sample_interval_s", STEP_S);
    RawFile::number(both, "sample_rate_hz", 1.0 / STEP_S);
    RawFile::number(f.dataset("/negative", voltages(1.0)), "sample_interval_s", -STEP_S);
    std::vector<double> jittered = times(0.0, 1.0);
    jittered[123] += 0.01 * STEP_S;
    f.dataset("/jittered_t", jittered);
    std::vector<double> with_nan = voltages(1.0);
    with_nan[7] = NAN;
    RawFile::number(f.dataset("/nan", with_nan), "sample_rate_hz", 1.0 / STEP_S);
    f.dataset("/short_t", std::vector<double>(10, 0.0));
  }
  EXPECT_NE(error_of(path, {"/nowhere", ""}).find("bad.h5: /nowhere: no such dataset (--dataset)"), std::string::npos);
  EXPECT_NE(error_of(path, {"/untimed", ""}).find("/untimed: no times: give --time-dataset"), std::string::npos);
  EXPECT_NE(error_of(path, {"/amps", ""}).find("units \"A\" are not a voltage unit"), std::string::npos);
  EXPECT_NE(error_of(path, {"/both", ""}).find("has both sample_interval_s and sample_rate_hz"), std::string::npos);
  EXPECT_NE(error_of(path, {"/negative", ""}).find("@sample_interval_s = -1e-08 s: expected a finite number > 0"), std::string::npos);
  EXPECT_NE(error_of(path, {"/untimed", "/jittered_t"}).find("/jittered_t: t[123] = "), std::string::npos);
  EXPECT_NE(error_of(path, {"/nan", ""}).find("/nan: sample 7 = nan V is not a finite voltage"), std::string::npos);
  EXPECT_NE(error_of(path, {"/untimed", "/short_t"}).find("/short_t: 10 times for 400 samples of /untimed"), std::string::npos);
  EXPECT_NE(error_of(path, {"/untimed", "/none"}).find("/none: no such dataset (--time-dataset)"), std::string::npos);
}

TEST(Hdf5Record, SpectrumOfADatasetEqualsThatOfTheSameRecordAsCsv) {
  // The command line: the same record given two ways gives the same spectrum file numbers.
  ScratchDir dir("hdf5-record-cli");
  const std::string h5 = dir.file("scope.h5");
  {
    RawFile f(h5);
    const hid_t set = f.dataset("/ch1", voltages(1e-3));
    RawFile::text(set, "units", "mV");
    RawFile::number(set, "sample_rate_hz", 1.0 / STEP_S);
  }
  std::string csv = "t,V\n";
  char line[96];
  for (std::size_t k = 0; k < SAMPLES; ++k) {
    std::snprintf(line, sizeof line, "%.17g,%.17g\n", static_cast<double>(k) * STEP_S, volts(k));
    csv += line;
  }
  dir.write("scope.csv", csv);
  const auto from_h5 = run_cli("spectrum " + h5 + " --dataset /ch1 -o " + dir.file("a.h5"), dir);
  ASSERT_EQ(from_h5.exit_code, 0) << from_h5.output;
  const auto from_csv = run_cli("spectrum " + dir.file("scope.csv") + " -o " + dir.file("b.h5"), dir);
  ASSERT_EQ(from_csv.exit_code, 0) << from_csv.output;
  // The same samples to a few ulp (mV x 1e-3 is not exact), the same analysis: an FFT's
  // rounding is relative to the largest component, so bins agree to 1e-12 of the largest.
  const Hdf5Reader a(dir.file("a.h5")), b(dir.file("b.h5"));
  for (const char* name : {"/spectrum/frequency", "/spectrum/voltage"}) {
    const std::vector<double> x = a.vector(name), y = b.vector(name);
    ASSERT_EQ(x.size(), y.size()) << name;
    ASSERT_GT(x.size(), 10u) << name;
    double largest = 0.0;
    for (double v : y) largest = std::max(largest, std::abs(v));
    for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x[k], y[k], 1e-12 * largest) << name << " bin " << k;
  }
  const auto refused = run_cli("spectrum " + h5 + " --dataset /ch1 --column V -o " + dir.file("c.h5"), dir);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("excludes"), std::string::npos) << refused.output;
  const auto untimed = run_cli("spectrum " + h5 + " --time-dataset /t -o " + dir.file("d.h5"), dir);
  EXPECT_NE(untimed.exit_code, 0);
  EXPECT_NE(untimed.output.find("requires --dataset"), std::string::npos) << untimed.output;
}

}  // namespace
}  // namespace stengmc
