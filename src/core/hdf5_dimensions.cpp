#include "core/hdf5_dimensions.hpp"

#include <H5DSpublic.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <map>
#include <memory>
#include <set>

#include "core/error.hpp"
#include "core/hdf5_untimed.hpp"

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

//! Attaches scales knowing the file from its writer: which datasets exist and their
//! extents come from its record of them, the datasets it holds open are used as they are,
//! which datasets are scales is remembered, and any other dataset is opened once (asking
//! HDF5 instead cost a single run's file a fifth of its CPU time).
class ScaleAttacher {
 public:
  ScaleAttacher(hid_t file, std::string file_name, const std::vector<DescribedDataset>& datasets, WrittenDatasets& written)
      : file_(file), file_name_(std::move(file_name)), written_(written) {
    for (const DescribedDataset& d : datasets) described_[d.path] = &d.description;
  }

  //! Finds (or makes) the scale of each axis of `dataset`; the attributes that attach
  //! them are written by write_attachments().
  void attach(const DescribedDataset& dataset) {
    const std::vector<std::string>& dimensions = dataset.description.dimensions;
    const std::vector<hsize_t>& extent = extent_of(dataset.path);
    if (extent.size() != dimensions.size())
      fail(dataset.path + " has " + std::to_string(extent.size()) + " axes but its description names " +
           std::to_string(dimensions.size()));
    if (is_coordinate(dataset.path)) {
      make_scale(dataset.path);
      return;
    }
    std::vector<std::string>& scales = dimension_list_[dataset.path];
    for (std::size_t axis = 0; axis < dimensions.size(); ++axis) {
      const std::string scale_path = scale_for(parent_of(dataset.path), dimensions[axis], extent[axis]);
      if (length_of(scale_path) != extent[axis])
        fail("axis " + std::to_string(axis) + " of " + dataset.path + " (" + std::to_string(extent[axis]) +
             " long) does not match its dimension " + scale_path);
      make_scale(scale_path);
      scales.push_back(scale_path);
      reference_list_[scale_path].push_back({dataset.path, static_cast<int>(axis)});
    }
  }

  //! The attributes H5DSattach_scale writes, each written once: a dataset's
  //! DIMENSION_LIST (per axis, a variable-length list of object references to its scales)
  //! and a scale's REFERENCE_LIST (the datasets attached to it and their axes), in HDF5's
  //! own layout (HDF5 Dimension Scale Specification, sections 3-4; hl/src/H5DS.c). Calling
  //! H5DSattach_scale per axis instead re-reads, deletes and rewrites both lists at every
  //! attachment: a third of a single run's time spent writing its file.
  void write_attachments() {
    const Handle reference_type(H5Tvlen_create(H5T_STD_REF_OBJ), H5Tclose);
    for (const auto& [path, scales] : dimension_list_) {
      std::vector<hobj_ref_t> references(scales.size());
      std::vector<hvl_t> lists(scales.size());
      for (std::size_t axis = 0; axis < scales.size(); ++axis) {
        references[axis] = reference_to(scales[axis]);
        lists[axis] = {1, &references[axis]};
      }
      write_attribute(path, "DIMENSION_LIST", reference_type.get(), lists.size(), lists.data());
    }
    // H5DS's ds_list_t: the attached dataset and the index of its axis (a C int).
    struct Attached {
      hobj_ref_t dataset;
      int dimension;
    };
    const Handle attached_type(H5Tcreate(H5T_COMPOUND, sizeof(Attached)), H5Tclose);
    if (H5Tinsert(attached_type.get(), "dataset", offsetof(Attached, dataset), H5T_STD_REF_OBJ) < 0 ||
        H5Tinsert(attached_type.get(), "dimension", offsetof(Attached, dimension), H5T_NATIVE_INT) < 0)
      fail("cannot make the type of REFERENCE_LIST");
    for (const auto& [scale, attached] : reference_list_) {
      std::vector<Attached> list;
      for (const auto& [path, axis] : attached) list.push_back({reference_to(path), axis});
      write_attribute(scale, "REFERENCE_LIST", attached_type.get(), list.size(), list.data());
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(file_name_ + ": " + what); }

  //! A reference to the dataset at `path`, made from its open identifier (".": itself)
  //! rather than by walking the path from the root.
  hobj_ref_t reference_to(const std::string& path) {
    hobj_ref_t reference;
    if (H5Rcreate(&reference, open(path), ".", H5R_OBJECT, -1) < 0) fail("cannot refer to " + path);
    return reference;
  }

  //! A 1-D attribute of `count` elements of `type` on the dataset at `path`.
  void write_attribute(const std::string& path, const char* name, hid_t type, std::size_t count, const void* values) {
    const hsize_t dims[1] = {count};
    const Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
    const Handle attribute(H5Acreate2(open(path), name, type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    if (attribute.get() < 0 || H5Awrite(attribute.get(), type, values) < 0) fail("cannot write " + path + "@" + name);
  }

  //! The dataset at `path`: as its writer holds it, or opened on first use and closed with
  //! the attacher.
  hid_t open(const std::string& path) {
    if (const auto held = written_.find(path); held != written_.end() && held->second.id != H5I_INVALID_HID)
      return held->second.id;
    auto found = open_.find(path);
    if (found != open_.end()) return found->second->get();
    const hid_t id = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (id < 0) fail("cannot open dataset " + path);
    open_.emplace(path, std::make_unique<Handle>(id, H5Dclose));
    return id;
  }

  const std::vector<hsize_t>& extent_of(const std::string& path) const {
    const auto found = written_.find(path);
    if (found == written_.end()) fail("dataset " + path + " was not written");
    return found->second.extent;
  }

  //! The length of a 1-D dataset (0 for any other).
  hsize_t length_of(const std::string& path) const {
    const std::vector<hsize_t>& extent = extent_of(path);
    return extent.size() == 1 ? extent.front() : 0;
  }

  bool is_coordinate(const std::string& path) const {
    const auto found = described_.find(path);
    return found != described_.end() && names_itself(path, *found->second);
  }

  //! A dataset at `path` (not a group: /asperity/x's dimension "asperity" is no group).
  bool dataset_exists(const std::string& path) const { return written_.count(path) > 0; }

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
      if (!found.empty() && length_of(found) == length) return found;
      return scale_for(group, spec.substr(bar + 1), length);
    }
    if (!found.empty()) return found;
    return make_index(joined(group, name), name, length);
  }

  //! An index coordinate `name` at `made`: 0 .. length-1 (int64), units "1" and a long_name.
  std::string make_index(const std::string& made, const std::string& name, hsize_t length) {
    const hsize_t dims[1] = {length};
    const Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
    const hid_t scale = H5Dcreate2(file_, made.c_str(), H5T_STD_I64LE, space.get(), H5P_DEFAULT,
                                   untimed_dataset().getId(), H5P_DEFAULT);
    if (scale < 0) fail("cannot create the index coordinate " + made);
    open_.emplace(made, std::make_unique<Handle>(scale, H5Dclose));
    written_[made].extent = {length};
    std::vector<std::int64_t> index(length);
    std::iota(index.begin(), index.end(), std::int64_t{0});
    if (length > 0 && H5Dwrite(scale, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, index.data()) < 0)
      fail("cannot write the index coordinate " + made);
    write_text(scale, made, "units", "1");
    write_text(scale, made, "long_name", INDEX_LONG_NAME + name);
    if (H5DSset_scale(scale, name.c_str()) < 0) fail("cannot make " + made + " a dimension scale");
    scales_.insert(made);
    return made;
  }

  //! A scalar text attribute (variable-length, as the writer's own).
  void write_text(hid_t object, const std::string& path, const char* name, const std::string& value) {
    const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    if (H5Tset_size(type.get(), H5T_VARIABLE) < 0) fail("cannot make a text type");
    const Handle attribute(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    const char* text = value.c_str();
    if (attribute.get() < 0 || H5Awrite(attribute.get(), type.get(), &text) < 0) fail("cannot write " + path + "@" + name);
  }

  //! Makes the dataset at `path` a scale named after itself, once.
  void make_scale(const std::string& path) {
    if (scales_.count(path)) return;
    if (H5DSset_scale(open(path), base_name(path).c_str()) < 0) fail("cannot make " + base_name(path) + " a dimension scale");
    scales_.insert(path);
  }

  hid_t file_;
  std::string file_name_;
  WrittenDatasets& written_;
  std::map<std::string, const DatasetDescription*> described_;
  std::map<std::string, std::unique_ptr<Handle>> open_;
  std::set<std::string> scales_;
  //! The scale of each axis of each dataset, and the datasets (with the axis) of each scale,
  //! in the order of attachment.
  std::map<std::string, std::vector<std::string>> dimension_list_;
  std::map<std::string, std::vector<std::pair<std::string, int>>> reference_list_;
};

}  // namespace

void attach_dimension_scales(hid_t file, const std::string& file_name, const std::vector<DescribedDataset>& datasets,
                             WrittenDatasets& written) {
  ScaleAttacher attacher(file, file_name, datasets, written);
  // Coordinates first: a dataset's scale must be one before anything attaches to it.
  for (const DescribedDataset& d : datasets)
    if (names_itself(d.path, d.description)) attacher.attach(d);
  for (const DescribedDataset& d : datasets)
    if (!names_itself(d.path, d.description)) attacher.attach(d);
  attacher.write_attachments();
}

}  // namespace stengmc
