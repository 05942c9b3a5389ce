#pragma once
//! numpy arrays from the library's std::vectors. Each array owns its data (moved or copied
//! into it), so a result outlives the C++ objects it came from.
#include <pybind11/numpy.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace stengmc::python {

//! A 1-D array that takes the vector over without copying.
template <typename T>
pybind11::array_t<T> to_numpy(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  pybind11::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return pybind11::array_t<T>(static_cast<pybind11::ssize_t>(owned->size()), owned->data(), owner);
}

//! A 1-D copy.
template <typename T>
pybind11::array_t<T> to_numpy(const std::vector<T>& values) {
  return to_numpy(std::vector<T>(values));
}

//! Counts and indices (std::size_t in the library) as int64, the type the files hold.
inline pybind11::array_t<std::int64_t> to_numpy_int64(const std::vector<std::size_t>& values) {
  return to_numpy(std::vector<std::int64_t>(values.begin(), values.end()));
}

//! A rows x columns array from equal-length rows (row-major, as the HDF5 files store them).
inline pybind11::array_t<double> rows_to_numpy(const std::vector<std::vector<double>>& rows) {
  const std::size_t columns = rows.empty() ? 0 : rows.front().size();
  pybind11::array_t<double> out({static_cast<pybind11::ssize_t>(rows.size()), static_cast<pybind11::ssize_t>(columns)});
  double* data = out.mutable_data();
  for (const std::vector<double>& row : rows) {
    if (row.size() != columns) throw Error("internal: rows of unequal length for a 2-D array");
    data = std::copy(row.begin(), row.end(), data);
  }
  return out;
}

//! A numpy array (any float dtype, any layout) as a vector of doubles; `what` names it in
//! the message when it is not one-dimensional.
inline std::vector<double> from_numpy(const pybind11::array_t<double, pybind11::array::forcecast>& array,
                                      const std::string& what) {
  if (array.ndim() != 1)
    throw InputError(what + ": expected a one-dimensional array, got " + std::to_string(array.ndim()) + " dimensions");
  const auto view = array.unchecked<1>();
  std::vector<double> out(static_cast<std::size_t>(view.shape(0)));
  for (pybind11::ssize_t i = 0; i < view.shape(0); ++i) out[static_cast<std::size_t>(i)] = view(i);
  return out;
}

}  // namespace stengmc::python
