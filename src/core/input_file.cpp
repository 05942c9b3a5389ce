#include "core/input_file.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "core/error.hpp"

namespace stengmc {

std::string describe_file_type(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory: return "a folder";
    case std::filesystem::file_type::character: return "a character device";
    case std::filesystem::file_type::block: return "a block device";
    case std::filesystem::file_type::fifo: return "a FIFO";
    case std::filesystem::file_type::socket: return "a socket";
    case std::filesystem::file_type::symlink: return "a symbolic link";
    default: return "not a regular file";
  }
}

std::uint64_t check_input_file(const std::string& path, const std::string& what) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || status.type() == std::filesystem::file_type::not_found)
    throw InputError(path + ": cannot open " + what + " for reading: no such file");
  if (status.type() != std::filesystem::file_type::regular)
    throw InputError(path + " is not a regular file (" + describe_file_type(status.type()) + "); " + what +
                     " must be a regular file");
  const auto size = std::filesystem::file_size(path, error);
  if (error) throw InputError(path + ": cannot read " + what + ": " + error.message());
  return size;
}

std::string read_text_file(const std::string& path, const std::string& what, std::uint64_t max_bytes) {
  const std::uint64_t size = check_input_file(path, what);
  if (size > max_bytes)
    throw InputError(path + ": " + what + " is " + std::to_string(size) + " bytes, more than the " +
                     std::to_string(max_bytes) + " such a file can reasonably be; is it the right file?");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what + " for reading");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::ifstream open_input_file(const std::string& path, const std::string& what) {
  check_input_file(path, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what + " for reading");
  return in;
}

std::string trim_blanks(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  const auto last = text.find_last_not_of(" \t\r");
  return first == std::string_view::npos ? std::string() : std::string(text.substr(first, last - first + 1));
}

std::optional<double> parse_number(std::string_view text, std::string* why) {
  const auto fail = [&](const char* reason) -> std::optional<double> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return fail("is not a number");
  double value = 0.0;
  // from_chars: locale-independent (strtod is not), and it returns subnormals as numbers
  // where std::stod throws out_of_range for them.
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) return fail("is beyond the range of a double");
  if (ec != std::errc() || end != text.data() + text.size()) return fail("is not a number");
  if (!std::isfinite(value)) return fail("is not finite");
  return value;
}

}  // namespace stengmc
