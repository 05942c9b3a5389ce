#include "io/netlist_export.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "circuit/steng_netlist.hpp"
#include "core/build_info.hpp"
#include "core/constants.hpp"
#include "core/error.hpp"
#include "core/posix_file.hpp"
#include "core/temporary_file.hpp"

namespace stengmc {

std::string export_netlist_text(const Study& study, const RunResult& result) {
  const std::size_t samples = result.circuit_samples;
  if (samples < 2) throw ModelError(study.file + ": the run's valid part has fewer than 2 samples: nothing to export");
  const std::span<const double> times(result.times_s.data(), samples);
  const std::size_t n = study.asperities.size();

  // Each element's x at the samples (the motion that drives it: x(t), or Model 1's x0(t)).
  std::vector<std::vector<double>> x(n, std::vector<double>(samples));
  double max_speed = 0.0;
  double capacitance = 0.0;  // sum C_i at the first sample [F]
  std::vector<StengElement> elements;
  for (std::size_t i = 0; i < n; ++i) {
    const Motion& motion = study.circuit_input == CircuitInput::imposed ? *result.drives[i] : *result.trajectories[i].motion;
    for (std::size_t j = 0; j < samples; ++j) {
      const PhasePoint p = motion.at(times[j]);
      x[i][j] = p.x_m;
      max_speed = std::max(max_speed, std::abs(p.v_m_per_s));
    }
    const StengElement& e = study.asperities[i].element;
    elements.push_back(e);
    capacitance += EPSILON_0 * e.width_m * (e.length_m - x[i][0]) / e.effective_thickness_m;
  }
  // The first step sized for the study's R (or, with a netlist load, for 1 kOhm as the
  // co-simulation does: netlist_circuit.cpp).
  const double resistance = study.netlist ? 1e3 : study.circuit.load_resistance_ohm;
  const SpiceTransientSettings settings = choose_transient(elements, max_speed, times[1] - times[0],
                                                           times.back() - times.front(), resistance * capacitance);

  std::ostringstream out;
  out << "* stengmc export-netlist: " << (study.title.empty() ? study.file : study.title) << "\n"
      << "* study " << study.file << ", realisation " << study.realisation << ", seed " << study.seed << "\n"
      << "* stengmc " << program_version() << " (git " << git_revision() << ")\n"
      << "*\n"
      << "* The S-TENG port is node " << STENG_PORT_NODE << " against ground 0: V(" << STENG_PORT_NODE
      << ") is the output voltage,\n"
      << "* I(Vstengmc_port) the current the elements deliver into the load. Each of the " << n << " elements is\n"
      << "* the paper's appendix subcircuit (MODEL.md §2), driven by its displacement x_i(t) in metres as\n"
      << "* the voltage of node stengmc_x<i> (a PWL source through the run's " << samples << " samples, "
      << times.front() << " s to " << times.back() << " s).\n"
      << "* PWL is linear between samples: its velocity is constant over each sample interval, where\n"
      << "* stengmc's own solver follows the motion itself, so V here differs from the run's by about\n"
      << "* omega dt / 2 at a line of angular frequency omega (raise sample_rate_hz to shrink it).\n"
      << "* Tolerances scaled to these femtocoulomb elements; the first step (a tenth of the .tran\n"
      << "* step) below the load's R times sum C; maximum step a tenth of the sample step.\n"
      << "* ngspice: ngspice -b -r out.raw <this file>   (exit status 0 even when the transient\n"
      << "* aborts: check that out.raw reaches " << times.back() << " s)\n"
      << "*\n";
  for (const std::string& card : steng_subcircuit_cards(EPSILON_0)) out << card << "\n";
  out << "\n";
  // The knots' times as the sample index over the rate, the double nearest j / f_s: 3e-08,
  // not the 3.0000000000000004e-08 that j dt accumulates (the same instant to 1 ulp).
  std::vector<double> pwl_time(samples);
  for (std::size_t j = 0; j < samples; ++j) pwl_time[j] = static_cast<double>(j) / study.sample_rate_hz;
  for (std::size_t i = 0; i < n; ++i) {
    std::string pwl = "PWL(\n";
    for (std::size_t j = 0; j < samples; ++j) {
      pwl += (j % 4 == 0 ? "+ " : " ") + spice_number(pwl_time[j]) + " " + spice_number(x[i][j]);
      if (j % 4 == 3 || j + 1 == samples) pwl += "\n";
    }
    pwl += "+ )";
    out << "* element " << i + 1 << ": k = " << study.asperities[i].stiffness_n_per_m << " N/m\n";
    for (const std::string& card : steng_element_cards(i, elements[i], pwl)) out << card << "\n";
  }
  out << "\n";
  for (const std::string& card : steng_port_cards(std::string(STENG_PORT_NODE))) out << card << "\n";
  if (study.netlist) {
    out << "* The load: " << study.netlist->file << " (the study's [circuit] netlist), as stengmc checked it: its\n"
        << "* cards without comments, continuation lines joined, included files inlined\n";
    for (const std::string& line : study.netlist->lines) out << line << "\n";
  } else {
    out << "* The load: the study's R || C_L\n"
        << "Rload " << STENG_PORT_NODE << " 0 " << spice_number(study.circuit.load_resistance_ohm) << "\n";
    if (study.circuit.load_capacitance_f > 0.0)
      out << "Cload " << STENG_PORT_NODE << " 0 " << spice_number(study.circuit.load_capacitance_f) << "\n";
  }
  out << "\n";
  // What the raw file keeps: without .save ngspice writes every node and branch of every
  // element at every step (35 MB for the paper's four asperities over 100 us).
  out << "* The raw file keeps the port voltage and the current the elements deliver; add names\n"
      << "* here for more (the element i's current into the load: i(v.xstengmc_<i>.vc))\n"
      << ".save v(" << STENG_PORT_NODE << ") i(vstengmc_port)";
  for (const NetlistProbe& probe : study.probes) {  // the study's [circuit] probes too
    const std::size_t branch = probe.vector.find("#branch");
    out << " " << (branch == std::string::npos ? probe.vector : "i(" + probe.vector.substr(0, branch) + ")");
  }
  out << "\n";
  for (const std::string& card : transient_cards(settings)) out << card << "\n";
  out << ".end\n";
  return out.str();
}

void write_netlist_file(const std::string& path, const Study& study, const RunResult& result) {
  const std::string text = export_netlist_text(study, result);
  TemporaryFile temporary(path);
  // The checked writes of every output (core/posix_file.hpp): a full disk is reported with
  // the system's reason, which an ofstream does not keep.
  write_file_durably(temporary.path(), text, path);
  temporary.commit();
  sync_directory_of(path);
}

}  // namespace stengmc
