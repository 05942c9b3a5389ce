// The circuit solver against an independent simulator: ngspice running the paper's
// appendix subcircuit (second model, Fig. 10) for four Table 2 elements in parallel on
// the paper's 1 MOhm load, on the same piecewise-linear x_i(t) (MODEL.md §2: a SPICE PWL
// source is linear interpolation, so our side uses Interpolation::linear).
// Facts this relies on are in NGSPICE-NOTES.md beside MODEL.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "circuit/element_sums.hpp"
#include "circuit/ngspice_runner.hpp"
#include "core/constants.hpp"
#include "tribology/sampled_motion.hpp"

namespace stengmc {
namespace {

// The motion: one oscillation per element at the Model 2 natural frequencies (MODEL.md §1,
// k = 25, 50, 100, 155 N/m), three damped and one undamped, around a 4 um offset.
// Amplitudes <= 3.5 um keep x in [0.5, 7.5] um, below l = 10 um.
constexpr double DURATION_S = 4e-6;
constexpr std::size_t SAMPLES = 2001;  // 2 ns step: ~250 samples per period at 1.98 MHz
constexpr double OFFSET_M = 4e-6;
constexpr std::array<double, 4> FREQUENCY_HZ{0.796e6, 1.125e6, 1.592e6, 1.981e6};
constexpr std::array<double, 4> AMPLITUDE_M{3.5e-6, 3.0e-6, 2.5e-6, 2.0e-6};
constexpr std::array<double, 4> DECAY_TIME_S{2e-6, 4e-6, 8e-6, 0.0};  // 0: undamped
constexpr std::array<double, 4> PHASE_RAD{0.0, 1.0, 2.0, 3.0};
constexpr double LOAD_OHM = 1e6;  // the paper's load

double displacement(std::size_t i, double t) {
  const double envelope = DECAY_TIME_S[i] > 0.0 ? std::exp(-t / DECAY_TIME_S[i]) : 1.0;
  return OFFSET_M + AMPLITUDE_M[i] * envelope * std::sin(2.0 * PI * FREQUENCY_HZ[i] * t + PHASE_RAD[i]);
}

double relative_l2(const std::vector<double>& reference, const std::vector<double>& value, std::size_t first = 0) {
  double difference = 0.0;
  double norm = 0.0;
  for (std::size_t k = first; k < reference.size(); ++k) {
    difference += (reference[k] - value[k]) * (reference[k] - value[k]);
    norm += reference[k] * reference[k];
  }
  return std::sqrt(difference / norm);
}

std::string tail(const std::string& text, std::size_t count) {
  return text.size() <= count ? text : "[...]\n" + text.substr(text.size() - count);
}

TEST(Ngspice, FourTable2ElementsOnOneMegaohmAgreeWithTheAppendixSubcircuit) {
  const auto ngspice = test::find_ngspice();
  ASSERT_TRUE(ngspice.has_value())
      << "ngspice is not installed (no executable 'ngspice' on PATH). This test needs it as the "
         "independent circuit reference; scripts/setup.sh installs it (Debian package 'ngspice').";

  // Same samples on both sides.
  const std::vector<StengElement> elements(4);  // Table 2: sigma 80e-6, d0 50e-6, w = l = 10e-6
  std::vector<double> times(SAMPLES);
  for (std::size_t k = 0; k < SAMPLES; ++k)
    times[k] = DURATION_S * static_cast<double>(k) / static_cast<double>(SAMPLES - 1);
  std::vector<std::vector<double>> x(elements.size(), std::vector<double>(SAMPLES));
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (std::size_t k = 0; k < SAMPLES; ++k) x[i][k] = displacement(i, times[k]);

  // --- Our solver.
  std::vector<SampledMotion> motions;
  for (std::size_t i = 0; i < elements.size(); ++i) motions.emplace_back(times, x[i], Interpolation::linear);
  std::vector<const Motion*> motion_pointers;
  for (const SampledMotion& m : motions) motion_pointers.push_back(&m);
  CircuitParams params;
  params.load_resistance_ohm = LOAD_OHM;
  const CircuitResult ours = solve_circuit(elements, motion_pointers, times, params);
  // The streamed solver (what `stengmc circuit` and the pipeline use) on the same input,
  // held to the same bars below.
  const CircuitResult streamed = solve_circuit_streamed(elements, motion_pointers, times, params);

  // --- ngspice. Scales for its absolute tolerances (NGSPICE-NOTES: abstol and chgtol
  // ~1e-3 reltol times the problem's current and charge scales, or a defaults-only run of
  // these ~1e-15 C elements is silently inaccurate).
  double current_scale = 0.0;  // largest sum of sigma w |x'| [A]
  double capacitance = 0.0;    // sum C_i at t = 0 [F]
  double charge_scale = 0.0;   // largest sigma w l [C]
  for (std::size_t k = 0; k + 1 < SAMPLES; ++k) {
    double sum = 0.0;
    for (std::size_t i = 0; i < elements.size(); ++i) {
      const StengElement& e = elements[i];
      sum += e.charge_density_c_per_m2 * e.width_m * std::abs(x[i][k + 1] - x[i][k]) / (times[k + 1] - times[k]);
    }
    current_scale = std::max(current_scale, sum);
  }
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const StengElement& e = elements[i];
    capacitance += EPSILON_0 * e.width_m * (e.length_m - x[i][0]) / e.effective_thickness_m;
    charge_scale = std::max(charge_scale, e.charge_density_c_per_m2 * e.width_m * e.length_m);
  }
  const double time_constant = LOAD_OHM * capacitance;  // R sum C ~ 3.5e-11 s
  const double sample_step = times[1] - times[0];

  test::SpiceTransient transient;
  transient.stop_time_s = DURATION_S;
  // ngspice's first step is a fraction of the print step and is a backward-Euler step: it
  // must be well below R sum C or V starts ~8 % off (NGSPICE-NOTES). Without `interp`
  // every accepted step is stored, so a short print step costs nothing.
  transient.print_step_s = 0.1 * time_constant;
  // The print step would be the default maximum step; give it explicitly. The maximum
  // step, not reltol, sets the reference's accuracy here; measured on this case (relative
  // L2 of V against our solver, ngspice wall time): 1 sample step 1.2e-3 (1.0 s), 1/4
  // 9e-5 (1.5 s), 1/10 3.4e-7 (2.5 s), 1/20 3.2e-7 (3.9 s). From 1/10 on, what is left is
  // our own solver's error at substeps = 4 (ngspice at reltol 1e-7 and max step 1/20,
  // and our solver at substeps = 16, agree to 2e-9): 1/10 makes ngspice the more
  // accurate side.
  transient.max_step_s = 0.1 * sample_step;
  // 1e-6 as NGSPICE-NOTES advise: 1e-8 aborts with "timestep too small" (the notes;
  // 1e-9 aborts here already in the first picosecond), and at 1e-7 the trapezoidal
  // element currents ring undamped over the first sample interval.
  transient.reltol = 1e-6;
  transient.abstol_a = 1e-3 * transient.reltol * current_scale;
  transient.chgtol_c = 1e-3 * transient.reltol * charge_scale;
  // The subcircuit carries each element's charge as a node voltage (n001, n002: ~1e-15 V),
  // which the default vntol of 1 uV would wave through Newton's convergence test. The
  // circuit is linear once the PWL sources are solved, so the results here do not change
  // with vntol (measured); the scaled value is kept so that stays true by construction.
  transient.vntol_v = 1e-3 * transient.reltol * charge_scale;
  // Trapezoidal, as the notes advise. Here gear gives the same V and Q at this maximum
  // step (it is better at a 1/4 sample step: 5e-6 against 9e-5) and 1e-6 to 6e-6 on the
  // element currents against trapezoidal's 1e-6.
  transient.method = "trap";

  // The subcircuit's epsilon0 is our EPSILON_0 (CODATA 2018); the paper prints
  // 8.8541878e-12, 1.5e-9 relative away. The same value on both sides keeps this a
  // comparison of solvers.
  const std::filesystem::path directory =
      test::make_unique_directory(std::filesystem::temp_directory_path(), "stengmc_ngspice_");
  const std::filesystem::path netlist = directory / "parallel_steng.cir";
  const std::filesystem::path raw_path = directory / "parallel_steng.raw";
  test::write_parallel_steng_netlist(netlist, raw_path, elements, times, x, LOAD_OHM, EPSILON_0, transient);
  const test::NgspiceRun run = test::run_ngspice(*ngspice, netlist);
  std::printf("ngspice: %.2f s wall time, exit status %d, files in %s (kept on failure)\n", run.wall_time_s,
              run.exit_status, directory.c_str());
  RecordProperty("ngspice_wall_time_s", std::to_string(run.wall_time_s));

  // ngspice exits 0 even when the transient aborts: what counts is whether the raw file
  // exists and reaches the final time.
  ASSERT_TRUE(std::filesystem::exists(raw_path))
      << "ngspice wrote no raw file; its output:\n" << tail(run.output, 8000);
  const test::RawFile raw = test::RawFile::read_binary(raw_path);
  const std::vector<double>& t_spice = raw.column("time");
  ASSERT_FALSE(t_spice.empty()) << "empty raw file; ngspice output:\n" << tail(run.output, 8000);
  ASSERT_NEAR(t_spice.back(), DURATION_S, 1e-9 * DURATION_S)
      << "the ngspice transient stopped at t = " << t_spice.back() << " s before " << DURATION_S
      << " s; its output:\n" << tail(run.output, 8000);
  std::printf("ngspice: %zu time points for %zu samples\n", t_spice.size(), SAMPLES);

  // Compare on the input grid: every PWL sample is a breakpoint where ngspice places a step
  // (to ~1e-13 relative); the value there ends the step arriving from the left, as our
  // solver's output does. Between samples the element currents spike and trapezoidal
  // rings right after each breakpoint (NGSPICE-NOTES).
  std::vector<std::size_t> at_sample(SAMPLES);
  for (std::size_t k = 0; k < SAMPLES; ++k) {
    const auto it = std::lower_bound(t_spice.begin(), t_spice.end(), times[k] - 1e-6 * sample_step);
    ASSERT_TRUE(it != t_spice.end() && std::abs(*it - times[k]) <= 1e-6 * sample_step)
        << "ngspice has no time point at the PWL breakpoint t = " << times[k] << " s";
    at_sample[k] = static_cast<std::size_t>(it - t_spice.begin());
  }
  auto on_grid = [&](const std::vector<double>& column, double sign) {
    std::vector<double> out(SAMPLES);
    for (std::size_t k = 0; k < SAMPLES; ++k) out[k] = sign * column[at_sample[k]];
    return out;
  };
  const std::vector<double> v_spice = on_grid(raw.column("v(out)"), 1.0);
  const std::vector<double> q_spice = on_grid(raw.column("v(q)"), 1.0);

  const double error_v = relative_l2(v_spice, ours.voltage_v);
  const double error_q = relative_l2(q_spice, ours.charge_c);
  std::printf("relative L2 error vs ngspice: V %.3e, Q %.3e\n", error_v, error_q);
  RecordProperty("relative_l2_error_v", std::to_string(error_v));
  RecordProperty("relative_l2_error_q", std::to_string(error_q));
  // V: 2e-3 is the bound the issue fixes. It is sized for the reference, not for us:
  // ngspice's step control watches the element charges (~100 V open-circuit voltages
  // behind ~1e-17 F), not the ~10 mV terminal voltage, so with its maximum step at the
  // sample step a reltol 1e-6 run is only good to ~5e-4 (NGSPICE-NOTES; 1.2e-3 measured
  // on this case). With the shorter maximum step above we measure ~3e-7. The bound still
  // catches a wrong source or conductance term or sign (errors of order 1) and a solver that smooths
  // over the velocity steps at the samples (spline vs linear: omega dt / sqrt(12) ~ 7e-3
  // at 2 MHz, MODEL.md §2).
  EXPECT_LE(error_v, 2e-3);
  // Q = int V/R dt (ngspice's own integral, see the netlist) averages V's step-to-step
  // error away (~6e-7 in the notes' runs, ~1e-10 measured here). Q is also what sees the
  // capacitances: V at the samples is quasi-static (blind to sum C_i), but each velocity
  // step adds to Q the charge of a relaxation layer, ~ (jump of V) * sum C_i. Adding 10 % of sum C_i
  // as C_L on our side alone moves Q by 1.4e-5 (V by nothing), so the 1e-5
  // catches capacitance errors of ~10 % and above.
  EXPECT_LE(error_q, 1e-5);
  const double streamed_v = relative_l2(v_spice, streamed.voltage_v);
  const double streamed_q = relative_l2(q_spice, streamed.charge_c);
  std::printf("streamed solver: relative L2 error vs ngspice: V %.3e, Q %.3e\n", streamed_v, streamed_q);
  EXPECT_LE(streamed_v, 2e-3);
  EXPECT_LE(streamed_q, 1e-5);

  // Element currents i_i = dQ_i/dt: minus the current through the 0 V sense source
  // (NGSPICE-NOTES), on the grid as left limits. The first two samples are left out:
  // ngspice's operating point has the capacitors open (I(Vc) = 0) while our i_i(0) is the
  // t = 0+ value sigma w x'(0), and trapezoidal integration carries that inconsistent
  // start as an undamped step-to-step oscillation of the capacitor currents until the
  // first breakpoint (sample 1) restarts it with backward Euler.
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const std::vector<double> i_spice = on_grid(raw.column("i(v.x" + std::to_string(i) + ".vc)"), -1.0);
    const double error_i = relative_l2(i_spice, ours.current_a[i], 2);
    std::printf("relative L2 error vs ngspice: element %zu current %.3e\n", i, error_i);
    RecordProperty("relative_l2_error_i" + std::to_string(i), std::to_string(error_i));
    // Measured ~1e-6 (the reference's own error: gear gives up to 6e-6 at the same
    // settings). On the grid V has relaxed to its quasi-static value, so C_i dV/dt is
    // invisible there (it lives in the R sum C layers after each breakpoint); what the
    // currents test beyond sigma w x' (and the left-limit convention) is the (eps0 w
    // x'/d0) V term, ~4e-5 of the current: dropping it measures 3.5e-5 to 4e-5. 1e-5 sits
    // between, a factor 7 above what we reach.
    EXPECT_LE(error_i, 1e-5) << "element " << i;
    EXPECT_LE(relative_l2(i_spice, streamed.current_a[i], 2), 1e-5) << "streamed, element " << i;
  }

  if (!HasFailure()) std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace stengmc
