// One asperity-run for bench/compare_scipy.py: Model 2 from rest to 50 us, x and x' on
// the 5001-point grid at 100 MHz (what scipy's solve_ivp returns with t_eval), timed as
// thread CPU time; x written as raw doubles for the script's accuracy check; prints the
// median time per run, the accepted steps and the median time of the integration alone
// (timed in a loop of its own; the rest is the sampling). Each of the REPETITIONS
// measurements times a batch of BATCH runs back to back and divides: one reading of the
// thread's CPU clock is a system call here (~0.6 us, 1-2 % of a run), which a run timed
// alone would carry once. Buffers are reused between runs, as a caller looping would.
//   bench_asperity_run V_B K TOLERANCE REPETITIONS OUT.bin
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "bench_support.hpp"
#include "tribology/model2.hpp"
#include "tribology/model2_integrator.hpp"
#include "tribology/model2_motion.hpp"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: bench_asperity_run V_B K TOLERANCE REPETITIONS OUT.bin\n");
    return 2;
  }
  stengmc::Model2Params params;
  params.belt_velocity_m_per_s = std::atof(argv[1]);
  params.relative_tolerance = std::atof(argv[3]);
  stengmc::Asperity asperity;
  asperity.stiffness_n_per_m = std::atof(argv[2]);
  const int repetitions = std::atoi(argv[4]);
  const stengmc::TimeGrid grid = stengmc::TimeGrid::covering(50e-6, 100e6);
  const std::vector<double> times = grid.times();
  stengmc::Model2Integration integration;
  stengmc::MotionSamples samples;
  constexpr int BATCH = 10;
  std::vector<double> seconds;
  std::vector<double> integration_seconds;
  for (int r = 0; r < repetitions; ++r) {
    const double start = bench::thread_cpu_seconds();
    for (int b = 0; b < BATCH; ++b) {
      stengmc::integrate_model2(asperity, params, times.back(), integration);
      stengmc::Model2Motion motion(std::move(integration));
      motion.sample(times, false, samples);
      integration = std::move(motion).release();
    }
    seconds.push_back((bench::thread_cpu_seconds() - start) / BATCH);
  }
  for (int r = 0; r < repetitions; ++r) {
    const double start = bench::thread_cpu_seconds();
    for (int b = 0; b < BATCH; ++b) stengmc::integrate_model2(asperity, params, times.back(), integration);
    integration_seconds.push_back((bench::thread_cpu_seconds() - start) / BATCH);
  }
  const std::size_t steps = integration.accepted_steps;
  const std::size_t propagator_steps = integration.oscillator_steps;
  const std::size_t rejected = integration.rejected_steps;
  std::fprintf(stderr, "steps %zu (propagator %zu), rejected %zu\n", steps, propagator_steps, rejected);
  std::ofstream out(argv[5], std::ios::binary);
  out.write(reinterpret_cast<const char*>(samples.x_m.data()), static_cast<std::streamsize>(samples.x_m.size() * sizeof(double)));
  // Total, steps, then the integration alone (the rest is the sampling).
  std::printf("%.9g %zu %.9g\n", bench::median(seconds), steps, bench::median(integration_seconds));
  return out ? 0 : 1;
}
