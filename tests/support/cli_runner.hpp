#pragma once
// Runs the stengmc executable as a user would, capturing exit code and output.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace stengmc::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

//! A fresh scratch folder per test, removed afterwards.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / ("stengmc-test-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }

 private:
  std::filesystem::path path_;
};

//! Runs a shell command line, capturing its exit code and output (stdout and stderr).
inline CliResult run_command(const std::string& command_line, const ScratchDir& scratch) {
  const std::string log = scratch.file("cli.log");
  const int status = std::system((command_line + " > " + log + " 2>&1").c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  result.output = text.str();
  return result;
}

//! Runs `stengmc arguments`; `environment` ("NAME=value ...") is set for that process only.
inline CliResult run_cli(const std::string& arguments, const ScratchDir& scratch, const std::string& environment = "") {
  return run_command((environment.empty() ? "" : "env " + environment + " ") + std::string(STENGMC_BINARY) + " " +
                         arguments,
                     scratch);
}

}  // namespace stengmc::testing
