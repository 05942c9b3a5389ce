#include "circuit/netlist_circuit.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

//! The smallest load resistance the first step is sized for [Ohm]: the load is the user's
//! and unknown here, and a TENG's loads are megaohms. A first step much shorter still
//! (sized for 1 Ohm: 7e-19 s) made Newton fail at the diodes of a bridge rectifier.
constexpr double SMALLEST_LOAD_OHM = 1e3;

//! Values at `grid` from ngspice's time points by the cubic through the four nearest
//! points (Lagrange): ngspice's steps do not land on the grid, and between them its
//! trapezoidal solution is smooth, so cubic interpolation adds an error of order h^4
//! (h <= a tenth of the sample step), far below the transient's own.
std::vector<double> resample(const std::vector<double>& time, const std::vector<double>& value,
                             std::span<const double> grid) {
  std::vector<double> out(grid.size());
  const std::size_t n = time.size();
  for (std::size_t j = 0; j < grid.size(); ++j) {
    const double t = grid[j];
    const auto it = std::lower_bound(time.begin(), time.end(), t);
    const std::size_t k = static_cast<std::size_t>(it - time.begin());
    if (k < n && time[k] == t) {
      out[j] = value[k];
      continue;
    }
    if (n < 4) {  // too few points for a cubic: linear
      const std::size_t b = std::clamp<std::size_t>(k, 1, n - 1);
      const double w = (t - time[b - 1]) / (time[b] - time[b - 1]);
      out[j] = (1.0 - w) * value[b - 1] + w * value[b];
      continue;
    }
    const std::size_t first = std::min(n - 4, k >= 2 ? k - 2 : 0);
    double sum = 0.0;
    for (std::size_t a = first; a < first + 4; ++a) {
      double basis = 1.0;
      for (std::size_t b = first; b < first + 4; ++b)
        if (b != a) basis *= (t - time[b]) / (time[a] - time[b]);
      sum += basis * value[a];
    }
    out[j] = sum;
  }
  return out;
}

void check_finite(const std::vector<double>& values, std::span<const double> times, const std::string& what,
                  const std::string& origin) {
  for (std::size_t j = 0; j < values.size(); ++j)
    if (!std::isfinite(values[j]))
      throw ModelError(origin + ": ngspice gave a non-finite " + what + " at t = " + std::to_string(times[j]) + " s");
}

}  // namespace

double netlist_circuit_devices(std::size_t elements, const NetlistLoad& load) {
  // Per element: its sources (every card but the instance) and the subcircuit's devices
  // (every card but .subckt, .param and .ends); one sense source at the port.
  const double per_element = static_cast<double>(steng_element_cards(0, StengElement{}, "0").size() - 1 +
                                                  steng_subcircuit_cards(EPSILON_0).size() - 3);
  return per_element * static_cast<double>(elements) + 1.0 + load.devices;
}

double netlist_circuit_steps(double samples) { return 2.0 * 10.0 * std::max(samples - 1.0, 1.0) + 100.0; }

NetlistCircuitRun solve_netlist_circuit(std::span<const StengElement> elements, std::span<const Motion* const> motions,
                                        std::span<const double> times, const NetlistLoad& load, bool element_traces,
                                        const std::vector<std::string>& extra_vectors, const ChildBudget& budget,
                                        bool show_progress) {
  NetlistCircuitRun run;
  if (times.size() < 2) {  // nothing to integrate: the initial state, V = Q = 0
    run.circuit.voltage_v.assign(times.size(), 0.0);
    run.circuit.charge_c.assign(times.size(), 0.0);
    if (element_traces) {
      run.circuit.current_a.assign(elements.size(), std::vector<double>(times.size(), 0.0));
      run.circuit.element_charge_c = run.circuit.current_a;
    }
    return run;
  }
  const double t0 = times.front();
  const double duration = times.back() - t0;

  double max_speed = 0.0;
  double capacitance = 0.0;  // sum C_i at t0 [F]
  for (std::size_t i = 0; i < elements.size(); ++i) {
    for (double t : times) max_speed = std::max(max_speed, std::abs(motions[i]->at(t).v_m_per_s));
    const StengElement& e = elements[i];
    capacitance += EPSILON_0 * e.width_m * (e.length_m - motions[i]->at(t0).x_m) / e.effective_thickness_m;
  }
  const double sample_step = duration / static_cast<double>(times.size() - 1);
  run.settings = choose_transient(elements, max_speed, sample_step, duration, SMALLEST_LOAD_OHM * capacitance);

  // The elements' x(t) reach ngspice as EXTERNAL sources, evaluated from the motions'
  // dense output wherever ngspice steps. PWL sources through the output samples would
  // hand it linear interpolation, whose piecewise-constant velocity is a first-order
  // error in V (omega dt / 2, ~6 % at 2 MHz and 10 ns; MODEL.md §2), and every PWL
  // knot forces a step (NGSPICE-NOTES: cost grows faster than the knot count). The
  // external source gives ngspice the same x(t) the built-in solver integrates. Written
  // as plain `external`: libngspice 39 (Debian) segfaults on `dc 0 external` (measured).
  NgspiceTransient transient;
  transient.origin = load.file;
  transient.stop_time_s = duration;
  transient.budget = budget;
  transient.show_progress = show_progress;
  transient.cards.push_back("* stengmc: S-TENG elements on the load " + load.file);
  for (std::string& card : steng_subcircuit_cards(EPSILON_0)) transient.cards.push_back(std::move(card));
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (std::string& card : steng_element_cards(i, elements[i], "external")) transient.cards.push_back(std::move(card));
  for (std::string& card : steng_port_cards(std::string(STENG_PORT_NODE))) transient.cards.push_back(std::move(card));
  transient.card_origins.assign(transient.cards.size(), "");
  for (std::size_t k = 0; k < load.lines.size(); ++k) {
    transient.cards.push_back(load.lines[k]);
    transient.card_origins.push_back(k < load.origins.size() ? load.origins[k] : load.file);
  }
  for (std::string& card : transient_cards(run.settings)) transient.cards.push_back(std::move(card));
  transient.cards.push_back(".end");
  transient.card_origins.resize(transient.cards.size(), "");

  std::vector<std::string> source_names;
  for (std::size_t i = 0; i < elements.size(); ++i) source_names.push_back(steng_displacement_source_name(i));
  transient.external_voltage = [&](std::string_view name, double t_s) {
    const auto it = std::find(source_names.begin(), source_names.end(), name);
    if (it == source_names.end())
      throw InputError("voltage source " + std::string(name) +
                       " is EXTERNAL: only stengmc's own displacement sources may be (remove 'external')");
    const double t = t0 + std::clamp(t_s, 0.0, duration);
    return motions[static_cast<std::size_t>(it - source_names.begin())]->at(t).x_m;
  };
  transient.vectors = {"v(" + std::string(STENG_PORT_NODE) + ")", STENG_PORT_CURRENT_VECTOR};
  if (element_traces)
    for (std::size_t i = 0; i < elements.size(); ++i) transient.vectors.push_back(steng_element_current_vector(i));
  transient.vectors.insert(transient.vectors.end(), extra_vectors.begin(), extra_vectors.end());
  run.raw = run_ngspice_transient(transient);

  // The grid in ngspice's time (which starts at 0).
  std::vector<double> grid(times.begin(), times.end());
  for (double& t : grid) t = std::clamp(t - t0, 0.0, duration);
  const std::vector<double>& time = run.raw.time_s;
  run.circuit.voltage_v = resample(time, run.raw.values[0], grid);
  // Q = integral of the port current, trapezoidal over ngspice's own steps (its
  // integration rule), then on the grid.
  const std::vector<double>& current = run.raw.values[1];
  std::vector<double> charge(time.size(), 0.0);
  for (std::size_t k = 1; k < time.size(); ++k)
    charge[k] = charge[k - 1] + 0.5 * (current[k] + current[k - 1]) * (time[k] - time[k - 1]);
  run.circuit.charge_c = resample(time, charge, grid);
  const std::size_t first_extra = 2 + (element_traces ? elements.size() : 0);
  for (std::size_t p = 0; p < extra_vectors.size(); ++p) {
    run.circuit.probes.push_back(resample(time, run.raw.values[first_extra + p], grid));
    check_finite(run.circuit.probes.back(), times, extra_vectors[p], load.file);
  }
  check_finite(run.circuit.voltage_v, times, "port voltage", load.file);
  check_finite(run.circuit.charge_c, times, "port charge", load.file);
  if (element_traces) {
    for (std::size_t i = 0; i < elements.size(); ++i) {
      std::vector<double> element_current = resample(time, run.raw.values[2 + i], grid);
      for (double& c : element_current) c = -c;  // the sense source's current flows into the element
      check_finite(element_current, times, "element current", load.file);
      run.circuit.current_a.push_back(std::move(element_current));
      const StengElement& e = elements[i];
      auto delivered = [&](std::size_t j) {
        const double x = motions[i]->at(times[j]).x_m;
        const double c = EPSILON_0 * e.width_m * (e.length_m - x) / e.effective_thickness_m;
        return e.charge_density_c_per_m2 * e.width_m * x - c * run.circuit.voltage_v[j];
      };
      std::vector<double> element_charge(times.size());
      const double initial = delivered(0);
      for (std::size_t j = 0; j < times.size(); ++j) element_charge[j] = delivered(j) - initial;
      run.circuit.element_charge_c.push_back(std::move(element_charge));
    }
  }
  return run;
}

}  // namespace stengmc
