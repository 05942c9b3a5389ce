#include "io/guarded_read.hpp"

#include <H5Cpp.h>
#include <malloc.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <thread>
#include <vector>

#include "core/error.hpp"

namespace stengmc {

void read_in_child_first(const std::string& path, const std::function<void()>& read) {
  std::error_code ignored;
  const auto size = std::filesystem::file_size(path, ignored);
  const double timeout_s = 10.0 + static_cast<double>(ignored ? 0 : size) / 20e6;
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t child = ::fork();
  if (child < 0) return;  // cannot fork (a process limit): read directly, as before
  if (child == 0) {
    try {
      read();
    } catch (...) {
    }
    // A damaged file can make HDF5 write past a buffer without crashing at once (the bank
    // fuzz found a corrupt global heap doing so): glibc then aborts at some later free, which
    // in the parent would be long after the read. So the child has malloc walk and
    // consolidate its free chunks, where such damage is caught (an abort: refused). (H5close
    // as well, to free what HDF5 holds, made each guarded read ~40 ms slower - the fuzz of
    // run files 13x - and is not needed to catch the bank's case.)
    ::malloc_trim(0);
    ::_exit(0);  // no atexit handlers: the parent's files and libraries are not the child's to close
  }
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0 && errno != EINTR) return;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      throw InputError(path + ": the HDF5 library did not finish reading this file in " + std::to_string(int(timeout_s)) +
                       " s; it is damaged (or not what it claims to be)");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (WIFSIGNALED(status))
    throw InputError(path + ": the HDF5 library crashed reading this file (" + strsignal(WTERMSIG(status)) +
                     "); it is damaged (or not what it claims to be)");
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
