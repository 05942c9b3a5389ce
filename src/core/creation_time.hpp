#pragma once
//! When a file says it was made: its root attribute created_utc (docs/output-files.md).
#include <string>

namespace stengmc {

//! "YYYY-MM-DDTHH:MM:SSZ": the time in SOURCE_DATE_EPOCH when it is set (the
//! reproducible-builds convention, https://reproducible-builds.org/specs/source-date-epoch/),
//! so one study, seed and version give byte-identical files; the current time otherwise.
//! Throws InputError naming the variable when it is set but not a whole number of seconds
//! from 0 to 253402300799 (9999-12-31T23:59:59Z).
std::string creation_time_utc();

}  // namespace stengmc
