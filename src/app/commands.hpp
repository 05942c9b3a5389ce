#pragma once
//! The subcommands of `stengmc`; each registers itself on the CLI11 app.
#include <CLI/CLI.hpp>

namespace stengmc::app {

void add_run_command(CLI::App& app);
void add_circuit_command(CLI::App& app);
void add_plot_command(CLI::App& app);
void add_spectrum_command(CLI::App& app);
void add_surface_command(CLI::App& app);

//! Renders the figures of an output file with scripts/plot_run.py; returns the PNG paths printed.
int render_figures(const std::string& h5_path);

}  // namespace stengmc::app
