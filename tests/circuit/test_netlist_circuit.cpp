// `[circuit] netlist` loads solved by the ngspice library (circuit/netlist_circuit.hpp)
// against the built-in solver (an independent solver: Radau IIA on the summed element
// equation, MODEL.md §2) and against a conservation law (the energy balance of a bridge
// rectifier, which no closed form covers). Both use the shipped examples in
// studies/circuits/, so what the README promises is what is tested.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "circuit/netlist_circuit.hpp"
#include "circuit/ngspice_runner.hpp"
#include "circuit/netlist_load.hpp"
#include "circuit/ngspice_library.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/hdf5_file.hpp"
#include "io/netlist_export.hpp"
#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"
#include "support/cli_runner.hpp"
#include "tribology/sampled_motion.hpp"

namespace stengmc {
namespace {

const std::string CIRCUITS = std::string(STENGMC_SOURCE_DIR) + "/studies/circuits/";

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test bug: '" + from + "' not in the text");
  return text.substr(0, at) + to + text.substr(at + from.size());
}

double relative_l2(const std::vector<double>& reference, const std::vector<double>& value) {
  double difference = 0.0, norm = 0.0;
  for (std::size_t k = 0; k < reference.size(); ++k) {
    difference += (reference[k] - value[k]) * (reference[k] - value[k]);
    norm += reference[k] * reference[k];
  }
  return std::sqrt(difference / norm);
}

RunOptions quiet() {
  RunOptions options;
  options.show_progress = false;
  return options;
}

TEST(NetlistCircuit, PaperResistorNetlistEqualsTheBuiltInSolver) {
  if (!ngspice_library_available()) GTEST_SKIP() << "built without ngspice (STENGMC_WITH_NGSPICE=OFF)";
  // The shipped study (four Table 2 asperities, l = 50 um, v_b = 10 m/s, 20 us at 100 MHz)
  // and the same study with the built-in 1 MOhm load in place of the netlist.
  const std::string path = CIRCUITS + "paper_resistor.toml";
  const std::string text = read_text(path);
  const Study through_ngspice = parse_study(text, path);
  const Study built_in = parse_study(replaced(text, "netlist = \"resistor_1meg.cir\"", "load_resistance_ohm = 1e6"), path);
  ASSERT_TRUE(through_ngspice.netlist);
  ASSERT_FALSE(built_in.netlist);
  const RunResult spice = run_study(through_ngspice, quiet());
  const RunResult reference = run_study(built_in, quiet());
  ASSERT_EQ(spice.circuit.voltage_v.size(), reference.circuit.voltage_v.size());

  const double error_v = relative_l2(reference.circuit.voltage_v, spice.circuit.voltage_v);
  const double error_q = relative_l2(reference.circuit.charge_c, spice.circuit.charge_c);
  std::printf("relative L2 against the built-in solver: V %.3e, Q %.3e\n", error_v, error_q);
  RecordProperty("relative_l2_error_v", std::to_string(error_v));
  // Measured 6.9e-6 on V and 1.1e-9 on Q (ngspice 39, reltol 1e-6, maximum step a tenth
  // of the sample step). That is ngspice's accuracy, not ours: its step control watches
  // the element charges (~100 V open-circuit voltages behind ~1e-16 F), not the ~10 mV
  // port voltage (NGSPICE-NOTES), and the built-in solver agrees with a tighter ngspice
  // run to 2e-9 (test_ngspice). The bound is 3x the measured figure: it catches a wrong
  // element or load (order 1), x(t) handed over as linear interpolation of the samples
  // (a first-order velocity error, ~6 % here) or a resampling error of ngspice's steps
  // onto the grid larger than its own.
  EXPECT_LE(error_v, 2e-5);
  // Q = integral of the port current (ngspice's) is where the capacitances show: 10 % of
  // sum C_i added as C_L moves Q by ~1e-5 (test_ngspice), 1e4 times the measured 1.1e-9.
  EXPECT_LE(error_q, 1e-8);

  // The element currents sum to the port current (Kirchhoff at the port: V / R here).
  ASSERT_EQ(spice.circuit.current_a.size(), 4u);
  double worst = 0.0, scale = 0.0;
  for (std::size_t j = 0; j < spice.circuit.voltage_v.size(); ++j) {
    double sum = 0.0;
    for (const auto& current : spice.circuit.current_a) sum += current[j];
    worst = std::max(worst, std::abs(sum - spice.circuit.voltage_v[j] / 1e6));
    scale = std::max(scale, std::abs(spice.circuit.voltage_v[j] / 1e6));
  }
  // Both sides are ngspice's own branch currents, resampled alike: equal to its Newton
  // tolerance (abstol = reltol x the current scale, ~1e-14 A against ~3e-8 A).
  EXPECT_LE(worst, 1e-4 * scale);
}

//! Trapezoidal integral of f * g over ngspice's time points.
double integral_of_product(const std::vector<double>& t, const std::vector<double>& f, const std::vector<double>& g) {
  double sum = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k)
    sum += 0.5 * (f[k] * g[k] + f[k - 1] * g[k - 1]) * (t[k] - t[k - 1]);
  return sum;
}

TEST(NetlistCircuit, BridgeRectifierEnergyBalanceCloses) {
  if (!ngspice_library_available()) GTEST_SKIP() << "built without ngspice (STENGMC_WITH_NGSPICE=OFF)";
  const Study study = read_study(CIRCUITS + "bridge_rectifier.toml");
  ASSERT_TRUE(study.netlist);
  const RunResult run = run_study(study, quiet());  // the motions the netlist run needs, kept
  std::vector<const Motion*> motions;
  std::vector<StengElement> elements;
  for (std::size_t i = 0; i < study.asperities.size(); ++i) {
    motions.push_back(run.trajectories[i].motion.get());
    elements.push_back(study.asperities[i].element);
  }
  // The same netlist, asked for the diode currents as well.
  const NetlistLoad& load = *study.netlist;
  const NetlistCircuitRun spice = solve_netlist_circuit(elements, motions, run.times_s, load, false,
                                                        {"v(vplus)", "v(vminus)", "@d1[id]", "@d2[id]", "@d3[id]", "@d4[id]"});
  // The run through the pipeline saw the same circuit.
  EXPECT_LE(relative_l2(run.circuit.voltage_v, spice.circuit.voltage_v), 1e-12);

  const std::vector<double>& t = spice.raw.time_s;
  const std::vector<double>& port_v = spice.raw.values[0];
  const std::vector<double>& port_i = spice.raw.values[1];
  const std::vector<double>& plus = spice.raw.values[2];
  const std::vector<double>& minus = spice.raw.values[3];
  std::vector<double> store_v(t.size()), zero(t.size(), 0.0);
  for (std::size_t k = 0; k < t.size(); ++k) store_v[k] = plus[k] - minus[k];
  auto difference = [&](const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> d(t.size());
    for (std::size_t k = 0; k < t.size(); ++k) d[k] = a[k] - b[k];
    return d;
  };
  constexpr double STORE_F = 0.1e-12, LOAD_OHM = 100e6;  // bridge_rectifier.cir
  const double delivered = integral_of_product(t, port_v, port_i);
  const double stored = 0.5 * STORE_F * (store_v.back() * store_v.back() - store_v.front() * store_v.front());
  std::vector<double> load_current(t.size());
  for (std::size_t k = 0; k < t.size(); ++k) load_current[k] = store_v[k] / LOAD_OHM;
  const double in_load = integral_of_product(t, store_v, load_current);
  // Each diode's anode minus cathode voltage times its current (RS included).
  const double in_diodes = integral_of_product(t, difference(port_v, plus), spice.raw.values[4]) +
                           integral_of_product(t, difference(zero, plus), spice.raw.values[5]) +
                           integral_of_product(t, difference(minus, port_v), spice.raw.values[6]) +
                           integral_of_product(t, difference(minus, zero), spice.raw.values[7]);
  const double imbalance = delivered - (stored + in_load + in_diodes);
  std::printf("energy: delivered %.4e J = stored %.4e + load %.4e + diodes %.4e J; imbalance %.2e (relative %.2e)\n",
              delivered, stored, in_load, in_diodes, imbalance, imbalance / delivered);
  RecordProperty("relative_energy_imbalance", std::to_string(imbalance / delivered));
  // The rectifier does harvest: the store is charged and the load takes energy.
  EXPECT_GT(stored, 0.0);
  EXPECT_GT(in_load, 0.0);
  EXPECT_GT(in_diodes, 0.0);
  // Energy conservation (Tellegen) at 1 %, the bound: each term is integrated
  // with the trapezoidal rule over ngspice's own steps, ngspice's own rule, so what is left
  // is its local error (reltol 1e-6) and the product of two trapezoidal integrands (O(h^2)
  // with h at most a tenth of the 10 ns sample step). Measured: see the printed line.
  EXPECT_LE(std::abs(imbalance), 0.01 * delivered);
}

TEST(NetlistCircuit, LoadNetlistsThatCannotWorkAreRejectedNamingTheFile) {
  // No element on the port node.
  try {
    parse_netlist_load("* title\nR1 a 0 1k\n", "load.cir");
    FAIL() << "a netlist without the port node was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("load.cir"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("steng"), std::string::npos) << e.what();
  }
  // An analysis card: stengmc sets the transient.
  try {
    parse_netlist_load("* title\nR1 steng 0 1k\n.tran 1n 1u\n", "load.cir");
    FAIL() << "a netlist with .tran was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("load.cir:3"), std::string::npos) << e.what();
  }
  // The title line never counts, .end ends it, comments are skipped.
  const NetlistLoad load = parse_netlist_load("R1 steng 0 1k title\n* c\nR2 steng 0 2k\n.end\nR3 x 0 1\n", "f.cir");
  ASSERT_EQ(load.lines.size(), 1u);
  EXPECT_EQ(load.lines[0], "R2 steng 0 2k");
}

TEST(NetlistCircuit, NgspiceErrorsExitWithStatusTwoNamingTheNetlist) {
  testing::ScratchDir scratch("netlist");
  const std::string study = read_text(CIRCUITS + "paper_resistor.toml");
  const std::string surface = std::string(STENGMC_SOURCE_DIR) + "/surfaces/paper_four_stiffnesses_l50.toml";
  auto run = [&](const std::string& netlist) {
    scratch.write("load.cir", netlist);
    const std::string text = replaced(replaced(replaced(study, "resistor_1meg.cir", "load.cir"),
                                               "../../surfaces/paper_four_stiffnesses_l50.toml", surface),
                                      "duration_s = 20e-6", "duration_s = 1e-6");
    return testing::run_cli("run " + scratch.write("study.toml", text) + " --out " + scratch.file("out.h5"), scratch);
  };
  if (!ngspice_library_available()) {  // a build without ngspice refuses a netlist study as bad input
    const auto refused = run("* load\nR1 steng 0 1e6\n");
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find("STENGMC_WITH_NGSPICE=OFF"), std::string::npos) << refused.output;
    return;
  }
  // A diode whose model is missing: ngspice refuses the circuit.
  const auto missing_model = run("* load\nD1 steng 0 nosuchmodel\nR1 steng 0 1e6\n");
  EXPECT_EQ(missing_model.exit_code, 2) << missing_model.output;
  EXPECT_NE(missing_model.output.find("load.cir"), std::string::npos) << missing_model.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5")));
  // A value ngspice cannot read: the message points at the line of the user's file.
  const auto bad_value = run("* load\n* a comment\nR1 steng 0 abc\n");
  EXPECT_EQ(bad_value.exit_code, 2) << bad_value.output;
  EXPECT_NE(bad_value.output.find("load.cir:3"), std::string::npos) << bad_value.output;
  // A good one writes the run file with the netlist recorded.
  const auto good = run("* load\nR1 steng 0 1e6\n");
  ASSERT_EQ(good.exit_code, 0) << good.output;
  Hdf5Reader file(scratch.file("out.h5"));
  EXPECT_EQ(file.string_attribute("/", "netlist_text"), "* load\nR1 steng 0 1e6\n");
}

//! The harvest of the README (scripts/rectifier_harvest.py): eight asperities on the bridge
//! rectifier. With ideal diodes (no junction capacitance) ngspice stops with "Timestep too
//! small": that is the solver failing on a netlist it took, exit 1 saying so, not bad input
//! (exit 2). The shipped netlist's 0.1 aF junctions integrate to the end.
TEST(NetlistCircuit, ARectifierNgspiceCannotFinishIsASolverFailureAndTheShippedOneFinishes) {
  if (!ngspice_library_available()) GTEST_SKIP() << "built without ngspice (STENGMC_WITH_NGSPICE=OFF)";
  testing::ScratchDir scratch("rectifier8");
  std::string asperities;
  for (const int k : {25, 50, 100, 155, 25, 50, 100, 155})
    asperities += "[[surface.asperity]]\nstiffness_n_per_m = " + std::to_string(k) + "\n";
  const std::string study = "duration_s = 2e-05\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\n"
                            "belt_velocity_m_per_s = 10\n[surface.defaults]\nlength_m = 50e-6\n" + asperities +
                            "[circuit]\nnetlist = \"rectifier.cir\"\n";
  const std::string shipped = read_text(CIRCUITS + "bridge_rectifier.cir");
  auto run = [&](const std::string& netlist) {
    scratch.write("rectifier.cir", netlist);
    std::filesystem::remove(scratch.file("out.h5"));
    return testing::run_cli("run " + scratch.write("study.toml", study) + " --out " + scratch.file("out.h5"), scratch);
  };
  const auto ideal = run(replaced(shipped, "CJO=1e-19", "CJO=0"));
  EXPECT_EQ(ideal.exit_code, 1) << ideal.output;
  EXPECT_NE(ideal.output.find("rectifier.cir: ngspice: the transient stopped"), std::string::npos) << ideal.output;
  EXPECT_NE(ideal.output.find("a solver failure"), std::string::npos) << ideal.output;
  EXPECT_EQ(ideal.output.find("input error"), std::string::npos) << ideal.output;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("out.h5")));
  const auto finished = run(shipped);
  EXPECT_EQ(finished.exit_code, 0) << finished.output;
}

//! `[circuit] probes`: the rectifier's storage node, its diodes' and load's currents,
//! recorded beside the port. Checked by circuit laws the probes do not share a code path
//! with: Ohm's law on Rload (i = (v(vplus) - v(vminus)) / 100 MOhm) and Kirchhoff's current
//! law at vplus (D1 and D2 feed Cstore and Rload), to ngspice's tolerances.
TEST(NetlistCircuit, ProbesRecordTheNetlistsNodesAndCurrentsAsCircuitLawsSay) {
  if (!ngspice_library_available()) GTEST_SKIP() << "built without ngspice (STENGMC_WITH_NGSPICE=OFF)";
  testing::ScratchDir scratch("probes");
  scratch.write("bridge_rectifier.cir", read_text(CIRCUITS + "bridge_rectifier.cir"));
  const std::string study = replaced(
      replaced(read_text(CIRCUITS + "bridge_rectifier.toml"), "../../surfaces",
               std::string(STENGMC_SOURCE_DIR) + "/surfaces"),
      "netlist = \"bridge_rectifier.cir\"",
      "netlist = \"bridge_rectifier.cir\"\nprobes = [\"v(vplus)\", \"V(vminus)\", \"i(d1)\", \"i(d2)\", \"i(cstore)\", \"i(rload)\"]");
  const auto r = testing::run_cli("run " + scratch.write("study.toml", study) + " -o " + scratch.file("out.h5"), scratch);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Hdf5Reader file(scratch.file("out.h5"));
  const auto plus = file.vector("/circuit/probes/v_vplus"), minus = file.vector("/circuit/probes/v_vminus");
  const auto d1 = file.vector("/circuit/probes/i_d1"), d2 = file.vector("/circuit/probes/i_d2");
  const auto store = file.vector("/circuit/probes/i_cstore"), load = file.vector("/circuit/probes/i_rload");
  EXPECT_EQ(file.string_attribute("/circuit/probes/v_vminus", "units"), "V");
  EXPECT_EQ(file.string_attribute("/circuit/probes/i_d1", "units"), "A");
  EXPECT_EQ(file.string_attribute("/circuit/probes/v_vminus", "spice_name"), "v(vminus)");
  ASSERT_EQ(plus.size(), file.vector("/time").size());
  double peak_load = 0.0, peak_diode = 0.0, ohm = 0.0, kirchhoff = 0.0;
  for (std::size_t j = 0; j < plus.size(); ++j) {
    peak_load = std::max(peak_load, std::abs(load[j]));
    peak_diode = std::max(peak_diode, std::abs(d1[j]) + std::abs(d2[j]));
    ohm = std::max(ohm, std::abs(load[j] - (plus[j] - minus[j]) / 100e6));
    kirchhoff = std::max(kirchhoff, std::abs(d1[j] + d2[j] - store[j] - load[j]));
  }
  ASSERT_GT(peak_load, 1e-10) << "the store never charged: nothing to check";
  EXPECT_LE(ohm, 1e-9 * peak_load);
  // ngspice's currents obey KCL to its abstol, scaled to the femtoamperes of these elements.
  EXPECT_LE(kirchhoff, 1e-3 * peak_diode);
}

TEST(NetlistCircuit, ProbesThatCannotBeRecordedAreRefusedAtTheirKey) {
  testing::ScratchDir scratch("probes-bad");
  scratch.write("load.cir", "* load\nR1 steng mid 1e6\nR2 mid 0 1e6\nQ1 mid steng 0 npn\n.model npn NPN\n");
  const std::string head = "duration_s = 1e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\n"
                           "[surface]\n[[surface.asperity]]\nstiffness_n_per_m = 75\n[circuit]\n";
  auto error_of = [&](const std::string& circuit) {
    try {
      (void)parse_study(head + circuit, scratch.file("study.toml"));
      return std::string("(no error)");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  EXPECT_EQ(error_of("netlist = \"load.cir\"\nprobes = [\"v(mid)\", \"i(r2)\", \"v(steng)\"]\n"), "(no error)");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"load_resistance_ohm = 1e6\nprobes = [\"v(mid)\"]\n", "it needs [circuit] netlist"},
      {"netlist = \"load.cir\"\nprobes = [\"v(nowhere)\"]\n", "names a node 'nowhere'"},
      {"netlist = \"load.cir\"\nprobes = [\"i(r9)\"]\n", "has no device 'r9'"},
      {"netlist = \"load.cir\"\nprobes = [\"p(mid)\"]\n", "write v(node)"},
      {"netlist = \"load.cir\"\nprobes = [\"v(a;b)\"]\n", "write v(node)"},
      {"netlist = \"load.cir\"\nprobes = [\"i(q1)\"]\n", "put a 0 V source in series"},
      {"netlist = \"load.cir\"\nprobes = [\"v(mid)\", \"V(MID)\"]\n", "listed twice"},
      {"netlist = \"load.cir\"\nprobes = [1]\n", "expected a string"}};
  for (const auto& [circuit, expected] : cases) {
    const std::string message = error_of(circuit);
    EXPECT_NE(message.find("[circuit] probes"), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

TEST(NetlistCircuit, ExportedNetlistRunsInNgspiceAsTheBuiltInSolverOnItsPwlInput) {
  const auto ngspice = test::find_ngspice();
  ASSERT_TRUE(ngspice.has_value()) << "no ngspice executable on PATH (scripts/setup.sh installs it)";
  // The resistor study, short (2 us: 200 PWL knots per element), with the built-in load.
  const std::string path = CIRCUITS + "paper_resistor.toml";
  const std::string text = replaced(replaced(read_text(path), "netlist = \"resistor_1meg.cir\"", "load_resistance_ohm = 1e6"),
                                    "duration_s = 20e-6", "duration_s = 2e-6");
  const Study study = parse_study(text, path);
  const RunResult run = run_study(study, quiet());
  const std::filesystem::path directory =
      test::make_unique_directory(std::filesystem::temp_directory_path(), "stengmc_export_");
  const std::string exported = export_netlist_text(study, run);
  {
    std::ofstream out(directory / "export.cir");
    out << exported;
  }
  // Knot times as a person writes them (3e-08, not 3.0000000000000004e-08), and a .save, so
  // the raw file holds the port and not every node of every element.
  EXPECT_NE(exported.find(" 3e-08 "), std::string::npos);
  {  // every knot time of the first element: at most 6 significant digits (j / 100 MHz, j < 200)
    const std::size_t from = exported.find("PWL(") + 4, to = exported.find(")", from);
    std::string block = exported.substr(from, to - from);
    std::replace(block.begin(), block.end(), '+', ' ');  // continuation marks (no exponent here has a '+')
    std::istringstream knots(block);
    std::string time, x;
    std::size_t count = 0;
    while (knots >> time >> x) {
      const std::string mantissa = time.substr(0, time.find('e'));
      std::size_t digits = 0;
      for (char c : mantissa) digits += std::isdigit(static_cast<unsigned char>(c)) ? 1 : 0;
      EXPECT_LE(digits, 6u) << time;
      ++count;
    }
    EXPECT_EQ(count, run.times_s.size());
  }
  EXPECT_NE(exported.find(".save v(steng) i(vstengmc_port)"), std::string::npos);
  const std::string command = "cd '" + directory.string() + "' && '" + ngspice->string() +
                              "' -b -r export.raw export.cir > ngspice.log 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text((directory / "ngspice.log").string());
  const test::RawFile raw = test::RawFile::read_binary(directory / "export.raw");
  const std::vector<double>& t = raw.column("time");
  ASSERT_NEAR(t.back(), run.times_s.back(), 1e-9 * run.times_s.back()) << "the transient stopped early";
  EXPECT_LT(std::filesystem::file_size(directory / "export.raw"), (t.size() + 1) * 4 * sizeof(double))
      << "more than time and the two saved vectors";

  // The reference: the built-in solver on exactly what the netlist holds, the samples
  // joined linearly (a PWL source; MODEL.md §2).
  std::vector<SampledMotion> motions;
  std::vector<const Motion*> pointers;
  std::vector<StengElement> elements;
  for (std::size_t i = 0; i < study.asperities.size(); ++i) {
    std::vector<double> x;
    for (double time : run.times_s) x.push_back(run.trajectories[i].motion->at(time).x_m);
    motions.emplace_back(run.times_s, x, Interpolation::linear);
    elements.push_back(study.asperities[i].element);
  }
  for (const SampledMotion& m : motions) pointers.push_back(&m);
  const CircuitResult reference = solve_circuit(elements, pointers, run.times_s, study.circuit);
  // Every PWL knot is a breakpoint ngspice steps onto: compare there.
  std::vector<double> v;
  for (double time : run.times_s) {
    const auto it = std::lower_bound(t.begin(), t.end(), time - 1e-6 * (run.times_s[1] - run.times_s[0]));
    ASSERT_TRUE(it != t.end());
    v.push_back(raw.column("v(steng)")[static_cast<std::size_t>(it - t.begin())]);
  }
  const double error_v = relative_l2(reference.voltage_v, v);
  std::printf("exported netlist in ngspice against the built-in solver on the same PWL input: V %.3e\n", error_v);
  // Measured 1.7e-7 (test_ngspice: 3.4e-7 for its own netlist of this subcircuit at the
  // same settings): ngspice's accuracy with a maximum step of a tenth of the sample step.
  // The bound, 1e-5, catches a wrong element, load, sign or time axis (order 1), a maximum
  // step left at the sample step (~1e-3, NGSPICE-NOTES) and displacements written with six
  // digits (their rounding, ~5e-12 m against ~5e-8 m per sample, is ~1e-4 in x').
  EXPECT_LE(error_v, 1e-5);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace stengmc
