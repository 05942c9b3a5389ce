#pragma once
//! The few POSIX file operations whose failures must be reported exactly (errno kept):
//! writing all of a buffer, and making a new directory entry durable.
#include <cstdint>
#include <string>
#include <string_view>

namespace stengmc {

//! Writes all of `bytes` at `offset`, retrying short writes and interruptions; false with
//! errno set on failure (a full disk: ENOSPC after a short write).
bool write_all(int fd, std::uint64_t offset, std::string_view bytes);

//! Writes `bytes` as the whole new file `path` (created or truncated) and fsyncs it; throws
//! Error "<name>: cannot write <what>: <system reason>" on failure, removing nothing (the
//! caller owns the name; TemporaryFile removes it).
void write_file_durably(const std::string& path, std::string_view bytes, const std::string& name,
                        const std::string& what = "the output file");

//! fsyncs the folder holding `path`, so a file created or renamed there survives a power
//! cut. Best effort: a filesystem that cannot sync a folder only loses the entry.
void sync_directory_of(const std::string& path);

}  // namespace stengmc
