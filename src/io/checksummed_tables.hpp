#pragma once
//! Tables (datasets) and numeric attributes that carry their checksum, so a reader can tell
//! a damaged file from a good one: HDF5 itself checks none of its raw data, and one flipped
//! byte in a table of numbers reads back as another number (a calibration bank moved two
//! estimated lines that way, silently). The checksum is the journals' 64-bit FNV-1a
//! (core/checksum.hpp) of the values' IEEE-754 bit patterns, in the order they are stored
//! (row after row), stored as 16 hex digits:
//!   a table:       attribute `checksum_fnv1a64` of the dataset (integer tables: of the values
//!                  as doubles, as a reader reads them; they are counts and offsets < 2^53);
//!   attributes:    attribute `attributes_checksum_fnv1a64` of their group, over the values
//!                  of the named numeric attributes in the order the format lists them.
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"

namespace stengmc {

//! Writes a table and its checksum.
void write_checked(Hdf5Writer& file, const std::string& path, std::span<const double> values);
void write_checked(Hdf5Writer& file, const std::string& path, const std::vector<std::vector<double>>& rows);
void write_checked(Hdf5Writer& file, const std::string& path, std::span<const std::int64_t> values);

//! A numeric attribute of a group, written as an integer or a double.
struct NumberAttribute {
  std::string name;
  double value = 0.0;
  bool integer = false;  //!< written as int64 (a count or an index; exact as a double)
};

//! Writes the attributes of `object` and the checksum of their values in the given order.
void write_checked_attributes(Hdf5Writer& file, const std::string& object, const std::vector<NumberAttribute>& attributes);

//! How a reader of checksummed tables names the file and says what to do about damage.
struct ChecksumReader {
  const Hdf5Reader& file;
  std::string path;    //!< the file, for messages
  std::string kind;    //!< what the file is ("the calibration bank")
  std::string advice;  //!< what to do about a damaged file ("make the bank again with stengmc calibrate")

  //! "<path>: <kind> is damaged (<what>); <advice>".
  static InputError damaged(const std::string& path, const std::string& kind, const std::string& what,
                            const std::string& advice);
  [[nodiscard]] InputError damaged(const std::string& what) const { return damaged(path, kind, what, advice); }

  //! A 1-D or 2-D table's values; InputError naming the file and the table when its
  //! checksum is missing or does not hold.
  [[nodiscard]] std::vector<double> vector(const std::string& table) const;
  [[nodiscard]] std::vector<std::vector<double>> matrix(const std::string& table) const;
  //! The named numeric attributes of `object`, by name; InputError when one is missing or
  //! their checksum does not hold.
  [[nodiscard]] std::map<std::string, double> attributes(const std::string& object,
                                                         const std::vector<std::string>& names) const;

 private:
  void check(const std::string& table, std::span<const double> values) const;
};

}  // namespace stengmc
