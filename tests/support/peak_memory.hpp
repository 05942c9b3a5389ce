#pragma once
//! The peak resident memory of a real `stengmc` run, for tests that check memory estimates
//! (the test target defines STENGMC_BINARY).
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

namespace stengmc::testing {

//! Peak resident memory [bytes] of `stengmc arguments` run as a child process.
inline double peak_memory_of(const std::string& arguments) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string command = "exec " + std::string(STENGMC_BINARY) + " " + arguments + " > /dev/null 2>&1";
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << arguments;
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // kilobytes on Linux
}

}  // namespace stengmc::testing
