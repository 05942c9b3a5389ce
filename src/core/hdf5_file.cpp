#include "core/hdf5_file.hpp"

#include <hdf5_hl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/error.hpp"
#include "core/hdf5_untimed.hpp"
#include "core/input_file.hpp"
#include "core/posix_file.hpp"

namespace stengmc {

namespace {

const H5::StrType& string_type() {
  static const H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  return type;
}

//! Runs HDF5 calls reading `object` of `file`, turning their exceptions (which do not
//! derive from std::exception) into ours, with the file and the object named, so the CLI
//! reports them.
template <class Call>
auto reading(const std::string& file, const std::string& object, Call call) -> decltype(call()) {
  try {
    return call();
  } catch (const H5::Exception& e) {
    throw Hdf5ReadFailure(file + ": cannot read " + object + ": " + e.getDetailMsg(), object);
  }
}

// Datasets larger than this are refused before allocating: a corrupt file can declare
// 1e12 elements.
constexpr hsize_t MAX_READ_ELEMENTS = 500'000'000;

void check_finite(const std::string& path, std::span<const double> values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw Error("refusing to write a non-finite value into " + path + " (element " + std::to_string(i) +
                  "); no output was written");
}

//! A transfer list whose type-conversion buffer holds `count` elements of `element_bytes`
//! (at least one, at most HDF5's default 1 MiB, beyond which it converts in pieces).
//! HDF5 converts variable-length strings through that buffer and, left to its default,
//! callocs 1 MiB for every such write: a quarter of a single run's page faults, for a few
//! dozen bytes of strings.
H5::DSetMemXferPropList conversion_buffer(std::size_t count, std::size_t element_bytes) {
  constexpr std::size_t DEFAULT_BYTES = 1 << 20;
  H5::DSetMemXferPropList transfer;
  transfer.setBuffer(std::clamp(count * element_bytes, element_bytes, DEFAULT_BYTES), nullptr, nullptr);
  return transfer;
}

//! Clears the superblock's file consistency flags in a file image, as H5Fget_file_image
//! does: an open file marks itself open for writing there, and a closed file must not say
//! so. Where they lie depends on the superblock's version (HDF5 File Format Specification,
//! section II.A: versions 0 and 1 at byte 20, four bytes; 2 and 3 at byte 11, one byte).
//! False (nothing changed) for an image that does not start with a superblock it knows.
bool clear_consistency_flags(char* image, std::size_t size) {
  constexpr std::string_view SIGNATURE("\x89HDF\r\n\x1a\n", 8);
  if (image == nullptr || size < 24 || std::string_view(image, SIGNATURE.size()) != SIGNATURE) return false;
  const auto version = static_cast<unsigned char>(image[8]);
  if (version <= 1) std::fill(image + 20, image + 24, '\0');
  else if (version <= 3) image[11] = '\0';
  else return false;
  return true;
}

}  // namespace

// ---------------------------------------------------------------- Hdf5Writer

Hdf5Writer::Hdf5Writer(std::string path, Describer describe) : path_(std::move(path)), describe_(std::move(describe)) {
  H5::Exception::dontPrint();
  const auto parent = std::filesystem::path(path_).parent_path();
  std::error_code ignored;
  if (!parent.empty()) std::filesystem::create_directories(parent, ignored);
  temporary_ = std::make_unique<TemporaryFile>(path_);
  // The file is built in memory (HDF5's core driver, no backing store) and written out by
  // commit() with plain checked writes. HDF5's own writes could fail inside H5Fclose (a
  // flush on a full disk), and HDF5 1.10 then frees the file's structures but keeps its id:
  // closing that id again, which H5File's destructor and the library's clean-up at exit
  // both do, crashes (HDFGroup/hdf5 PR #2291, fixed in 1.14.1). In memory nothing fails
  // but allocation, and commit() reports the system's reason for a failed write exactly.
  try {
    H5::FileAccPropList access;
    constexpr std::size_t GROWTH_BYTES = 1 << 20;
    if (H5Pset_fapl_core(access.getId(), GROWTH_BYTES, false) < 0)
      throw H5::PropListIException("H5Pset_fapl_core", "cannot select the core driver");
    file_ = std::make_unique<H5::H5File>(temporary_->path(), H5F_ACC_TRUNC, untimed_file(), access);
  } catch (const H5::Exception& e) {
    throw Error(path_ + ": cannot create the output file in memory: " + e.getDetailMsg());
  }
}

Hdf5Writer::~Hdf5Writer() = default;  // the file in memory is dropped; temporary_ removes any on disk

template <class Call>
void Hdf5Writer::guarded(const std::string& what, Call call) {
  try {
    call();
  } catch (const H5::Exception& e) {
    throw Error(path_ + ": " + what + ": " + e.getDetailMsg());
  }
}

H5::Group& Hdf5Writer::group_for(const std::string& dataset_path) {
  const std::size_t slash = dataset_path.rfind('/');
  const std::string path = slash == 0 || slash == std::string::npos ? "/" : dataset_path.substr(0, slash);
  if (const auto found = groups_.find(path); found != groups_.end()) return found->second;
  if (path == "/") return groups_.emplace(path, file_->openGroup("/")).first->second;
  H5::Group& parent = group_for(path);
  const std::string name = path.substr(path.rfind('/') + 1);
  if (!parent.nameExists(name)) {
    // Made with the C call, which takes a group creation list, and opened as any group.
    const hid_t made = H5Gcreate2(parent.getId(), name.c_str(), H5P_DEFAULT, untimed_group(), H5P_DEFAULT);
    if (made < 0 || H5Gclose(made) < 0) throw H5::GroupIException("H5Gcreate2", "cannot create group " + path);
  }
  H5::Group group = parent.openGroup(name);
  return groups_.emplace(path, std::move(group)).first->second;
}

H5::DataSet& Hdf5Writer::create_dataset(const std::string& path, const H5::DataType& type,
                                        const std::vector<hsize_t>& extent, const H5::DSetCreatPropList& layout) {
  H5::Group& group = group_for(path);
  const H5::DataSpace space(static_cast<int>(extent.size()), extent.data());
  H5::DataSet& dataset = datasets_[path] = group.createDataSet(path.substr(path.rfind('/') + 1), type, space, layout);
  written_[path] = {extent, dataset.getId()};
  return dataset;
}

void Hdf5Writer::annotate(H5::DataSet& dataset, std::string_view units, std::optional<std::string_view> long_name) {
  const H5::DataSpace scalar(H5S_SCALAR);
  if (!units.empty()) dataset.createAttribute("units", string_type(), scalar).write(string_type(), std::string(units));
  if (long_name)
    dataset.createAttribute("long_name", string_type(), scalar).write(string_type(), std::string(*long_name));
}

namespace {

//! 1-D datasets are chunked and compressed (shuffle + deflate 1): per-realisation tables of
//! a large ensemble are read a column at a time and compress several-fold; the values are
//! stored exactly. Datasets of up to 64 KiB stay contiguous: compressing them saves a few
//! kilobytes at most and cost a single run's file a third of its write time (zlib's
//! set-up per dataset and its deflate). Empty ones must (a chunk cannot be empty).
H5::DSetCreatPropList column_layout(hsize_t size) {
  constexpr hsize_t SMALLEST_COMPRESSED = 8192;  // values: 64 KiB of doubles
  if (size < SMALLEST_COMPRESSED) return untimed_dataset();  // shared, not a new list per dataset
  H5::DSetCreatPropList layout = untimed(H5::DSetCreatPropList());
  constexpr hsize_t CHUNK = 16384;
  const hsize_t chunk[1] = {std::min(size, CHUNK)};
  layout.setChunk(1, chunk);
  layout.setShuffle();
  layout.setDeflate(1);
  return layout;
}

//! The extent of `size` values written under `shape` (empty: 1-D), which must hold them all.
std::vector<hsize_t> extent_of(const std::string& path, std::size_t size, const std::vector<std::size_t>& shape) {
  if (shape.empty()) return {size};
  std::size_t product = 1;
  for (const std::size_t n : shape) product *= n;
  if (product != size)
    throw Error(path + ": " + std::to_string(size) + " values do not fill its shape of " + std::to_string(product));
  return {shape.begin(), shape.end()};
}

//! A 1-D array's compressed layout; an N-D one (an ensemble's statistics, G values) stays contiguous.
H5::DSetCreatPropList layout_of(const std::vector<hsize_t>& extent) {
  return extent.size() == 1 ? column_layout(extent.front()) : untimed_dataset();
}

}  // namespace

void Hdf5Writer::write(const std::string& path, std::span<const double> values, std::string_view units) {
  write(path, values, units, std::nullopt);
}

void Hdf5Writer::write(const std::string& path, std::span<const double> values, std::string_view units,
                       std::optional<std::string_view> long_name, const std::vector<std::size_t>& shape) {
  check_finite(path, values);
  const std::vector<hsize_t> extent = extent_of(path, values.size(), shape);
  guarded("cannot write " + path, [&] {
    H5::DataSet& dataset = create_dataset(path, H5::PredType::NATIVE_DOUBLE, extent, layout_of(extent));
    if (!values.empty()) dataset.write(values.data(), H5::PredType::NATIVE_DOUBLE);
    annotate(dataset, units, long_name);
  });
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::vector<double>>& rows, std::string_view units) {
  write(path, rows, units, std::nullopt);
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::vector<double>>& rows, std::string_view units,
                       std::optional<std::string_view> long_name, std::optional<std::size_t> gap_columns) {
  const std::size_t columns = gap_columns ? *gap_columns : rows.empty() ? 0 : rows.front().size();
  std::vector<double> flat;
  flat.reserve(rows.size() * columns);
  for (const auto& row : rows) {
    if (row.size() != columns) throw Error(path + ": rows of different lengths");
    flat.insert(flat.end(), row.begin(), row.end());
  }
  if (gap_columns) {
    for (std::size_t i = 0; i < flat.size(); ++i)
      if (std::isinf(flat[i]))
        throw Error("refusing to write an infinite value into " + path + " (element " + std::to_string(i) +
                    "); no output was written");
  } else {
    check_finite(path, flat);
  }
  guarded("cannot write " + path, [&] {
    H5::DataSet& dataset = create_dataset(path, H5::PredType::NATIVE_DOUBLE, {rows.size(), columns}, untimed_dataset());
    if (!flat.empty()) dataset.write(flat.data(), H5::PredType::NATIVE_DOUBLE);
    annotate(dataset, units, long_name);
  });
}

void Hdf5Writer::write(const std::string& path, std::span<const std::int64_t> values, std::string_view units) {
  write(path, values, units, std::nullopt);
}

void Hdf5Writer::write(const std::string& path, std::span<const std::int64_t> values, std::string_view units,
                       std::optional<std::string_view> long_name, const std::vector<std::size_t>& shape) {
  const std::vector<hsize_t> extent = extent_of(path, values.size(), shape);
  guarded("cannot write " + path, [&] {
    H5::DataSet& dataset = create_dataset(path, H5::PredType::NATIVE_INT64, extent, layout_of(extent));
    if (!values.empty()) dataset.write(values.data(), H5::PredType::NATIVE_INT64);
    annotate(dataset, units, long_name);
  });
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::string>& values, std::string_view units) {
  write(path, values, units, std::nullopt);
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::string>& values, std::string_view units,
                       std::optional<std::string_view> long_name, const std::vector<std::size_t>& shape) {
  const std::vector<hsize_t> extent = extent_of(path, values.size(), shape);
  guarded("cannot write " + path, [&] {
    std::vector<const char*> pointers;
    pointers.reserve(values.size());
    for (const auto& v : values) pointers.push_back(v.c_str());
    H5::DataSet& dataset = create_dataset(path, string_type(), extent, untimed_dataset());
    if (!values.empty()) dataset.write(pointers.data(), string_type(), H5::DataSpace::ALL, H5::DataSpace::ALL,
                                       conversion_buffer(values.size(), sizeof(hvl_t)));
    annotate(dataset, units, long_name);
  });
}

DatasetDescription Hdf5Writer::described(const std::string& path, std::optional<std::string_view> units) {
  if (!describe_) throw Error(path_ + ": " + path + ": this file has no vocabulary to describe its datasets");
  DatasetDescription description = describe_(path);
  if (units) description.units = *units;
  described_.push_back({path, description});
  return description;
}

void Hdf5Writer::write(const std::string& path, std::span<const double> values) {
  const DatasetDescription d = described(path);
  write(path, values, d.units, d.long_name, d.shape);
  comment(path, d);
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::vector<double>>& rows) {
  const DatasetDescription d = described(path);
  write(path, rows, d.units, d.long_name);
  comment(path, d);
}

void Hdf5Writer::write_with_gaps(const std::string& path, const std::vector<std::vector<double>>& rows, std::size_t columns) {
  const DatasetDescription d = described(path);
  write(path, rows, d.units, d.long_name, columns);
  comment(path, d);
}

void Hdf5Writer::write(const std::string& path, std::span<const std::int64_t> values) {
  const DatasetDescription d = described(path);
  write(path, values, d.units, d.long_name, d.shape);
  comment(path, d);
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::string>& values) {
  const DatasetDescription d = described(path);
  write(path, values, d.units, d.long_name, d.shape);
  comment(path, d);
}

void Hdf5Writer::write_with_units(const std::string& path, std::span<const double> values, std::string_view units) {
  const DatasetDescription d = described(path, units);
  write(path, values, d.units, d.long_name, d.shape);
  comment(path, d);
}

void Hdf5Writer::comment(const std::string& path, const DatasetDescription& description) {
  if (!description.comment.empty()) attribute(path, "comment", description.comment);
}

void Hdf5Writer::group(const std::string& path) {
  guarded("cannot create group " + path, [&] { group_for(path + "/"); });
}

namespace {

//! Attribute `name` of the group or dataset at `path`, if it has one. (An open attribute
//! keeps its object alive in the library, so the object may be closed here.)
std::optional<H5::Attribute> find_attribute(const H5::H5File& file, const std::string& path, const std::string& name) {
  if (path != "/" && file.childObjType(path) == H5O_TYPE_DATASET) {
    const H5::DataSet dataset = file.openDataSet(path);
    if (!dataset.attrExists(name)) return std::nullopt;
    return dataset.openAttribute(name);
  }
  const H5::Group group = file.openGroup(path);
  if (!group.attrExists(name)) return std::nullopt;
  return group.openAttribute(name);
}

}  // namespace

H5::H5Object& Hdf5Writer::object_at(const std::string& path) {
  if (const auto dataset = datasets_.find(path); dataset != datasets_.end()) return dataset->second;
  if (const auto group = groups_.find(path); group != groups_.end()) return group->second;
  return groups_.emplace(path, file_->openGroup(path)).first->second;  // fails for a path that is neither
}

void Hdf5Writer::attribute(const std::string& object, const std::string& name, std::string_view value) {
  guarded("cannot write attribute " + object + "@" + name, [&] {
    H5::Attribute attribute = object_at(object).createAttribute(name, string_type(), H5::DataSpace(H5S_SCALAR));
    attribute.write(string_type(), std::string(value));
  });
}

void Hdf5Writer::attribute(const std::string& object, const std::string& name, double value) {
  if (!std::isfinite(value)) throw Error("refusing to write a non-finite attribute " + object + "@" + name);
  guarded("cannot write attribute " + object + "@" + name, [&] {
    H5::Attribute attribute =
        object_at(object).createAttribute(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(H5S_SCALAR));
    attribute.write(H5::PredType::NATIVE_DOUBLE, &value);
  });
}

void Hdf5Writer::attribute(const std::string& object, const std::string& name, std::int64_t value) {
  guarded("cannot write attribute " + object + "@" + name, [&] {
    H5::Attribute attribute =
        object_at(object).createAttribute(name, H5::PredType::NATIVE_INT64, H5::DataSpace(H5S_SCALAR));
    attribute.write(H5::PredType::NATIVE_INT64, &value);
  });
}

void Hdf5Writer::commit() {
  std::string copy;             // the image, when the driver's own memory cannot be used
  std::string_view image;
  guarded("cannot finish the file", [&] {
    const hid_t id = file_->getId();
    attach_dimension_scales(id, path_, described_, written_);
    datasets_.clear();  // closed: their headers go to the file's image with the flush
    groups_.clear();
    if (H5Fflush(id, H5F_SCOPE_LOCAL) < 0) throw H5::FileIException("H5Fflush", "cannot flush the file");
    // The image is the file's first EOA bytes (H5Fget_file_image). The core driver's handle
    // is the address of its memory (H5FDcore.c, H5FD__core_get_handle), which holds them
    // when its EOF lies beyond the EOA (H5Fget_filesize is the larger of the two): then the
    // file is written out from there, without a copy of a size of the file (a quarter of
    // a single run's page faults). Otherwise (the two equal) H5Fget_file_image copies it.
    const ssize_t size = H5Fget_file_image(id, nullptr, 0);
    hsize_t extent = 0;
    void* handle = nullptr;
    if (size < 0 || H5Fget_filesize(id, &extent) < 0)
      throw H5::FileIException("H5Fget_file_image", "cannot take the file's image");
    if (extent > static_cast<hsize_t>(size) && H5Fget_vfd_handle(id, H5P_DEFAULT, &handle) >= 0 && handle != nullptr &&
        clear_consistency_flags(*static_cast<char**>(handle), static_cast<std::size_t>(size))) {
      image = std::string_view(*static_cast<char**>(handle), static_cast<std::size_t>(size));
      return;
    }
    copy.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(id, copy.data(), copy.size()) != size)
      throw H5::FileIException("H5Fget_file_image", "cannot take the file's image");
    image = copy;
    file_->close();  // frees the in-memory file before its copy is written out
  });
  write_file_durably(temporary_->path(), image, path_);
  file_.reset();
  temporary_->commit();
  sync_directory_of(path_);
}

// ---------------------------------------------------------------- Hdf5Reader

Hdf5Reader::Hdf5Reader(std::string path) : path_(std::move(path)) {
  H5::Exception::dontPrint();
  check_input_file(path_, "an HDF5 file");
  try {
    file_ = H5::H5File(path_, H5F_ACC_RDONLY);
  } catch (const H5::Exception&) {
    throw InputError(path_ + ": not a readable HDF5 file");
  }
}

bool Hdf5Reader::has(const std::string& path) const {
  // Walk the path so a missing intermediate group is "absent", not an HDF5 error.
  std::size_t start = 1;
  while (true) {
    const std::size_t slash = path.find('/', start);
    const std::string prefix = path.substr(0, slash);
    if (H5Lexists(file_.getId(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    start = slash + 1;
  }
}

namespace {

//! Opens `path` as a numeric dataset of `rank` dimensions and returns its extent.
std::vector<hsize_t> numeric_extent(const H5::H5File& file, const std::string& file_name, const std::string& path,
                                    int rank, H5::DataSet& dataset) {
  if (H5Oexists_by_name(file.getId(), path.c_str(), H5P_DEFAULT) <= 0 ||
      file.childObjType(path) != H5O_TYPE_DATASET)
    throw InputError(file_name + ": " + path + " is not a dataset");
  dataset = file.openDataSet(path);
  H5::DataSpace space = dataset.getSpace();
  if (space.getSimpleExtentNdims() != rank)
    throw InputError(file_name + ": dataset " + path + " must be " + (rank == 1 ? "one" : "two") +
                     "-dimensional" + (rank == 2 ? " (asperities x samples)" : ""));
  const H5T_class_t type = dataset.getTypeClass();
  if (type != H5T_FLOAT && type != H5T_INTEGER) throw InputError(file_name + ": dataset " + path + " must hold numbers");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  space.getSimpleExtentDims(dims.data());
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (total > MAX_READ_ELEMENTS)
    throw InputError(file_name + ": dataset " + path + " has " + std::to_string(total) + " elements, above the limit of " +
                     std::to_string(MAX_READ_ELEMENTS));
  return dims;
}

}  // namespace

std::vector<double> Hdf5Reader::vector(const std::string& path) const {
  if (!has(path)) throw InputError(path_ + ": dataset " + path + " is missing");
  return reading(path_, path, [&] {
    H5::DataSet dataset;
    const auto dims = numeric_extent(file_, path_, path, 1, dataset);
    std::vector<double> values(dims[0]);
    if (!values.empty()) dataset.read(values.data(), H5::PredType::NATIVE_DOUBLE);
    return values;
  });
}

std::optional<std::string> Hdf5Reader::dimension_scale(const std::string& path, unsigned axis) const {
  if (!has(path)) throw InputError(path_ + ": dataset " + path + " is missing");
  return reading(path_, path, [&] {
    const H5::DataSet dataset = file_.openDataSet(path);
    std::optional<std::string> found;
    if (H5DSget_num_scales(dataset.getId(), axis) <= 0) return found;
    // The first scale attached: its name is the path it was opened by.
    auto first = [](hid_t, unsigned, hid_t scale, void* out) -> herr_t {
      const ssize_t length = H5Iget_name(scale, nullptr, 0);
      if (length <= 0) return 0;
      std::string name(static_cast<std::size_t>(length) + 1, '\0');
      H5Iget_name(scale, name.data(), name.size());
      name.resize(static_cast<std::size_t>(length));
      *static_cast<std::optional<std::string>*>(out) = name;
      return 1;  // stop at it
    };
    H5DSiterate_scales(dataset.getId(), axis, nullptr, first, &found);
    return found;
  });
}

std::vector<std::vector<double>> Hdf5Reader::matrix(const std::string& path) const {
  if (!has(path)) throw InputError(path_ + ": dataset " + path + " is missing");
  return reading(path_, path, [&] {
    H5::DataSet dataset;
    const auto dims = numeric_extent(file_, path_, path, 2, dataset);
    std::vector<double> flat(dims[0] * dims[1]);
    if (!flat.empty()) dataset.read(flat.data(), H5::PredType::NATIVE_DOUBLE);
    std::vector<std::vector<double>> rows(dims[0]);
    for (hsize_t i = 0; i < dims[0]; ++i)
      rows[i].assign(flat.begin() + static_cast<std::ptrdiff_t>(i * dims[1]),
                     flat.begin() + static_cast<std::ptrdiff_t>((i + 1) * dims[1]));
    return rows;
  });
}

std::string Hdf5Reader::string_attribute(const std::string& object, const std::string& name) const {
  return reading(path_, "attribute " + object + "@" + name, [&] {
    const auto found = find_attribute(file_, object, name);
    if (!found) return std::string();
    const H5::Attribute& attribute = *found;
    if (attribute.getTypeClass() != H5T_STRING) throw InputError(path_ + ": attribute " + object + "@" + name + " is not text");
    std::string value;
    attribute.read(attribute.getStrType(), value);
    return value;
  });
}

std::optional<double> Hdf5Reader::number_attribute(const std::string& object, const std::string& name) const {
  return reading(path_, "attribute " + object + "@" + name, [&]() -> std::optional<double> {
    if (!has(object) && object != "/") return std::nullopt;
    const auto found = find_attribute(file_, object, name);
    if (!found) return std::nullopt;
    const H5::Attribute& attribute = *found;
    if (attribute.getTypeClass() != H5T_FLOAT && attribute.getTypeClass() != H5T_INTEGER)
      throw InputError(path_ + ": attribute " + object + "@" + name + " is not a number");
    double value = 0.0;
    attribute.read(H5::PredType::NATIVE_DOUBLE, &value);
    return value;
  });
}

std::optional<std::int64_t> Hdf5Reader::integer_attribute(const std::string& object, const std::string& name) const {
  return reading(path_, "attribute " + object + "@" + name, [&]() -> std::optional<std::int64_t> {
    const auto found = find_attribute(file_, object, name);
    if (!found) return std::nullopt;
    const H5::Attribute& attribute = *found;
    if (attribute.getTypeClass() != H5T_INTEGER) throw InputError(path_ + ": attribute " + object + "@" + name + " is not an integer");
    std::int64_t value = 0;
    attribute.read(H5::PredType::NATIVE_INT64, &value);
    return value;
  });
}

void check_format_version(const Hdf5Reader& file, const std::string& path, std::int64_t supported) {
  if (file.string_attribute("/", "file_type").rfind("stengmc", 0) != 0) return;
  const auto version = file.integer_attribute("/", "format_version");
  if (!version) throw InputError(path + ": a stengmc file without an integer root attribute format_version (damaged?)");
  if (*version < 1)
    throw InputError(path + ": format_version " + std::to_string(*version) + " is not a valid version (>= 1); damaged file?");
  if (*version > supported)
    throw InputError(path + ": format_version " + std::to_string(*version) + " is newer than this stengmc reads (" +
                     std::to_string(supported) + "); update stengmc");
}

}  // namespace stengmc
