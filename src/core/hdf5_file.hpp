#pragma once
//! Thin HDF5 (C++ API) wrappers: datasets carry a `units` attribute, groups are made on
//! demand, nothing non-finite is ever written (but NaN for what is absent: write_with_gaps),
//! and files appear only when complete.
#include <H5Cpp.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/hdf5_dimensions.hpp"
#include "core/temporary_file.hpp"

namespace stengmc {

//! Every HDF5 failure is rethrown as stengmc::Error (writer) or InputError (reader)
//! naming the file and the object.
//!
//! Builds a new HDF5 file in memory; `commit()` writes it under a temporary name
//! (core/temporary_file.hpp), fsyncs it and renames it into place, so a killed or failed run
//! never leaves a half-written result under the final name, and a failed write (a full
//! disk) is reported with the system's reason ("No space left on device").
//!
//! A writer given a `Describer` (the vocabulary of a family of files: io/output_vocabulary)
//! also takes each dataset's units, long_name and axis names from it, and commit() attaches
//! the axes to dimension scales (core/hdf5_dimensions.hpp): the file is then netCDF-4 too.
class Hdf5Writer {
 public:
  //! The description of the dataset at a path; throws Error for a path it does not know.
  using Describer = std::function<DatasetDescription(const std::string& path)>;

  explicit Hdf5Writer(std::string path, Describer describe = {});
  ~Hdf5Writer();
  Hdf5Writer(const Hdf5Writer&) = delete;
  Hdf5Writer& operator=(const Hdf5Writer&) = delete;

  //! 1-D dataset of doubles; throws Error if any value is NaN or Inf.
  void write(const std::string& path, std::span<const double> values, std::string_view units);
  //! 2-D dataset [rows][columns] of doubles (every row the same length).
  void write(const std::string& path, const std::vector<std::vector<double>>& rows, std::string_view units);
  //! 1-D dataset of integers.
  void write(const std::string& path, std::span<const std::int64_t> values, std::string_view units);
  //! 1-D dataset of variable-length strings.
  void write(const std::string& path, const std::vector<std::string>& values, std::string_view units);

  //! The same, described by the Describer: units, long_name and named axes.
  void write(const std::string& path, std::span<const double> values);
  void write(const std::string& path, const std::vector<std::vector<double>>& rows);
  void write(const std::string& path, std::span<const std::int64_t> values);
  void write(const std::string& path, const std::vector<std::string>& values);
  //! A described 2-D dataset [rows][columns] that marks what is absent with NaN (the only
  //! non-finite value written anywhere; CF readers take NaN as missing): a track's stiffness in
  //! the windows it is not in contact. Every row has `columns` values (none: extent rows x columns).
  void write_with_gaps(const std::string& path, const std::vector<std::vector<double>>& rows, std::size_t columns);
  //! Described, but with a unit the Describer cannot know (one that depends on the data).
  void write_with_units(const std::string& path, std::span<const double> values, std::string_view units);

  //! Creates the group (and its parents) if it does not exist yet.
  void group(const std::string& path);

  //! String attribute on a group or dataset ("/" for the root).
  void attribute(const std::string& object, const std::string& name, std::string_view value);
  //! Numeric attributes.
  void attribute(const std::string& object, const std::string& name, double value);
  void attribute(const std::string& object, const std::string& name, std::int64_t value);

  //! Writes the file out and renames it to its final path, from HDF5's memory (or, where
  //! that cannot be, from a copy of it: then the file exists twice in memory).
  void commit();

 private:
  //! The group that holds `dataset_path`, made (with its parents) if absent; kept open.
  H5::Group& group_for(const std::string& dataset_path);
  //! Creates the dataset at `path` in its group and keeps it open until commit(), so its
  //! attributes, dimension scales and references need no walk of the path. `layout` is an
  //! untimed one (core/hdf5_untimed.hpp), so the file holds no time of its making.
  H5::DataSet& create_dataset(const std::string& path, const H5::DataType& type, const std::vector<hsize_t>& extent,
                              const H5::DSetCreatPropList& layout);
  //! The group or dataset at `path` ("/": the root), as held open or opened.
  H5::H5Object& object_at(const std::string& path);
  //! The dataset's units (none for "") and, when given, its long_name (written while it is open).
  void annotate(H5::DataSet& dataset, std::string_view units, std::optional<std::string_view> long_name);
  //! The raw writes, with the long_name of a described dataset; a flat array under the
  //! extent `shape` when one is given (DatasetDescription::shape).
  void write(const std::string& path, std::span<const double> values, std::string_view units,
             std::optional<std::string_view> long_name, const std::vector<std::size_t>& shape = {});
  //! With gap_columns, NaN is written (write_with_gaps) and the extent is rows x gap_columns.
  void write(const std::string& path, const std::vector<std::vector<double>>& rows, std::string_view units,
             std::optional<std::string_view> long_name, std::optional<std::size_t> gap_columns = std::nullopt);
  void write(const std::string& path, std::span<const std::int64_t> values, std::string_view units,
             std::optional<std::string_view> long_name, const std::vector<std::size_t>& shape = {});
  void write(const std::string& path, const std::vector<std::string>& values, std::string_view units,
             std::optional<std::string_view> long_name, const std::vector<std::size_t>& shape = {});
  //! The Describer's description of `path`, remembered for commit(); its units unless
  //! `units` is given.
  DatasetDescription described(const std::string& path, std::optional<std::string_view> units = std::nullopt);
  //! The described dataset's CF `comment`, when its description has one.
  void comment(const std::string& path, const DatasetDescription& description);
  //! Runs HDF5 calls on the file; their failures become Error naming the output.
  template <class Call>
  void guarded(const std::string& what, Call call);

  std::string path_;
  std::unique_ptr<TemporaryFile> temporary_;
  std::unique_ptr<H5::H5File> file_;
  Describer describe_;
  std::vector<DescribedDataset> described_;
  std::map<std::string, H5::Group> groups_;      //!< every group made or opened, by path ("/" the root)
  std::map<std::string, H5::DataSet> datasets_;  //!< every dataset written, open until commit()
  WrittenDatasets written_;  //!< every dataset written with its extent, so commit() need not ask HDF5
};

//! The HDF5 library failed reading an object of an existing file, which is then damaged
//! (or not what it claims to be). The message names the file and the object and gives the
//! library's words; object() alone ("attribute /@file_type", "/atoms/onset_values") lets the reader
//! of a family of files say it in that family's terms, without the library's words.
class Hdf5ReadFailure : public InputError {
 public:
  Hdf5ReadFailure(const std::string& message, std::string object) : InputError(message), object_(std::move(object)) {}
  [[nodiscard]] const std::string& object() const { return object_; }

 private:
  std::string object_;
};

//! Reads datasets and attributes from an existing file, with errors naming the file (an
//! HDF5 failure: Hdf5ReadFailure).
class Hdf5Reader {
 public:
  explicit Hdf5Reader(std::string path);

  [[nodiscard]] bool has(const std::string& path) const;
  //! 1-D dataset of doubles (or an integer dataset, converted).
  [[nodiscard]] std::vector<double> vector(const std::string& path) const;
  //! 2-D dataset of doubles as rows.
  [[nodiscard]] std::vector<std::vector<double>> matrix(const std::string& path) const;
  //! String attribute, or "" when absent.
  [[nodiscard]] std::string string_attribute(const std::string& object, const std::string& name) const;
  //! Numeric attribute, or nothing when absent.
  [[nodiscard]] std::optional<double> number_attribute(const std::string& object, const std::string& name) const;
  //! Integer attribute, or nothing when absent.
  [[nodiscard]] std::optional<std::int64_t> integer_attribute(const std::string& object, const std::string& name) const;
  //! The path of the dimension scale attached to axis `axis` of dataset `path` (the HDF5
  //! Dimension Scale API: how netCDF-4 and xarray store a coordinate), or nothing when none is.
  [[nodiscard]] std::optional<std::string> dimension_scale(const std::string& path, unsigned axis) const;

 private:
  std::string path_;
  H5::H5File file_;
};

//! A file whose root `file_type` is a stengmc one says which format it has: refuse one
//! without a valid `format_version` (an integer >= 1) or with a newer one than this program
//! reads, `supported` (InputError naming the file). Files of other programs are not checked.
void check_format_version(const Hdf5Reader& file, const std::string& path, std::int64_t supported);

}  // namespace stengmc
