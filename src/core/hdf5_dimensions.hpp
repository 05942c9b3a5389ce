#pragma once
//! Named axes for HDF5 datasets, the netCDF-4 way: HDF5 dimension scales (H5DS, the
//! high-level library) plus CF `units` and `long_name` attributes, so netCDF readers
//! (xarray with h5netcdf, tested; netCDF-C and MATLAB read the same layout) open
//! stengmc's files as labelled arrays without knowing their layout (netCDF-4 format
//! specification, "Dimensions and dimension scales"; CF conventions 1.10, 3.1-3.2).
#include <hdf5.h>

#include <map>
#include <string>
#include <vector>

namespace stengmc {

//! What a dataset holds: its CF attributes and the name of each of its axes.
struct DatasetDescription {
  std::string units;                    //!< CF/UDUNITS-2 unit ("s", "V", "N/m"; "1": dimensionless); "": none written
  std::string long_name;                //!< what it is, in words
  std::vector<std::string> dimensions;  //!< one name per axis, outermost first ("a|b": see below)
  //! CF `comment` ("": none): what the unit cannot say, or, for a dataset with no single
  //! unit (units ""), the unit of each of its parts.
  std::string comment = {};
  //! The extent of a flat array written under this description, outermost first (an
  //! ensemble's statistics over a product grid: one axis per swept parameter); empty: the
  //! array's own. Its product must be the array's length.
  std::vector<std::size_t> shape = {};
};

//! A dataset of the file and its description.
struct DescribedDataset {
  std::string path;
  DatasetDescription description;
};

//! A dataset as its writer knows it without asking HDF5: its extent and, while the writer
//! holds it open, its identifier (H5I_INVALID_HID otherwise).
struct WrittenDataset {
  std::vector<hsize_t> extent;
  hid_t id = H5I_INVALID_HID;
};

//! Every dataset of a file, by path.
using WrittenDatasets = std::map<std::string, WrittenDataset>;

//! The long_name of an index coordinate made for a dimension, before the dimension's name
//! (readers that compare a file with its source tell these apart by it).
inline constexpr const char* INDEX_LONG_NAME = "index along dimension ";

//! Attaches the axes of every dataset to dimension scales. netCDF's scoping rule finds
//! the scale of dimension `d` for a dataset in group G: the dataset named `d` in G or in
//! its nearest ancestor group, which must itself be described as a coordinate (1-D, its
//! one dimension named `d`, the same length) and is made a scale; where there is none, an
//! index coordinate is made in G: a 1-D 64-bit integer dataset `d` holding 0 .. length-1,
//! units "1", long_name INDEX_LONG_NAME + `d`, so every dimension has a coordinate
//! (issue 25; netCDF's "pure" dimensions, a scale with no values, are no longer made:
//! xarray shows them without labels). A name "a|b" is dimension a
//! where a's scale has the axis's length, else b: the circuit's traces of a run whose
//! circuit stopped early span only the leading samples of /time. No written value is
//! touched.
//! Throws Error when a description contradicts the file (a wrong axis count or length, a
//! dimension name taken by a dataset that is not its coordinate).
//! `written` names every dataset of the file with its extent (the index coordinates made here
//! are added): the file is not searched, a dataset the writer holds open is used as it is,
//! and any other is opened once.
void attach_dimension_scales(hid_t file, const std::string& file_name, const std::vector<DescribedDataset>& datasets,
                             WrittenDatasets& written);

}  // namespace stengmc
