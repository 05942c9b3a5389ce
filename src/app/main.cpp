// stengmc: the command line. It parses, calls the library, prints, and is the only
// place that catches errors and chooses the exit code.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/commands.hpp"
#include "core/build_info.hpp"
#include "core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"stengmc: Monte Carlo studies of sliding triboelectric sensors (S-TENG) on rough surfaces.\n"
               "Every quantity is in SI units. Model: MODEL.md; file layouts: README.md."};
  app.set_version_flag("--version", std::string("stengmc ") + stengmc::program_version() + " (git " +
                                        stengmc::git_revision() + ")");
  app.require_subcommand(1);
  stengmc::app::add_run_command(app);
  stengmc::app::add_circuit_command(app);
  stengmc::app::add_plot_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const stengmc::InputError& e) {
    std::fprintf(stderr, "stengmc: input error: %s\n", e.what());
    return 2;
  } catch (const stengmc::ModelError& e) {
    std::fprintf(stderr, "stengmc: model error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stengmc: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
