#include "core/hdf5_dimensions.hpp"

#include <H5DSpublic.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "core/error.hpp"

namespace stengmc {

namespace {

//! The group part of a dataset path ("/" for a dataset of the root).
std::string parent_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string base_name(const std::string& path) { return path.substr(path.rfind('/') + 1); }

//! A coordinate variable: 1-D, its one dimension named as itself (netCDF; CF 5).
bool names_itself(const std::string& path, const DatasetDescription& d) {
  return d.dimensions.size() == 1 && d.dimensions.front() == base_name(path);
}

std::string joined(const std::string& group, const std::string& name) { return (group == "/" ? "" : group) + "/" + name; }

//! An HDF5 identifier closed when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  [[nodiscard]] hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

class ScaleAttacher {
 public:
  ScaleAttacher(hid_t file, std::string file_name, const std::vector<DescribedDataset>& datasets)
      : file_(file), file_name_(std::move(file_name)) {
    for (const DescribedDataset& d : datasets) described_[d.path] = &d.description;
  }

  void attach(const DescribedDataset& dataset) {
    const std::vector<std::string>& dimensions = dataset.description.dimensions;
    const Handle data(open(dataset.path), H5Dclose);
    const std::vector<hsize_t> extent = extent_of(data.get());
    if (extent.size() != dimensions.size())
      fail(dataset.path + " has " + std::to_string(extent.size()) + " axes but its description names " +
           std::to_string(dimensions.size()));
    if (is_coordinate(dataset.path)) {
      make_scale(data.get(), base_name(dataset.path));
      return;
    }
    for (std::size_t axis = 0; axis < dimensions.size(); ++axis) {
      const std::string scale_path = scale_for(parent_of(dataset.path), dimensions[axis], extent[axis]);
      const Handle scale(open(scale_path), H5Dclose);
      if (length_of(scale.get()) != extent[axis])
        fail("axis " + std::to_string(axis) + " of " + dataset.path + " (" + std::to_string(extent[axis]) +
             " long) does not match its dimension " + scale_path);
      make_scale(scale.get(), base_name(scale_path));
      if (H5DSattach_scale(data.get(), scale.get(), static_cast<unsigned>(axis)) < 0)
        fail("cannot attach dimension " + scale_path + " to " + dataset.path);
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(file_name_ + ": " + what); }

  hid_t open(const std::string& path) const {
    const hid_t id = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (id < 0) fail("cannot open dataset " + path);
    return id;
  }

  static std::vector<hsize_t> extent_of(hid_t dataset) {
    const Handle space(H5Dget_space(dataset), H5Sclose);
    std::vector<hsize_t> extent(static_cast<std::size_t>(std::max(0, H5Sget_simple_extent_ndims(space.get()))));
    H5Sget_simple_extent_dims(space.get(), extent.data(), nullptr);
    return extent;
  }

  //! The length of a 1-D dataset (0 for any other).
  static hsize_t length_of(hid_t dataset) {
    const std::vector<hsize_t> extent = extent_of(dataset);
    return extent.size() == 1 ? extent.front() : 0;
  }

  bool is_coordinate(const std::string& path) const {
    const auto found = described_.find(path);
    return found != described_.end() && names_itself(path, *found->second);
  }

  //! A dataset at `path` (not a group: /asperity/x's dimension "asperity" is no group).
  bool dataset_exists(const std::string& path) const {
    // Walk the path: H5Lexists fails on a missing intermediate group.
    std::size_t start = 1;
    while (true) {
      const std::size_t slash = path.find('/', start);
      if (H5Lexists(file_, path.substr(0, slash).c_str(), H5P_DEFAULT) <= 0) return false;
      if (slash == std::string::npos) break;
      start = slash + 1;
    }
    H5O_info_t info;
    return H5Oget_info_by_name(file_, path.c_str(), &info, H5P_DEFAULT) >= 0 && info.type == H5O_TYPE_DATASET;
  }

  //! The dataset named `name` seen from `group` (netCDF's scoping), or "".
  std::string visible(const std::string& group, const std::string& name) const {
    for (std::string g = group;; g = parent_of(g)) {
      const std::string candidate = joined(g, name);
      if (dataset_exists(candidate)) {
        if (described_.count(candidate) && !is_coordinate(candidate))
          fail("dimension \"" + name + "\" of a dataset in " + group + " would be " + candidate +
               ", which is not its coordinate (rename the dimension)");
        return candidate;
      }
      if (g == "/") return "";
    }
  }

  //! The scale of dimension `spec` for an axis of `length` in `group`, made if absent.
  //! "a|b": dimension a where its scale is `length` long, else b (a leading part of a).
  std::string scale_for(const std::string& group, const std::string& spec, hsize_t length) {
    const std::size_t bar = spec.find('|');
    const std::string name = spec.substr(0, bar);
    const std::string found = visible(group, name);
    if (bar != std::string::npos) {
      if (!found.empty()) {
        const Handle scale(open(found), H5Dclose);
        if (length_of(scale.get()) == length) return found;
      }
      return scale_for(group, spec.substr(bar + 1), length);
    }
    if (!found.empty()) return found;
    const std::string made = joined(group, name);
    const hsize_t dims[1] = {length};
    const Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
    // netCDF-C's pure dimensions are 32-bit floats never written (no storage allocated).
    const Handle scale(H5Dcreate2(file_, made.c_str(), H5T_IEEE_F32BE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       H5Dclose);
    if (scale.get() < 0) fail("cannot create dimension " + made);
    char marker[96];
    std::snprintf(marker, sizeof marker, "This is a netCDF dimension but not a netCDF variable.%10llu",
                  static_cast<unsigned long long>(length));
    if (H5DSset_scale(scale.get(), marker) < 0) fail("cannot make " + made + " a dimension scale");
    return made;
  }

  void make_scale(hid_t dataset, const std::string& name) const {
    const htri_t scale = H5DSis_scale(dataset);
    if (scale < 0 || (scale == 0 && H5DSset_scale(dataset, name.c_str()) < 0))
      fail("cannot make " + name + " a dimension scale");
  }

  hid_t file_;
  std::string file_name_;
  std::map<std::string, const DatasetDescription*> described_;
};

}  // namespace

void attach_dimension_scales(hid_t file, const std::string& file_name, const std::vector<DescribedDataset>& datasets) {
  ScaleAttacher attacher(file, file_name, datasets);
  // Coordinates first: a dataset's scale must be one before anything attaches to it.
  for (const DescribedDataset& d : datasets)
    if (names_itself(d.path, d.description)) attacher.attach(d);
  for (const DescribedDataset& d : datasets)
    if (!names_itself(d.path, d.description)) attacher.attach(d);
}

}  // namespace stengmc
