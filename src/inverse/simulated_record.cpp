#include "inverse/simulated_record.hpp"

#include <memory>

#include "core/error.hpp"
#include "pipeline/run_study.hpp"
#include "surface/surface.hpp"

namespace stengmc {

std::vector<double> simulate_record(const KnownDevice& device, std::span<const double> k, const RecordGrid& grid) {
  std::vector<SimulatedAsperity> asperities;
  for (double stiffness : k) asperities.push_back({stiffness, device.asperity.normal_load_n, 0.0});
  return simulate_record(device, asperities, grid);
}

std::vector<double> simulate_record(const KnownDevice& device, std::span<const SimulatedAsperity> asperities,
                                    const RecordGrid& grid) {
  if (grid.start_s != 0.0) throw Error("simulate_record: the grid must start at t = 0");
  Study study;
  study.file = "(simulated record)";
  study.model = ModelKind::model2;
  study.model2 = device.model;
  study.circuit = device.circuit;
  study.sample_rate_hz = grid.sample_rate_hz();
  study.duration_s = grid.duration_s();
  for (const SimulatedAsperity& s : asperities) {
    Asperity a = device.asperity;
    a.stiffness_n_per_m = s.stiffness_n_per_m;
    a.normal_load_n = s.normal_load_n;
    a.onset_s = s.onset_s;
    study.asperities.push_back(a);
  }
  study.surface = std::make_shared<const Surface>(Surface::fixed_list(study.asperities));
  study.population = study.surface->sample(0, 0);
  RunOptions options;
  options.show_progress = false;
  options.keep_traces = false;  // only V is wanted
  RunResult result = run_study(study, options);
  if (!result.valid) throw ModelError("simulate_record: an asperity reached l");
  result.circuit.voltage_v.resize(grid.samples);
  return std::move(result.circuit.voltage_v);
}

}  // namespace stengmc
