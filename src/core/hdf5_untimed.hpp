#pragma once
//! Creation property lists for HDF5 objects without timestamps. HDF5 records by default the
//! time each group and dataset was made and last changed in its object header (File Format
//! Specification, IV.A.2.r/s): two runs of one study then differ in a few hundred bytes,
//! so a checksum of a file cannot show it is the same result. Every object stengmc writes
//! is made with one of these lists; what a file is and when it was made it says in its
//! root attributes instead (io/run_file: created_utc).
#include <H5Cpp.h>

namespace stengmc {

//! The file's own list: its root group without timestamps.
const H5::FileCreatPropList& untimed_file();

//! For a group made with H5Gcreate2 (the C++ API of HDF5 1.10 takes no group list).
hid_t untimed_group();

//! For a contiguous dataset with HDF5's other defaults (shared by every such dataset).
const H5::DSetCreatPropList& untimed_dataset();

//! `layout` (a chunked, compressed one) without timestamps.
H5::DSetCreatPropList untimed(H5::DSetCreatPropList layout);

}  // namespace stengmc
