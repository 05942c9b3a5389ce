#pragma once
//! Test helper: runs ngspice on the paper's S-TENG subcircuit (appendix, second model,
//! Fig. 10) and reads back its binary raw file, so the circuit solver can be checked
//! against an independent simulator (NGSPICE-NOTES.md in the shared folder).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/asperity.hpp"

namespace stengmc::test {

//! The ngspice executable found on PATH, or nothing.
std::optional<std::filesystem::path> find_ngspice();

//! A fresh, uniquely named directory under `parent` (mkdtemp).
std::filesystem::path make_unique_directory(const std::filesystem::path& parent, std::string_view prefix);

//! What an ngspice batch run printed and how it ended.
struct NgspiceRun {
  //! The process exit status. Says nothing about the transient: ngspice 39 exits 0 when it
  //! aborts, and 1 after a successful run driven from a .control block ("no simulations run").
  int exit_status = -1;
  std::string output;    //!< stdout and stderr merged
  double wall_time_s = 0.0;  //!< elapsed time of the run [s]
};

//! Runs `ngspice -b <netlist>` inside the netlist's directory.
NgspiceRun run_ngspice(const std::filesystem::path& ngspice, const std::filesystem::path& netlist);

//! One plot of an ngspice raw file with real data (Flags: real), as columns.
class RawFile {
 public:
  //! Reads a binary raw file (`set filetype=binary` + `write`): an ASCII header, then
  //! `No. Points` rows of `No. Variables` little-endian doubles. Throws std::runtime_error.
  static RawFile read_binary(const std::filesystem::path& path);

  //! The column of a vector by its name as listed in the header (case-insensitive,
  //! e.g. "time", "v(out)", "i(v.x0.vc)"). Throws std::runtime_error if absent.
  [[nodiscard]] const std::vector<double>& column(std::string_view name) const;

  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] std::size_t points() const { return columns_.empty() ? 0 : columns_.front().size(); }

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
};

//! Transient settings of the reference run (NGSPICE-NOTES.md: scale the absolute
//! tolerances to the problem, shorten the first and the maximum step).
struct SpiceTransient {
  double stop_time_s = 0.0;
  double print_step_s = 0.0;  //!< tstep: ngspice's first step is a fraction of it [s]
  double max_step_s = 0.0;    //!< tmax [s]
  double reltol = 1e-6;
  double abstol_a = 1e-12;    //!< current tolerance [A]
  double chgtol_c = 1e-14;    //!< charge tolerance [C]
  double vntol_v = 1e-6;      //!< node voltage tolerance [V]
  std::string method = "trap";
};

//! Writes the netlist of the S-TENG elements in parallel on a load R: element i is the
//! paper's `s-teng` subcircuit (with the `V(1)` typo read as V(l) and the terminals
//! renamed vp/vn, since ngspice will not take `+`/`-` inside V()), driven by a PWL
//! source through (times_s, displacement_m[i]). The delivered charge Q = int V/R dt is
//! integrated by ngspice itself: a B source of current V(out)/R charges a 1 F capacitor,
//! whose voltage (node `q`) is then Q in coulombs. The result is written to `raw_file`.
//! @param epsilon0  the vacuum permittivity written as the subcircuit's .param [F/m]
void write_parallel_steng_netlist(const std::filesystem::path& netlist, const std::filesystem::path& raw_file,
                                  std::span<const StengElement> elements, std::span<const double> times_s,
                                  std::span<const std::vector<double>> displacement_m, double load_resistance_ohm,
                                  double epsilon0, const SpiceTransient& transient);

}  // namespace stengmc::test
