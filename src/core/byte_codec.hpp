#pragma once
//! Values as bytes and back: fixed-width little-endian integers, doubles as their IEEE-754
//! bit pattern (std::bit_cast), text and vectors with their length first. Portable between
//! machines and bitwise exact: the journal's record format (ensemble/journal.hpp), and what a
//! child process that read a file hands back to its parent (io/guarded_read.hpp).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace stengmc {

//! Appends fixed-width little-endian values to a byte string.
class ByteEncoder {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) u8(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void text(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes_.append(s);
  }
  void doubles(std::span<const double> values) {
    for (double v : values) f64(v);
  }
  void vector(const std::vector<double>& values) {
    u64(values.size());
    doubles(values);
  }
  void rows(const std::vector<std::vector<double>>& rows) {
    u64(rows.size());
    for (const auto& row : rows) vector(row);
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

//! Reads what a ByteEncoder wrote; each read returns false (and reads nothing it cannot
//! hold: a count is checked against the bytes left before anything is allocated) when the
//! bytes run out, so a caller can say what is malformed.
class ByteDecoder {
 public:
  explicit ByteDecoder(std::string_view bytes) : bytes_(bytes) {}
  bool u8(std::uint8_t& v) {
    if (left() < 1) return false;
    v = static_cast<std::uint8_t>(bytes_[position_++]);
    return true;
  }
  bool u32(std::uint32_t& v) {
    std::uint64_t wide = 0;
    if (!little_endian(4, wide)) return false;
    v = static_cast<std::uint32_t>(wide);
    return true;
  }
  bool u64(std::uint64_t& v) { return little_endian(8, v); }
  bool text(std::string& s) {
    std::uint32_t n = 0;
    if (!u32(n) || left() < n) return false;
    s.assign(bytes_.substr(position_, n));
    position_ += n;
    return true;
  }
  bool doubles(std::size_t n, double* out) {
    if (left() / 8 < n) return false;  // before allocating anything of size n
    for (std::size_t i = 0; i < n; ++i) {
      std::uint64_t bits = 0;
      little_endian(8, bits);
      out[i] = std::bit_cast<double>(bits);
    }
    return true;
  }
  bool vector(std::vector<double>& values) {
    std::uint64_t n = 0;
    if (!u64(n) || left() / 8 < n) return false;
    values.resize(n);
    return doubles(n, values.data());
  }
  bool rows(std::vector<std::vector<double>>& rows) {
    std::uint64_t n = 0;
    if (!u64(n) || left() / 8 < n) return false;  // each row holds at least its length
    rows.resize(n);
    for (auto& row : rows)
      if (!vector(row)) return false;
    return true;
  }
  [[nodiscard]] std::size_t left() const { return bytes_.size() - position_; }

 private:
  bool little_endian(std::size_t width, std::uint64_t& v) {
    if (left() < width) return false;
    v = 0;
    for (std::size_t i = 0; i < width; ++i)
      v |= std::uint64_t{static_cast<unsigned char>(bytes_[position_ + i])} << (8 * i);
    position_ += width;
    return true;
  }

  std::string_view bytes_;
  std::size_t position_ = 0;
};

}  // namespace stengmc
