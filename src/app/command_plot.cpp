#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "app/install_layout.hpp"
#include "core/error.hpp"

namespace stengmc::app {

namespace {

//! Debian's python3 has h5py and matplotlib; a python3 earlier on PATH (pyenv, venv)
//! often has neither. STENGMC_PYTHON overrides.
std::string python() {
  if (const char* chosen = std::getenv("STENGMC_PYTHON")) return chosen;
  return std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

int render_figures(const std::string& h5_path) {
  const std::string script = (scripts_dir() / "plot_run.py").string();
  const std::string command = python() + " " + quoted(script) + " " + quoted(h5_path);
  std::fflush(stdout);  // keep our lines ahead of the script's in a pipe
  return std::system(command.c_str());
}

void add_plot_command(CLI::App& app) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* command = app.add_subcommand("plot", "Render PNG figures of output files (beside each file)");
  command->add_option("files", *files, "HDF5 files written by stengmc")->required()->check(CLI::ExistingFile);
  command->callback([files] {
    for (const auto& f : *files)
      if (render_figures(f) != 0) throw Error("plotting " + f + " failed");
  });
}

}  // namespace stengmc::app
