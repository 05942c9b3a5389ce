#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.hpp"
#include "app/limit_options.hpp"
#include "app/validators.hpp"
#include "circuit/element_sums.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "io/displacement_input.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "io/output_path.hpp"
#include "io/run_file.hpp"
#include "tribology/domain_check.hpp"
#include "tribology/sampled_motion.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc::app {

namespace {

struct CircuitOptions {
  std::string input;
  std::string out;
  std::string interpolation = "spline";
  CircuitParams params;
  StengElement csv_element;  // Table 2 defaults
  LimitOptions limits;
};

std::vector<std::unique_ptr<Motion>> interpolate(const DisplacementInput& input, Interpolation interpolation,
                                                 const std::string& file) {
  std::vector<std::unique_ptr<Motion>> motions;
  for (std::size_t i = 0; i < input.x_m.size(); ++i) {
    try {
      motions.push_back(std::make_unique<SampledMotion>(input.times_s, input.x_m[i], interpolation));
    } catch (const InputError& e) {
      throw InputError(file + ": element " + std::to_string(i + 1) + ": " + e.what());
    }
    // A spline can overshoot l between samples that all stay below it.
    try {
      if (const auto exit = first_domain_exit(*motions.back(), input.times_s, input.x_m[i], input.elements[i].length_m))
        throw InputError(file + ": element " + std::to_string(i + 1) + ": x reaches l = " +
                         std::to_string(input.elements[i].length_m) + " m at t = " + std::to_string(*exit) +
                         " s between samples (" + std::string(interpolation_name(interpolation)) +
                         " interpolation); the S-TENG element formulas (MODEL.md §2) hold only for x < l");
    } catch (const ModelError& e) {
      throw InputError(file + ": element " + std::to_string(i + 1) + ": " + e.what());
    }
  }
  return motions;
}

void run(const CircuitOptions& options) {
  check_output_path(options.out, {{options.input, "the displacement file"}});
  const bool csv = std::filesystem::path(options.input).extension() == ".csv";
  // A CSV of S bytes holds at most S/2 numbers: bound what reading it may cost first.
  if (csv)
    check_work(estimate_circuit(static_cast<double>(check_input_file(options.input, "the displacement CSV file")) / 2.0, 1.0,
                                options.params.substeps),
               options.limits.limits(), options.input + ": reading it");
  const DisplacementInput input = csv ? read_displacement_csv(options.input, options.csv_element)
                                      : read_displacement_hdf5(options.input);
  const Interpolation interpolation = parse_interpolation(options.interpolation, "--interpolation");
  check_work(estimate_circuit(static_cast<double>(input.times_s.size()), static_cast<double>(input.x_m.size()),
                              options.params.substeps),
             options.limits.limits(), options.input + ": the circuit");
  const auto motions = interpolate(input, interpolation, options.input);
  std::vector<const Motion*> pointers;
  for (const auto& m : motions) pointers.push_back(m.get());
  std::printf("stengmc circuit %s: %zu elements, %zu samples, %s interpolation, R = %.4g Ohm, C_L = %.4g F\n",
              options.input.c_str(), input.x_m.size(), input.times_s.size(), options.interpolation.c_str(),
              options.params.load_resistance_ohm, options.params.load_capacitance_f);
  Progress progress("circuit", input.times_s.size());
  const CircuitResult circuit = solve_circuit_streamed(input.elements, pointers, input.times_s, options.params, &progress);

  Hdf5Writer file(options.out, describe_output);
  Provenance provenance;
  provenance.file_type = "stengmc-circuit";
  provenance.input_file = options.input;
  write_provenance(file, provenance);
  file.attribute("/", "interpolation", interpolation_name(interpolation));
  file.write("/time", input.times_s);
  file.write("/asperity/x", input.x_m);
  // Left limits, like the currents: with linear interpolation x' of the interval that
  // ends at the sample (a PWL source's slope there), which is what produced V at t_j.
  std::vector<std::vector<double>> v(input.x_m.size());
  for (std::size_t i = 0; i < input.x_m.size(); ++i)
    for (double t : input.times_s) v[i].push_back(motions[i]->at(t, Side::left).v_m_per_s);
  file.write("/asperity/v", v);
  write_elements(file, input.elements);
  write_circuit(file, circuit, options.params);
  file.commit();
  double peak = 0.0;
  for (double x : circuit.voltage_v) peak = std::max(peak, std::abs(x));
  std::printf("voltage peak %.4g V; final charge %.4g C\nwrote %s\n", peak, circuit.charge_c.back(), options.out.c_str());
}

}  // namespace

void add_circuit_command(CLI::App& app) {
  auto options = std::make_shared<CircuitOptions>();
  CLI::App* command = app.add_subcommand(
      "circuit", "Drive the S-TENG circuit with displacements from a file (HDF5 in stengmc's layout, or CSV t,x1,...)");
  command->add_option("input", options->input, "IN.h5 (/time, /asperity/x, /asperity/{sigma,d0,w,l}) or IN.csv")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--out", options->out, "Output HDF5 file")
      ->required()
      ->check(non_empty_path());
  command->add_option("-R,--load-resistance", options->params.load_resistance_ohm, "Load resistance [Ohm]")
      ->required()
      ->check(finite_number(false));
  command->add_option("-C,--load-capacitance", options->params.load_capacitance_f, "Load capacitance [F]")
      ->capture_default_str()
      ->check(finite_number(true));
  command->add_option("--interpolation", options->interpolation, "x between samples: spline (not-a-knot) or linear (SPICE PWL)")
      ->capture_default_str()
      ->check(CLI::IsMember({"spline", "linear"}));
  command->add_option("--substeps", options->params.substeps, "Radau IIA steps per sample interval")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000).description("INTEGER in 1..1e6"));
  command->add_option("--sigma", options->csv_element.charge_density_c_per_m2, "CSV input: charge density [C/m^2]")
      ->capture_default_str();
  command->add_option("--d0", options->csv_element.effective_thickness_m, "CSV input: effective thickness [m]")
      ->capture_default_str()
      ->check(finite_number(false));
  command->add_option("--width", options->csv_element.width_m, "CSV input: element width w [m]")
      ->capture_default_str()
      ->check(finite_number(false));
  command->add_option("--length", options->csv_element.length_m, "CSV input: element length l [m]")
      ->capture_default_str()
      ->check(finite_number(false));
  add_limit_options(command, options->limits);
  command->callback([options] { run(*options); });
}

}  // namespace stengmc::app
