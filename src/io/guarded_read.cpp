#include "io/guarded_read.hpp"

#include <H5Cpp.h>
#include <fcntl.h>
#include <malloc.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/byte_codec.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

//! What a child process wrote to its pipe, and how it ended (waitpid's status).
struct ChildOutcome {
  std::string bytes;
  int status = 0;
};

//! Writes all of `bytes` to the pipe `fd`, retrying short writes; gives up silently (the
//! parent then sees a short or empty result and says so).
void write_to_pipe(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

//! Runs `work` in a child process and collects the bytes it returns, through a pipe read
//! while the child runs (a result of megabytes would fill the pipe). The child is killed
//! after 10 s + 1 s per 20 MB of the file (InputError naming `path`). Nothing when no child
//! can be made (a process limit): the caller then works in this process, as before.
std::optional<ChildOutcome> run_in_child(const std::string& path, const std::function<std::string()>& work) {
  std::error_code ignored;
  const auto size = std::filesystem::file_size(path, ignored);
  const double timeout_s = 10.0 + static_cast<double>(ignored ? 0 : size) / 20e6;
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) return std::nullopt;
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(ends[0]);
    ::close(ends[1]);
    return std::nullopt;
  }
  if (child == 0) {
    ::close(ends[0]);
    const std::string bytes = work();
    // A damaged file can make HDF5 write past a buffer without crashing at once (the bank
    // fuzz found a corrupt global heap doing so): glibc then aborts at some later free. So
    // the child has malloc walk and consolidate its free chunks before it answers, where
    // such damage is often caught (an abort: refused). (H5close as well, to free what HDF5
    // holds, made each guarded read ~40 ms slower - the fuzz of run files 13x.)
    ::malloc_trim(0);
    write_to_pipe(ends[1], bytes);
    ::_exit(0);  // no atexit handlers: the parent's files and libraries are not the child's to close
  }
  ::close(ends[1]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  ChildOutcome outcome;
  for (;;) {  // until end of file: the child has answered, or died
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      ::kill(child, SIGKILL);
      ::waitpid(child, nullptr, 0);
      ::close(ends[0]);
      throw InputError(path + ": the HDF5 library did not finish reading this file in " + std::to_string(int(timeout_s)) +
                       " s; it is damaged (or not what it claims to be)");
    }
    pollfd readable{ends[0], POLLIN, 0};
    const int ready = ::poll(&readable, 1, static_cast<int>(std::min<std::int64_t>(left.count(), 1000)));
    if (ready <= 0) continue;  // a signal, or no data yet
    char buffer[1 << 16];
    const ssize_t n = ::read(ends[0], buffer, sizeof buffer);
    if (n > 0) outcome.bytes.append(buffer, static_cast<std::size_t>(n));
    else if (n == 0 || errno != EINTR) break;
  }
  ::close(ends[0]);
  while (::waitpid(child, &outcome.status, 0) < 0)
    if (errno != EINTR) return std::nullopt;  // SIGCHLD ignored by someone: no status to judge by
  return outcome;
}

//! Refuses the file when the child that read it died of a signal (or did not exit 0).
void refuse_if_crashed(const std::string& path, int status) {
  if (WIFSIGNALED(status))
    throw InputError(path + ": the HDF5 library crashed reading this file (" + strsignal(WTERMSIG(status)) +
                     "); it is damaged (or not what it claims to be)");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw InputError(path + ": the process reading this file failed (exit status " + std::to_string(WEXITSTATUS(status)) +
                     "); it is damaged (or not what it claims to be)");
}

// How the child's answer starts: its read returned, or threw.
constexpr std::uint8_t RETURNED = 0, THREW_INPUT_ERROR = 1, THREW_ERROR = 2;

}  // namespace

void read_in_child_first(const std::string& path, const std::function<void()>& read) {
  const auto outcome = run_in_child(path, [&] {
    try {
      read();
    } catch (...) {  // the parent's own read meets the same error and reports it
    }
    return std::string();
  });
  if (outcome) refuse_if_crashed(path, outcome->status);
}

std::string read_in_child(const std::string& path, const std::function<std::string()>& read) {
  const auto outcome = run_in_child(path, [&] {
    ByteEncoder answer;
    try {
      std::string result = read();
      answer.u8(RETURNED);
      answer.bytes() += result;
    } catch (const InputError& e) {
      answer.u8(THREW_INPUT_ERROR);
      answer.bytes() += e.what();
    } catch (const std::exception& e) {
      answer.u8(THREW_ERROR);
      answer.bytes() += e.what();
    } catch (...) {
      answer.u8(THREW_ERROR);
      answer.bytes() += path + ": reading it failed with an unknown exception";
    }
    return std::move(answer.bytes());
  });
  if (!outcome) return read();  // no child could be made: read here, as before
  refuse_if_crashed(path, outcome->status);
  const std::string& answer = outcome->bytes;
  if (answer.empty()) throw Error(path + ": the process reading this file ended without an answer");
  const std::string message = answer.substr(1);
  switch (static_cast<std::uint8_t>(answer[0])) {
    case RETURNED: return message;
    case THREW_INPUT_ERROR: throw InputError(message);
    default: throw Error(message);
  }
}

namespace {

herr_t read_attribute(hid_t object, const char* name, const H5A_info_t*, void*) {
  const hid_t attribute = H5Aopen(object, name, H5P_DEFAULT);
  if (attribute < 0) return -1;
  const hid_t type = H5Aget_type(attribute);
  const hid_t space = H5Aget_space(attribute);
  const hssize_t count = H5Sget_simple_extent_npoints(space);
  herr_t status = -1;
  if (type >= 0 && count >= 0 && count < (1 << 20)) {
    if (H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0) {
      std::vector<char*> text(static_cast<std::size_t>(count), nullptr);
      status = H5Aread(attribute, type, text.data());
      if (status >= 0) H5Dvlen_reclaim(type, space, H5P_DEFAULT, text.data());
    } else {
      const std::size_t bytes = H5Tget_size(type);
      if (bytes > 0 && bytes < (1 << 16)) {
        std::vector<char> buffer(bytes * static_cast<std::size_t>(count));
        status = H5Aread(attribute, type, buffer.data());
        // Variable-length data (a dimension scale's DIMENSION_LIST) is allocated by the read.
        if (status >= 0 && H5Tdetect_class(type, H5T_VLEN) > 0) H5Dvlen_reclaim(type, space, H5P_DEFAULT, buffer.data());
      }
    }
  }
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
  H5Aclose(attribute);
  return status < 0 ? -1 : 0;
}

herr_t read_object(hid_t file, const char* name, const H5O_info_t* info, void*) {
  const hid_t object = H5Oopen(file, name, H5P_DEFAULT);
  if (object < 0) return -1;
  herr_t status = H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, read_attribute, nullptr);
  if (status >= 0 && info->type == H5O_TYPE_DATASET) {
    const hid_t space = H5Dget_space(object);
    const hssize_t count = H5Sget_simple_extent_npoints(space);
    const hid_t type = H5Dget_type(object);
    const H5T_class_t kind = type >= 0 ? H5Tget_class(type) : H5T_NO_CLASS;
    if (count < 0 || count > 500'000'000) {
      status = -1;
    } else if (count > 0 && (kind == H5T_FLOAT || kind == H5T_INTEGER)) {
      std::vector<double> values(static_cast<std::size_t>(count));
      status = H5Dread(object, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    } else if (count > 0 && kind == H5T_STRING && H5Tis_variable_str(type) > 0) {
      std::vector<char*> text(static_cast<std::size_t>(count), nullptr);
      status = H5Dread(object, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data());
      if (status >= 0) H5Dvlen_reclaim(type, space, H5P_DEFAULT, text.data());
    }
    if (type >= 0) H5Tclose(type);
    if (space >= 0) H5Sclose(space);
  }
  H5Oclose(object);
  return status < 0 ? -1 : 0;
}

}  // namespace

void read_every_hdf5_object(const std::string& path) {
  H5::Exception::dontPrint();
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw InputError(path + ": not a readable HDF5 file");
  const herr_t status = H5Ovisit(file, H5_INDEX_NAME, H5_ITER_NATIVE, read_object, nullptr);
  H5Fclose(file);
  if (status < 0) throw InputError(path + ": some of its objects cannot be read (a damaged file?)");
}

}  // namespace stengmc
