// Dimension scales of described datasets (core/hdf5_dimensions): coordinates and index
// coordinates as netCDF-4 lays them out, and descriptions that contradict the data refused.
// (That whole files open in xarray is Io.OutputsOpenInXarray.)
#include <gtest/gtest.h>

#include <hdf5.h>
#include <H5DSpublic.h>  // after hdf5.h, which it assumes

#include <filesystem>
#include <map>
#include <string>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

//! A vocabulary for the tests: path -> (units, long name, dimensions).
Hdf5Writer::Describer vocabulary(std::map<std::string, std::vector<std::string>> dimensions) {
  return [dimensions](const std::string& path) {
    const auto found = dimensions.find(path);
    if (found == dimensions.end()) throw Error("no description of " + path);
    return DatasetDescription{"m", "a length", found->second};
  };
}

std::string attribute_text(hid_t object, const char* name) {
  const hid_t attribute = H5Aopen(object, name, H5P_DEFAULT);
  const hid_t type = H5Aget_type(attribute);
  std::string text(H5Tget_size(type), '\0');
  if (H5Tis_variable_str(type) > 0) {
    char* value = nullptr;
    H5Aread(attribute, type, &value);
    text = value;
    H5free_memory(value);
  } else {
    H5Aread(attribute, type, text.data());
    text.resize(text.find('\0') == std::string::npos ? text.size() : text.find('\0'));
  }
  H5Tclose(type);
  H5Aclose(attribute);
  return text;
}

TEST(Hdf5Dimensions, CoordinatesArePreferredAndOtherAxesGetIndexCoordinates) {
  testing::ScratchDir scratch("hdf5-dimensions");
  const std::string out = scratch.file("out.h5");
  {
    Hdf5Writer file(out, vocabulary({{"/time", {"time"}}, {"/a/x", {"n", "time"}}, {"/a/k", {"n"}}}));
    file.write("/time", std::vector<double>{0.0, 1.0, 2.0});
    file.write("/a/x", std::vector<std::vector<double>>{{1, 2, 3}, {4, 5, 6}});
    file.write("/a/k", std::vector<double>{7, 8});
    file.commit();
  }
  const hid_t f = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t time = H5Dopen2(f, "/time", H5P_DEFAULT), x = H5Dopen2(f, "/a/x", H5P_DEFAULT),
              k = H5Dopen2(f, "/a/k", H5P_DEFAULT), n = H5Dopen2(f, "/a/n", H5P_DEFAULT);
  ASSERT_GE(n, 0) << "no index coordinate /a/n";
  EXPECT_GT(H5DSis_scale(time), 0);
  EXPECT_EQ(attribute_text(time, "NAME"), "time");  // a coordinate variable: named as itself
  // An axis without a coordinate gets one: its index 0, 1 (a coordinate variable too, not
  // netCDF-C's pure dimension, which xarray shows unlabelled).
  EXPECT_EQ(attribute_text(n, "NAME"), "n");
  EXPECT_EQ(attribute_text(n, "units"), "1");
  EXPECT_EQ(attribute_text(n, "long_name"), "index along dimension n");
  EXPECT_EQ(Hdf5Reader(out).vector("/a/n"), (std::vector<double>{0.0, 1.0}));
  EXPECT_GT(H5DSis_attached(x, n, 0), 0);
  EXPECT_GT(H5DSis_attached(x, time, 1), 0);  // the root's /time, seen from /a
  EXPECT_GT(H5DSis_attached(k, n, 0), 0);
  // The attachments are written once, in H5DS's layout, by the writer: HDF5's own readers of
  // them (above, and these) see exactly one scale per axis and no attachment that was not made.
  EXPECT_EQ(H5DSget_num_scales(x, 0), 1);
  EXPECT_EQ(H5DSget_num_scales(x, 1), 1);
  EXPECT_EQ(H5DSis_attached(x, time, 0), 0);
  EXPECT_EQ(H5DSis_attached(k, time, 0), 0);
  EXPECT_EQ(attribute_text(x, "units"), "m");
  EXPECT_EQ(attribute_text(x, "long_name"), "a length");
  for (hid_t d : {time, x, k, n}) H5Dclose(d);
  H5Fclose(f);
  EXPECT_EQ(Hdf5Reader(out).matrix("/a/x"), (std::vector<std::vector<double>>{{1, 2, 3}, {4, 5, 6}}));
}

TEST(Hdf5Dimensions, AShorterAxisTakesTheAlternativeDimension) {
  testing::ScratchDir scratch("hdf5-dimensions-alt");
  const std::string out = scratch.file("out.h5");
  {
    Hdf5Writer file(out, vocabulary({{"/time", {"time"}}, {"/c/v", {"time|valid_time"}}}));
    file.write("/time", std::vector<double>{0.0, 1.0, 2.0});
    file.write("/c/v", std::vector<double>{5.0, 6.0});  // stopped after two samples
    file.commit();
  }
  const hid_t f = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t v = H5Dopen2(f, "/c/v", H5P_DEFAULT), valid = H5Dopen2(f, "/c/valid_time", H5P_DEFAULT);
  ASSERT_GE(valid, 0);
  EXPECT_GT(H5DSis_attached(v, valid, 0), 0);
  H5Dclose(v);
  H5Dclose(valid);
  H5Fclose(f);
}

//! Commit refuses with an Error whose message holds `expected`, and leaves no file.
void expect_refused(const std::map<std::string, std::vector<std::string>>& dimensions, const std::string& expected) {
  testing::ScratchDir scratch("hdf5-dimensions-bad");
  const std::string out = scratch.file("out.h5");
  {
    Hdf5Writer file(out, vocabulary(dimensions));
    file.write("/time", std::vector<double>{0.0, 1.0, 2.0});
    file.write("/g/time", std::vector<double>{4.0, 5.0});
    file.write("/g/v", std::vector<double>{1.0, 2.0});
    try {
      file.commit();
      FAIL() << "no exception";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Hdf5Dimensions, DescriptionsThatContradictTheDataAreRefused) {
  // Two axis names for a 1-D dataset.
  expect_refused({{"/time", {"time"}}, {"/g/time", {"event"}}, {"/g/v", {"event", "n"}}}, "/g/v has 1 axes");
  // "time" seen from /g is /g/time, a dataset over "event", not a time coordinate.
  expect_refused({{"/time", {"time"}}, {"/g/time", {"event"}}, {"/g/v", {"time"}}}, "would be /g/time");
}

}  // namespace
}  // namespace stengmc
