#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/install_layout.hpp"
#include "core/error.hpp"
#include "io/guarded_read.hpp"
#include "io/output_path.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "io/run_file.hpp"

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

//! Refuses, before Python starts, what no figure script can plot: a file that is not HDF5,
//! not a stengmc output, or of another format version.
void check_plottable(const std::string& path) {
  check_input_file(path, "an HDF5 file");
  read_in_child_first(path, [&] { read_every_hdf5_object(path); });  // what the scripts will read
  const Hdf5Reader file(path);
  const std::string type = file.string_attribute("/", "file_type");
  if (type.rfind("stengmc-", 0) != 0)
    throw InputError(path + ": not a stengmc output file (its file_type is " + (type.empty() ? "missing" : "'" + type + "'") +
                     ")");
  check_format_version(file, path, RUN_FILE_FORMAT_VERSION);
}

//! Every figure the scripts may write for `h5_path`: <stem>.<format>, and
//! <stem>_spectrum.<format> (a run with spectra) or <stem>_sweep.<format> (an ensemble
//! sweep), beside it.
std::vector<std::string> figure_paths(const std::string& h5_path, const std::string& format) {
  const std::string stem = std::filesystem::path(h5_path).replace_extension().string();
  return {stem + "." + format, stem + "_spectrum." + format, stem + "_sweep." + format};
}

}  // namespace

int render_figures(const std::string& h5_path, const FigureOptions& options) {
  // The scripts write where they are told: a device or a FIFO there would take a figure (or
  // block), and a file named like a figure may be the very file plotted.
  for (const std::string& figure : figure_paths(h5_path, options.format))
    check_output_path(figure, {{h5_path, "the file to plot"}}, "the figure");
  const std::string script = (scripts_dir() / "plot_run.py").string();
  const std::string command = python() + " " + quoted(script) + " " + quoted(h5_path) + " --figure-format " +
                              quoted(options.format) + " --dpi " + std::to_string(options.dpi);
  std::fflush(stdout);  // keep our lines ahead of the script's in a pipe
  return std::system(command.c_str());
}

void add_figure_options(CLI::App* command, CLI::Option* figures, FigureOptions& options) {
  CLI::Option* format = command->add_option("--figure-format", options.format, "png, pdf or svg (pdf and svg are vector)")
                            ->check(CLI::IsMember({"png", "pdf", "svg"}))
                            ->capture_default_str();
  CLI::Option* dpi = command->add_option("--dpi", options.dpi, "Resolution of PNG figures (and of pdf/svg's raster parts)")
                         ->check(CLI::Range(20, 1200))
                         ->capture_default_str();
  if (figures != nullptr) {
    format->needs(figures);
    dpi->needs(figures);
  }
}

void add_plot_command(CLI::App& app) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto options = std::make_shared<FigureOptions>();
  CLI::App* command = app.add_subcommand("plot", "Render the figures of output files (beside each file)");
  command->add_option("files", *files, "HDF5 files written by stengmc")->required()->check(CLI::ExistingFile);
  add_figure_options(command, nullptr, *options);
  command->callback([files, options] {
    for (const auto& f : *files) {
      check_plottable(f);
      const int status = render_figures(f, *options);
      // The scripts exit 2 for a file they cannot plot, having said why.
      if (WIFEXITED(status) && WEXITSTATUS(status) == 2) throw InputError(f + ": cannot be plotted (see above)");
      if (status != 0) throw Error("plotting " + f + " failed");
    }
  });
}

}  // namespace stengmc::app
