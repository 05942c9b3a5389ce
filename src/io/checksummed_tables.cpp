#include "io/checksummed_tables.hpp"

#include <charconv>
#include <optional>

#include "core/checksum.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

constexpr const char* TABLE_CHECKSUM = "checksum_fnv1a64";
constexpr const char* ATTRIBUTES_CHECKSUM = "attributes_checksum_fnv1a64";

std::vector<double> flat_of(const std::vector<std::vector<double>>& rows) {
  std::vector<double> flat;
  for (const auto& row : rows) flat.insert(flat.end(), row.begin(), row.end());
  return flat;
}

//! The checksum stored as `object@name`, or nothing when it is absent or not 16 hex digits.
std::optional<std::uint64_t> stored_checksum(const Hdf5Reader& file, const std::string& object, const char* name) {
  const std::string text = file.string_attribute(object, name);
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value, 16);
  if (text.size() != 16 || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

void write_checked(Hdf5Writer& file, const std::string& path, std::span<const double> values) {
  file.write(path, values);
  file.attribute(path, TABLE_CHECKSUM, checksum_text(fnv1a64_of_values(values)));
}

void write_checked(Hdf5Writer& file, const std::string& path, const std::vector<std::vector<double>>& rows) {
  file.write(path, rows);
  file.attribute(path, TABLE_CHECKSUM, checksum_text(fnv1a64_of_values(flat_of(rows))));
}

void write_checked(Hdf5Writer& file, const std::string& path, std::span<const std::int64_t> values) {
  file.write(path, values);
  const std::vector<double> as_read(values.begin(), values.end());  // what a reader's vector() returns
  file.attribute(path, TABLE_CHECKSUM, checksum_text(fnv1a64_of_values(as_read)));
}

void write_checked_attributes(Hdf5Writer& file, const std::string& object, const std::vector<NumberAttribute>& attributes) {
  std::vector<double> values;
  for (const NumberAttribute& a : attributes) {
    if (a.integer) file.attribute(object, a.name, static_cast<std::int64_t>(a.value));
    else file.attribute(object, a.name, a.value);
    values.push_back(a.value);
  }
  file.attribute(object, ATTRIBUTES_CHECKSUM, checksum_text(fnv1a64_of_values(values)));
}

InputError ChecksumReader::damaged(const std::string& path, const std::string& kind, const std::string& what,
                                   const std::string& advice) {
  return InputError(path + ": " + kind + " is damaged (" + what + "); " + advice);
}

std::vector<double> ChecksumReader::vector(const std::string& table) const {
  std::vector<double> values = file.vector(table);
  check(table, values);
  return values;
}

std::vector<std::vector<double>> ChecksumReader::matrix(const std::string& table) const {
  std::vector<std::vector<double>> rows = file.matrix(table);
  check(table, flat_of(rows));
  return rows;
}

std::map<std::string, double> ChecksumReader::attributes(const std::string& object,
                                                         const std::vector<std::string>& names) const {
  std::map<std::string, double> found;
  std::vector<double> values;
  for (const std::string& name : names) {
    const auto value = file.number_attribute(object, name);
    if (!value)
      throw InputError(path + ": attribute " + object + "@" + name + " is missing: the file is damaged; " + advice);
    found[name] = *value;
    values.push_back(*value);
  }
  const auto stored = stored_checksum(file, object, ATTRIBUTES_CHECKSUM);
  const std::uint64_t actual = fnv1a64_of_values(values);
  if (!stored)
    throw InputError(path + ": the attributes of " + object + " carry no checksum (" + object + "@" + ATTRIBUTES_CHECKSUM +
                     "): the file is damaged; " + advice);
  if (*stored != actual)
    throw InputError(path + ": the attributes of " + object + " are damaged (checksum " + checksum_text(actual) +
                     ", written as " + checksum_text(*stored) + "); " + advice);
  return found;
}

void ChecksumReader::check(const std::string& table, std::span<const double> values) const {
  const auto stored = stored_checksum(file, table, TABLE_CHECKSUM);
  const std::uint64_t actual = fnv1a64_of_values(values);
  if (!stored)
    throw InputError(path + ": table " + table + " carries no checksum (" + table + "@" + TABLE_CHECKSUM +
                     "): the file is damaged; " + advice);
  if (*stored != actual)
    throw InputError(path + ": table " + table + " is damaged (checksum " + checksum_text(actual) + ", written as " +
                     checksum_text(*stored) + "); " + advice);
}

}  // namespace stengmc
