// The HDF5 writer never leaves a partial or non-finite file (docs/output-files.md).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

bool any_temporary(const std::string& folder) {
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().extension() == ".tmp") return true;
  return false;
}

TEST(Hdf5Writer, RefusesNonFiniteValuesAndLeavesNoFileBehind) {
  testing::ScratchDir scratch("hdf5-nan");
  const std::string out = scratch.file("out.h5");
  for (double bad : {std::nan(""), static_cast<double>(INFINITY), -static_cast<double>(INFINITY)}) {
    {
      Hdf5Writer file(out);
      const std::vector<double> values{1.0, bad, 3.0};
      EXPECT_THROW(file.write("/x", values, "m"), Error);
      EXPECT_THROW(file.attribute("/", "a", bad), Error);
    }  // destroyed without commit
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(any_temporary(scratch.file("")));
  }
}

TEST(Hdf5Writer, HdfFailuresBecomeErrorsNamingTheFile) {
  testing::ScratchDir scratch("hdf5-fail");
  Hdf5Writer file(scratch.file("out.h5"));
  const std::vector<double> values{1.0};
  file.write("/x", values, "m");
  try {
    file.write("/x", values, "m");  // the dataset exists already: HDF5 refuses
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write /x"), std::string::npos) << e.what();
  }
}

TEST(Hdf5Writer, CommitMovesTheCompleteFileIntoPlace) {
  testing::ScratchDir scratch("hdf5-commit");
  const std::string out = scratch.file("out.h5");
  {
    Hdf5Writer file(out);
    const std::vector<double> values{1.0, 2.0};
    file.write("/group/x", values, "m");
    EXPECT_FALSE(std::filesystem::exists(out));  // not before commit
    file.commit();
  }
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_FALSE(any_temporary(scratch.file("")));
  EXPECT_EQ(Hdf5Reader(out).vector("/group/x"), (std::vector<double>{1.0, 2.0}));
}

// commit() writes the file from the core driver's own memory, clearing the superblock's
// consistency flags as H5Fget_file_image does (an open file marks itself open for writing
// there). A file smaller than the driver's 1 MiB step and one larger than it: each must
// come back whole, with the flags of a closed file (superblock version 0, bytes 20-23).
TEST(Hdf5Writer, CommittedFilesAreWholeAndMarkedClosed) {
  testing::ScratchDir scratch("hdf5-image");
  for (const std::size_t count : {std::size_t{3}, std::size_t{400'000}}) {
    const std::string out = scratch.file("out" + std::to_string(count) + ".h5");
    std::vector<double> values(count);
    for (std::size_t i = 0; i < count; ++i) values[i] = std::sin(0.37 * static_cast<double>(i)) * 1e-6;  // incompressible
    {
      Hdf5Writer file(out);
      file.write("/x", values, "m");
      file.commit();
    }
    std::ifstream in(out, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GE(bytes.size(), 24u);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89HDF\r\n\x1a\n", 8));
    EXPECT_EQ(bytes[8], '\0') << "superblock version";
    EXPECT_EQ(bytes.substr(20, 4), std::string(4, '\0')) << "file consistency flags of " << out;
    EXPECT_EQ(Hdf5Reader(out).vector("/x"), values);
  }
}

// No object records when it was made (core/hdf5_untimed.hpp): HDF5's default stamps each
// group and dataset, so equal results differed in their bytes and their sha256. Every kind
// of object the writer makes: the root, nested groups, contiguous and chunked columns,
// matrices, integers, strings.
TEST(Hdf5Writer, NoObjectCarriesATimestamp) {
  testing::ScratchDir scratch("hdf5-untimed");
  const std::string out = scratch.file("out.h5");
  {
    Hdf5Writer file(out);
    file.write("/a/b/small", std::vector<double>{1.0, 2.0}, "m");
    file.write("/a/large", std::vector<double>(20'000, 0.5), "m");  // chunked and compressed
    file.write("/matrix", std::vector<std::vector<double>>{{1.0, 2.0}, {3.0, 4.0}}, "V");
    file.write("/ids", std::vector<std::int64_t>{3, 4}, "1");
    file.write("/names", std::vector<std::string>{"x", "y"}, "1");
    file.group("/empty");
    file.attribute("/", "created_utc", "2023-11-14T22:13:20Z");
    file.commit();
  }
  const H5::H5File file(out, H5F_ACC_RDONLY);
  std::vector<std::string> visited;
  std::vector<std::string> timed;
  struct Seen {
    std::vector<std::string>& visited;
    std::vector<std::string>& timed;
  } seen{visited, timed};
  const auto look = [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
    auto& s = *static_cast<Seen*>(data);
    s.visited.emplace_back(name);
    if (info->atime != 0 || info->mtime != 0 || info->ctime != 0 || info->btime != 0) s.timed.emplace_back(name);
    return 0;
  };
  ASSERT_GE(H5Ovisit2(file.getId(), H5_INDEX_NAME, H5_ITER_INC, look, &seen, H5O_INFO_TIME), 0);
  EXPECT_EQ(visited.size(), 9u) << "the root, /a, /a/b, /empty and five datasets";
  EXPECT_TRUE(timed.empty()) << timed.size() << " objects carry a timestamp, the first " << timed.front();
}

// The writer gives HDF5 a string-conversion buffer sized to the data, at most 1 MiB
// (hdf5_file.cpp); a column of more strings than that holds is converted in pieces. Both
// must come back exactly as written, read through HDF5's own API.
TEST(Hdf5Writer, StringColumnsShorterAndLongerThanTheConversionBufferRoundTrip) {
  testing::ScratchDir scratch("hdf5-strings");
  const std::string out = scratch.file("out.h5");
  const std::vector<std::string> few{"", "regrip"};
  std::vector<std::string> many;  // 100000 x 16 bytes of conversion: more than 1 MiB
  for (int i = 0; i < 100'000; ++i) many.push_back("failure " + std::to_string(i * 7919 % 100'003));
  {
    Hdf5Writer file(out);
    file.write("/few", few, "");
    file.write("/many", many, "");
    file.commit();
  }
  const H5::H5File file(out, H5F_ACC_RDONLY);
  const H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  const std::vector<std::pair<std::string, const std::vector<std::string>*>> columns{{"/few", &few}, {"/many", &many}};
  for (const auto& [path, expected] : columns) {
    const H5::DataSet dataset = file.openDataSet(path);
    std::vector<char*> read(expected->size());
    dataset.read(read.data(), type);
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < read.size(); ++i) mismatches += (read[i] == nullptr || (*expected)[i] != read[i]);
    EXPECT_EQ(mismatches, 0u) << path;
    H5::DataSet::vlenReclaim(read.data(), type, dataset.getSpace());
  }
}

TEST(Hdf5Reader, AGroupWhereADatasetIsExpectedIsAnInputError) {
  testing::ScratchDir scratch("hdf5-group");
  const std::string out = scratch.file("in.h5");
  {
    Hdf5Writer file(out);
    const std::vector<double> values{1.0};
    file.write("/asperity/x/inner", values, "m");  // /asperity/x is a group
    file.commit();
  }
  EXPECT_THROW((void)Hdf5Reader(out).matrix("/asperity/x"), InputError);
}

}  // namespace
}  // namespace stengmc
