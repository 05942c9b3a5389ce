#include "core/creation_time.hpp"

#include <charconv>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <string_view>

#include "core/error.hpp"

namespace stengmc {

namespace {

//! The last second a four-digit year can name. GCC's limit for the same variable: above it
//! the text would no longer be the fixed-width ISO 8601 every reader of created_utc expects.
constexpr long long LAST_SECOND = 253402300799;

//! The variable's seconds. The convention asks for the output of `date +%s`: decimal digits,
//! no sign, no fraction, no spaces; anything else is an error, not a guess, because a
//! silently ignored value would give files that only look reproducible.
std::time_t epoch_seconds(std::string_view text) {
  long long seconds = -1;
  const auto [end, failure] = std::from_chars(text.data(), text.data() + text.size(), seconds);
  const bool digits_only = !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
  if (!digits_only || failure != std::errc() || end != text.data() + text.size() || seconds > LAST_SECOND)
    throw InputError("environment variable SOURCE_DATE_EPOCH = \"" + std::string(text) +
                     "\": expected a whole number of seconds since 1970-01-01T00:00:00Z, from 0 to " +
                     std::to_string(LAST_SECOND) + " (as `date +%s` prints; it becomes the files' created_utc), "
                     "or the variable unset for the current time");
  return static_cast<std::time_t>(seconds);
}

}  // namespace

std::string creation_time_utc() {
  const char* fixed = std::getenv("SOURCE_DATE_EPOCH");
  const std::time_t when =
      fixed != nullptr ? epoch_seconds(fixed) : std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm parts{};
  gmtime_r(&when, &parts);  // not std::gmtime: its shared result would race with another thread's
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
  return text;
}

}  // namespace stengmc
