#include "io/hdf5_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.hpp"

namespace stengmc {

namespace {

const H5::StrType& string_type() {
  static const H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  return type;
}

void check_finite(const std::string& path, std::span<const double> values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw Error("refusing to write a non-finite value into " + path + " (element " + std::to_string(i) +
                  "): this is a bug, please report it with the study file");
}

}  // namespace

// ---------------------------------------------------------------- Hdf5Writer

Hdf5Writer::Hdf5Writer(std::string path) : path_(std::move(path)), temporary_path_(path_ + ".tmp") {
  H5::Exception::dontPrint();
  const auto parent = std::filesystem::path(path_).parent_path();
  std::error_code ignored;
  if (!parent.empty()) std::filesystem::create_directories(parent, ignored);
  try {
    file_ = H5::H5File(temporary_path_, H5F_ACC_TRUNC);
  } catch (const H5::Exception&) {
    throw Error(temporary_path_ + ": cannot create the output file (does the folder exist and is it writable?)");
  }
}

Hdf5Writer::~Hdf5Writer() {
  if (committed_) return;
  try {
    file_.close();
  } catch (...) {
  }
  std::remove(temporary_path_.c_str());
}

H5::Group Hdf5Writer::group_for(const std::string& dataset_path) {
  H5::Group group = file_.openGroup("/");
  std::size_t start = 1;
  for (std::size_t slash = dataset_path.find('/', start); slash != std::string::npos;
       slash = dataset_path.find('/', start)) {
    const std::string name = dataset_path.substr(start, slash - start);
    group = group.nameExists(name) ? group.openGroup(name) : group.createGroup(name);
    start = slash + 1;
  }
  return group;
}

void Hdf5Writer::set_units(H5::DataSet& dataset, std::string_view units) {
  H5::Attribute attribute = dataset.createAttribute("units", string_type(), H5::DataSpace(H5S_SCALAR));
  attribute.write(string_type(), std::string(units));
}

void Hdf5Writer::write(const std::string& path, std::span<const double> values, std::string_view units) {
  check_finite(path, values);
  const hsize_t dims[1] = {values.size()};
  group_for(path);
  H5::DataSet dataset = file_.createDataSet(path, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(1, dims));
  if (!values.empty()) dataset.write(values.data(), H5::PredType::NATIVE_DOUBLE);
  set_units(dataset, units);
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::vector<double>>& rows, std::string_view units) {
  const std::size_t columns = rows.empty() ? 0 : rows.front().size();
  std::vector<double> flat;
  flat.reserve(rows.size() * columns);
  for (const auto& row : rows) {
    if (row.size() != columns) throw Error(path + ": rows of different lengths");
    flat.insert(flat.end(), row.begin(), row.end());
  }
  check_finite(path, flat);
  const hsize_t dims[2] = {rows.size(), columns};
  group_for(path);
  H5::DataSet dataset = file_.createDataSet(path, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(2, dims));
  if (!flat.empty()) dataset.write(flat.data(), H5::PredType::NATIVE_DOUBLE);
  set_units(dataset, units);
}

void Hdf5Writer::write(const std::string& path, std::span<const std::int64_t> values, std::string_view units) {
  const hsize_t dims[1] = {values.size()};
  group_for(path);
  H5::DataSet dataset = file_.createDataSet(path, H5::PredType::NATIVE_INT64, H5::DataSpace(1, dims));
  if (!values.empty()) dataset.write(values.data(), H5::PredType::NATIVE_INT64);
  set_units(dataset, units);
}

void Hdf5Writer::write(const std::string& path, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const auto& v : values) pointers.push_back(v.c_str());
  const hsize_t dims[1] = {values.size()};
  group_for(path);
  H5::DataSet dataset = file_.createDataSet(path, string_type(), H5::DataSpace(1, dims));
  if (!values.empty()) dataset.write(pointers.data(), string_type());
}

void Hdf5Writer::attribute(const std::string& object, const std::string& name, std::string_view value) {
  H5::Group group = file_.openGroup(object);
  H5::Attribute attribute = group.createAttribute(name, string_type(), H5::DataSpace(H5S_SCALAR));
  attribute.write(string_type(), std::string(value));
}

void Hdf5Writer::group(const std::string& path) { group_for(path + "/"); }

void Hdf5Writer::attribute(const std::string& object, const std::string& name, double value) {
  if (!std::isfinite(value)) throw Error("refusing to write a non-finite attribute " + object + "@" + name);
  H5::Group group = file_.openGroup(object);
  H5::Attribute attribute = group.createAttribute(name, H5::PredType::NATIVE_DOUBLE, H5::DataSpace(H5S_SCALAR));
  attribute.write(H5::PredType::NATIVE_DOUBLE, &value);
}

void Hdf5Writer::attribute(const std::string& object, const std::string& name, std::int64_t value) {
  H5::Group group = file_.openGroup(object);
  H5::Attribute attribute = group.createAttribute(name, H5::PredType::NATIVE_INT64, H5::DataSpace(H5S_SCALAR));
  attribute.write(H5::PredType::NATIVE_INT64, &value);
}

void Hdf5Writer::commit() {
  file_.close();
  std::error_code error;
  std::filesystem::rename(temporary_path_, path_, error);
  if (error) throw Error(path_ + ": cannot move the finished output into place: " + error.message());
  committed_ = true;
}

// ---------------------------------------------------------------- Hdf5Reader

Hdf5Reader::Hdf5Reader(std::string path) : path_(std::move(path)) {
  H5::Exception::dontPrint();
  if (!std::filesystem::exists(path_)) throw InputError(path_ + ": no such file");
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

std::vector<double> Hdf5Reader::vector(const std::string& path) const {
  if (!has(path)) throw InputError(path_ + ": dataset " + path + " is missing");
  H5::DataSet dataset = file_.openDataSet(path);
  H5::DataSpace space = dataset.getSpace();
  if (space.getSimpleExtentNdims() != 1) throw InputError(path_ + ": dataset " + path + " must be one-dimensional");
  hsize_t dims[1] = {0};
  space.getSimpleExtentDims(dims);
  const H5T_class_t type = dataset.getTypeClass();
  if (type != H5T_FLOAT && type != H5T_INTEGER) throw InputError(path_ + ": dataset " + path + " must hold numbers");
  std::vector<double> values(dims[0]);
  if (!values.empty()) dataset.read(values.data(), H5::PredType::NATIVE_DOUBLE);
  return values;
}

std::vector<std::vector<double>> Hdf5Reader::matrix(const std::string& path) const {
  if (!has(path)) throw InputError(path_ + ": dataset " + path + " is missing");
  H5::DataSet dataset = file_.openDataSet(path);
  H5::DataSpace space = dataset.getSpace();
  if (space.getSimpleExtentNdims() != 2)
    throw InputError(path_ + ": dataset " + path + " must be two-dimensional (asperities x samples)");
  if (dataset.getTypeClass() != H5T_FLOAT && dataset.getTypeClass() != H5T_INTEGER)
    throw InputError(path_ + ": dataset " + path + " must hold numbers");
  hsize_t dims[2] = {0, 0};
  space.getSimpleExtentDims(dims);
  std::vector<double> flat(dims[0] * dims[1]);
  if (!flat.empty()) dataset.read(flat.data(), H5::PredType::NATIVE_DOUBLE);
  std::vector<std::vector<double>> rows(dims[0]);
  for (hsize_t i = 0; i < dims[0]; ++i)
    rows[i].assign(flat.begin() + static_cast<std::ptrdiff_t>(i * dims[1]), flat.begin() + static_cast<std::ptrdiff_t>((i + 1) * dims[1]));
  return rows;
}

std::string Hdf5Reader::string_attribute(const std::string& object, const std::string& name) const {
  H5::Group group = file_.openGroup(object);
  if (!group.attrExists(name)) return "";
  H5::Attribute attribute = group.openAttribute(name);
  std::string value;
  attribute.read(attribute.getStrType(), value);
  return value;
}

}  // namespace stengmc
