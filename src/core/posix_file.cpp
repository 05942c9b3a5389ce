#include "core/posix_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>

#include "core/error.hpp"

namespace stengmc {

bool write_all(int fd, std::uint64_t offset, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::pwrite(fd, bytes.data(), bytes.size(), static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
    offset += static_cast<std::uint64_t>(n);
  }
  return true;
}

void write_file_durably(const std::string& path, std::string_view bytes, const std::string& name,
                        const std::string& what) {
  const auto fail = [&](const std::string& action, int error) {
    throw Error(name + ": " + action + ": " + std::generic_category().message(error));
  };
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) fail("cannot create " + what, errno);
  // fsync before the caller renames: otherwise a power cut can leave the final name on an
  // empty file (ext4's delayed allocation).
  if (!write_all(fd, 0, bytes) || ::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    fail("cannot write " + what, error);
  }
  if (::close(fd) != 0) fail("cannot write " + what, errno);  // NFS reports late
}

void sync_directory_of(const std::string& path) {
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace stengmc
