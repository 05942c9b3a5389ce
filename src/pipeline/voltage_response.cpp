#include "pipeline/voltage_response.hpp"

#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "circuit/element_sums.hpp"
#include "core/error.hpp"
#include "tribology/domain_check.hpp"
#include "tribology/model2_integrator.hpp"
#include "tribology/model2_motion.hpp"

namespace stengmc {

struct VoltageWorkspace::Buffers {
  std::vector<double> times;
  ElementSums sums;
  MotionSamples samples;
  //! One motion per asperity: the circuit may evaluate a motion (the belt's catch) while
  //! it solves, so all stay alive until then; their knots are reused by the next call.
  std::vector<std::optional<Model2Motion>> motions;
  std::vector<Model2Integration> spare;  // integrations released by last call's motions
  SummedCircuit circuit;
  std::size_t cached_count = 0;
  double cached_step = 0.0;
};

VoltageWorkspace::VoltageWorkspace() : buffers_(std::make_unique<Buffers>()) {}
VoltageWorkspace::~VoltageWorkspace() = default;

namespace {

std::string exit_message(std::size_t index, const Asperity& a, double time_s) {
  char text[256];
  std::snprintf(text, sizeof text,
                "asperity %zu (k = %g N/m): x reaches l = %g um at t = %g us; the S-TENG element formulas "
                "(MODEL.md §2) hold only for x < l",
                index + 1, a.stiffness_n_per_m, a.element.length_m * 1e6, time_s * 1e6);
  return text;
}

}  // namespace

VoltageResponse voltage_response(std::span<const Asperity> asperities, const Model2Params& model,
                                 const CircuitParams& circuit, const TimeGrid& grid, VoltageWorkspace& workspace) {
  VoltageWorkspace::Buffers& b = workspace.buffers();
  if (b.cached_count != grid.count || b.cached_step != grid.step_s) {
    b.times = grid.times();
    b.cached_count = grid.count;
    b.cached_step = grid.step_s;
  }
  const std::span<const double> times(b.times);
  const double t_end = grid.count > 0 ? grid.at(grid.count - 1) : 0.0;

  // Last call's knots come back for this call's integrations.
  for (std::optional<Model2Motion>& m : b.motions)
    if (m) {
      b.spare.push_back(std::move(*m).release());
      m.reset();
    }
  b.motions.resize(asperities.size());
  b.sums.reset(times);
  std::size_t steps = 0;
  for (std::size_t i = 0; i < asperities.size(); ++i) {
    const Asperity& a = asperities[i];
    Model2Integration integration;
    if (!b.spare.empty()) {
      integration = std::move(b.spare.back());
      b.spare.pop_back();
    }
    integrate_model2(a, model, t_end, integration);
    steps += integration.accepted_steps;
    b.motions[i].emplace(std::move(integration));
    const Model2Motion& motion = *b.motions[i];
    motion.sample(times, true, b.samples);
    std::optional<double> exit;
    try {
      exit = first_domain_exit(motion, times, b.samples, a.element.length_m);
    } catch (const ModelError& e) {
      throw ModelError("asperity " + std::to_string(i + 1) + ": " + e.what());
    }
    if (exit) throw ModelError(exit_message(i, a, *exit));
    b.sums.add(a.element, b.samples, motion);
  }
  solve_summed_circuit(b.sums, times.size(), circuit, b.circuit);
  return {times, b.circuit.voltage_v, b.circuit.charge_c, steps};
}

}  // namespace stengmc
