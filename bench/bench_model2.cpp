// Model 2 tribology of the paper's Fig. 6 case: 4 asperities (k = 25, 50, 100, 155 N/m),
// 50 us at 100 MHz (5001 samples), Table 1/2 values, at v_b = 1 and 10 m/s. Everything
// solve_model2 does is timed: integration, dense output, sampling and event location.
#include <benchmark/benchmark.h>

#include <cstddef>

#include "tribology/model2.hpp"

namespace {

void fig6_tribology(benchmark::State& state, std::string_view form, bool propagator = true) {
  const stengmc::TimeGrid grid = stengmc::TimeGrid::covering(50e-6, 100e6);
  stengmc::Model2Params params;
  params.belt_velocity_m_per_s = static_cast<double>(state.range(0));
  params.friction_law = stengmc::find_friction_law(form);
  params.sliding_propagator = propagator;
  std::size_t steps = 0;
  std::size_t rejected = 0;
  for (auto _ : state) {
    steps = 0;
    rejected = 0;
    for (const double k : {25.0, 50.0, 100.0, 155.0}) {
      stengmc::Asperity asperity;
      asperity.stiffness_n_per_m = k;
      const stengmc::Trajectory t = stengmc::solve_model2(asperity, params, grid);
      benchmark::DoNotOptimize(t.x_m.data());
      steps += t.solver_steps;
      rejected += t.rejected_steps;
    }
  }
  // Per iteration (all 4 asperities), the same in every iteration.
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["rejected"] = static_cast<double>(rejected);
}

void BM_Fig6TribologyConsistent(benchmark::State& state) {
  fig6_tribology(state, "consistent");
}
void BM_Fig6TribologyLiteral(benchmark::State& state) { fig6_tribology(state, "literal"); }
// The previous code path: RODAS4 alone (no sliding propagator).
void BM_Fig6TribologyRodas4Only(benchmark::State& state) {
  fig6_tribology(state, "consistent", false);
}

// Both belt velocities, medians of 5 repetitions.
void fig6_cases(benchmark::internal::Benchmark* b) {
  b->ArgName("v_b")->Arg(1)->Arg(10)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
}
BENCHMARK(BM_Fig6TribologyConsistent)->Apply(fig6_cases);
BENCHMARK(BM_Fig6TribologyLiteral)->Apply(fig6_cases);
BENCHMARK(BM_Fig6TribologyRodas4Only)->Apply(fig6_cases);

}  // namespace

BENCHMARK_MAIN();
