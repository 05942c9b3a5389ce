#include "core/hdf5_untimed.hpp"

namespace stengmc {

namespace {

//! H5Pset_obj_track_times applies to any object creation list: files (their root group),
//! groups and datasets alike.
template <class List>
List without_times(List list) {
  if (H5Pset_obj_track_times(list.getId(), false) < 0)
    throw H5::PropListIException("H5Pset_obj_track_times", "cannot turn off object timestamps");
  return list;
}

}  // namespace

// Made once, on first use, and kept for the life of the program: HDF5 copies a creation
// list into each object it makes, so one list serves every file.
const H5::FileCreatPropList& untimed_file() {
  static const H5::FileCreatPropList list = without_times(H5::FileCreatPropList());
  return list;
}

hid_t untimed_group() {
  static const H5::PropList list = without_times(H5::PropList(H5P_GROUP_CREATE));
  return list.getId();
}

const H5::DSetCreatPropList& untimed_dataset() {
  static const H5::DSetCreatPropList list = without_times(H5::DSetCreatPropList());
  return list;
}

H5::DSetCreatPropList untimed(H5::DSetCreatPropList layout) { return without_times(std::move(layout)); }

}  // namespace stengmc
