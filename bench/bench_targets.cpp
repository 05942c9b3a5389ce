// The issue-12 targets in one run, each with its ratio against the previous code path
// (the same measurement on a build of the base revision, `--baseline PATH/stengmc`, or the
// previous algorithm still in the library) and the target it must meet:
//   1. ensemble: 1000 realisations x 20 asperities x 50 us, full pipeline, 2 threads;
//   2. the paper's four asperities (Fig. 6, l = 50 um, without [spectrum]) as a whole
//      process, start to file written, CPU time;
//   3. cost per realisation against the asperity count (16 .. 1024) and the duration
//      (12.5 .. 200 us, spectra included): log-log slopes;
//   4. memory per asperity of a realisation (traces not requested);
//   5. voltage_response: one asperity, 100 us at 100 MHz, through a reused workspace;
//   6. Model 2 tribology: sliding propagator against RODAS4 alone, with their accuracy;
//   7. the streamed circuit against the motion-node solver (previous circuit).
// Timings are medians; CPU times are reported beside wall times because other processes
// on a shared machine inflate wall time (the share they took is printed). `--quick` runs
// 100 ensemble realisations (extrapolated x10) and fewer repetitions; `--paper-only` runs
// target 2 alone (with `--baseline`, a minute).
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.hpp"
#include "circuit/circuit_solver.hpp"
#include "circuit/element_sums.hpp"
#include "ensemble/run_realisation.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/voltage_response.hpp"
#include "tribology/model2.hpp"

namespace {

namespace fs = std::filesystem;
using bench::Clock;

struct Options {
  bool quick = false;
  bool paper_only = false;  // only target 2, the paper case as a process
  std::string baseline;  // path of the base revision's stengmc, or empty
  std::string stengmc = STENGMC_BINARY;  // the binary measured (--binary: another build's)
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") o.quick = true;
    else if (a == "--paper-only") o.paper_only = true;
    else if (a == "--baseline" && i + 1 < argc) o.baseline = argv[++i];
    else if (a == "--binary" && i + 1 < argc) o.stengmc = argv[++i];
    else throw std::runtime_error("usage: bench_targets [--quick] [--paper-only] [--baseline PATH/stengmc] [--binary PATH/stengmc]");
  }
  if (const char* q = std::getenv("STENGMC_BENCH_QUICK"); q && *q && std::string(q) != "0") o.quick = true;
  return o;
}

//! One line of the final table.
struct Row {
  std::string target, value, goal, ratio;
  bool met = true;
};
std::vector<Row> rows;

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, format, a, b, c);
  return text;
}

//! The share of the machine other processes took while `work` ran.
template <class Work>
double others_share(Work&& work, double& wall_s, double& own_cpu_s) {
  const double busy0 = bench::machine_busy_seconds();
  work();
  const double busy = bench::machine_busy_seconds() - busy0;
  const double cores = static_cast<double>(std::thread::hardware_concurrency());
  return std::clamp((busy - own_cpu_s) / (cores * std::max(wall_s, 1e-9)), 0.0, 1.0);
}

// ---- 1. Ensemble headline --------------------------------------------------------------

void ensemble_headline(const Options& o, const bench::StudyFactory& factory, const fs::path& scratch) {
  const std::uint64_t realisations = o.quick ? 100 : 1000;
  const double scale = 1000.0 / static_cast<double>(realisations);
  const fs::path study = factory.file(20, 50e-6, realisations);
  auto run = [&](const std::string& binary, const char* out) {
    bench::ProcessRun r;
    double wall = 0.0, cpu = 0.0;
    const double others = others_share(
        [&] {
          r = bench::run_process({binary, "run", study.string(), "-j", "2", "--restart", "-o", (scratch / out).string()});
          wall = r.wall_s;
          cpu = r.cpu_s;
        },
        wall, cpu);
    if (r.exit_status != 0) throw std::runtime_error(binary + " run " + study.string() + " failed");
    std::printf("   %-9s wall %7.1f s, CPU %7.1f s (%.1f ms per realisation); others took %.0f %% of the machine\n",
                out, r.wall_s * scale, r.cpu_s * scale, 1e3 * r.cpu_s / static_cast<double>(realisations), 100 * others);
    return r;
  };
  std::printf("1. Ensemble: 1000 realisations x n = 20 x 50 us, full pipeline, 2 threads%s\n",
              o.quick ? " (--quick: 100 run, times x10)" : "");
  const bench::ProcessRun now = run(o.stengmc, "new.h5");
  Row row{"ensemble 1000 x 20 x 50 us, 2 threads", fmt("%.1f s wall, %.1f ms CPU / realisation", now.wall_s * scale,
                                                       1e3 * now.cpu_s / static_cast<double>(realisations)),
          "<= 10 s", "", now.wall_s * scale <= 10.0};
  if (!o.baseline.empty()) {
    const bench::ProcessRun old = run(o.baseline, "baseline.h5");
    row.ratio = fmt("%.1fx wall, %.1fx CPU vs base", old.wall_s / now.wall_s, old.cpu_s / now.cpu_s);
  }
  rows.push_back(row);
  std::printf("\n");
}

// ---- 2. Paper case as a process ----------------------------------------------------------

void paper_process(const Options& o, const fs::path& scratch) {
  // The target is a run of stengmc as a user starts it: its own runs back to back. The
  // ratio to the base comes from a second series, interleaved (now, base, now, base, ...):
  // a few ms per run, so the machine's load drifts between runs of one binary, and
  // interleaving gives both the same drift; but each run then starts after the other
  // binary, whose libraries (the base loads ~30) have pushed its own out of the caches.
  const int repetitions = o.quick ? 5 : 31;
  std::printf("2. The paper's four asperities (Fig. 6, l = 50 um, no [spectrum]) as a process: CPU, median of %d runs "
              "back to back%s\n",
              repetitions, o.baseline.empty() ? "" : "; against the base, a second series interleaved with it");
  for (const char* name : {"fig6_vb1_l50", "fig6_vb10_l50"}) {
    // The paper study without its [spectrum] table, the surface path made absolute.
    std::string text = bench::read_text(fs::path(STENGMC_SOURCE_DIR) / "studies" / "paper" / (std::string(name) + ".toml"));
    text = text.substr(0, text.find("\n[spectrum]"));
    const std::string from = "../../surfaces/";
    text.replace(text.find(from), from.size(), std::string(STENGMC_SOURCE_DIR) + "/surfaces/");
    const fs::path study = scratch / (std::string(name) + "_nospectrum.toml");
    bench::write_text(study, text + "\n");
    auto cpu_of = [&](const std::string& binary) {
      // stengmc's own CPU: not through GNU time, whose start would count too (~1.4 ms).
      const bench::ProcessRun run = bench::run_process({binary, "run", study.string(), "-o", (scratch / "paper.h5").string()},
                                                       bench::PeakMemory::not_measured);
      if (run.exit_status != 0) throw std::runtime_error(binary + " run " + study.string() + " failed");
      return run.cpu_s;
    };
    std::vector<double> alone_cpu;
    for (int r = 0; r < repetitions; ++r) alone_cpu.push_back(cpu_of(o.stengmc));
    const double now = bench::median(alone_cpu);
    Row row{std::string("paper case process, ") + name, fmt("%.1f ms CPU", 1e3 * now), "<= 10 ms", "", now <= 0.010};
    std::printf("   %-14s %6.1f ms", name, 1e3 * now);
    if (!o.baseline.empty()) {
      std::vector<double> now_cpu, old_cpu;
      for (int r = 0; r < repetitions; ++r) {
        now_cpu.push_back(cpu_of(o.stengmc));
        old_cpu.push_back(cpu_of(o.baseline));
      }
      const double paired = bench::median(now_cpu), old = bench::median(old_cpu);
      row.ratio = fmt("%.1fx vs base (interleaved: %.1f against %.1f ms)", old / paired, 1e3 * paired, 1e3 * old);
      std::printf("   interleaved with the base: %6.1f against %6.1f ms (%.1fx)", 1e3 * paired, 1e3 * old, old / paired);
    }
    std::printf("\n");
    rows.push_back(row);
  }
  std::printf("\n");
}

// ---- 3. Scaling --------------------------------------------------------------------------

//! Thread CPU time of run_realisation, per realisation, over ids 0 .. count-1.
double cpu_per_realisation(const stengmc::StudyFile& base, std::uint64_t count) {
  stengmc::run_realisation(base, 0, false);  // warm-up: plans, allocator
  const double start = bench::thread_cpu_seconds();
  for (std::uint64_t id = 0; id < count; ++id) stengmc::run_realisation(base, id, false);
  return (bench::thread_cpu_seconds() - start) / static_cast<double>(count);
}

//! CPU per realisation of the base revision: its process for 1 + `extra` realisations
//! minus its process for one, over `extra` (start-up, summary and file writing cancel).
double baseline_cpu(const Options& o, const bench::StudyFactory& factory, int count, double duration_s,
                    const fs::path& scratch, std::uint64_t extra) {
  double cpu[2];
  int k = 0;
  for (const std::uint64_t r : {std::uint64_t{1}, 1 + extra}) {
    const bench::ProcessRun run = bench::run_process({o.baseline, "run", factory.file(count, duration_s, r).string(), "-j",
                                                      "1", "--restart", "-o", (scratch / "b.h5").string()});
    if (run.exit_status != 0) throw std::runtime_error(o.baseline + ": realisation failed");
    cpu[k++] = run.cpu_s;
  }
  return (cpu[1] - cpu[0]) / static_cast<double>(extra);
}

void scaling(const Options& o, const bench::StudyFactory& factory, const fs::path& scratch) {
  std::printf("3. Cost per realisation (one thread, CPU, mean over realisations; spectra included)\n");
  const std::vector<int> counts = o.quick ? std::vector<int>{16, 64, 256, 1024} : std::vector<int>{16, 32, 64, 128, 256, 512, 1024};
  std::vector<double> nx, ny;
  for (int n : counts) {
    const std::uint64_t reps = std::max<std::uint64_t>(2, (o.quick ? 512 : 2048) / static_cast<std::uint64_t>(n));
    const double per = cpu_per_realisation(factory.make(n, 50e-6, reps), reps);
    nx.push_back(n);
    ny.push_back(per);
    std::printf("   n = %4d, 50 us: %8.2f ms  (%.3f ms per asperity)\n", n, 1e3 * per, 1e3 * per / n);
  }
  const std::vector<double> durations{12.5e-6, 25e-6, 50e-6, 100e-6, 200e-6};
  std::vector<double> tx, ty;
  for (double d : durations) {
    const std::uint64_t reps = o.quick ? 4 : 10;
    const double per = cpu_per_realisation(factory.make(20, d, reps), reps);
    tx.push_back(d);
    ty.push_back(per);
    std::printf("   n =   20, %5.1f us: %6.2f ms\n", 1e6 * d, 1e3 * per);
  }
  const double slope_n = bench::loglog_slope(nx, ny), slope_t = bench::loglog_slope(tx, ty);
  std::printf("   slopes: cost ~ n^%.3f (16..1024), ~ T^%.3f (12.5..200 us)\n", slope_n, slope_t);
  Row rn{"cost vs asperities n = 16..1024", fmt("n^%.3f (%.2f ms at 16, %.0f ms at 1024)", slope_n, 1e3 * ny.front(), 1e3 * ny.back()),
         "exponent <= 1.05", "", slope_n <= 1.05};
  Row rt{"cost vs duration T = 12.5..200 us", fmt("T^%.3f (%.2f ms at 12.5 us, %.1f ms at 200 us)", slope_t, 1e3 * ty.front(), 1e3 * ty.back()),
         "exponent <= 1.05", "", slope_t <= 1.05};
  if (!o.baseline.empty()) {
    // The base revision on the ends of both ranges.
    const double n16 = baseline_cpu(o, factory, 16, 50e-6, scratch, 8);
    const double n1024 = baseline_cpu(o, factory, 1024, 50e-6, scratch, 1);
    const double t12 = baseline_cpu(o, factory, 20, 12.5e-6, scratch, 16);
    const double t200 = baseline_cpu(o, factory, 20, 200e-6, scratch, 4);
    const double old_n = std::log(n1024 / n16) / std::log(1024.0 / 16.0);
    const double old_t = std::log(t200 / t12) / std::log(16.0);
    std::printf("   base: n = 16 %.1f ms, n = 1024 %.0f ms (n^%.2f); T = 12.5 us %.1f ms, 200 us %.1f ms (T^%.2f)\n",
                1e3 * n16, 1e3 * n1024, old_n, 1e3 * t12, 1e3 * t200, old_t);
    rn.ratio = fmt("base n^%.2f; %.1fx faster at n = 1024", old_n, n1024 / ny.back());
    rt.ratio = fmt("base T^%.2f; %.1fx faster at 200 us", old_t, t200 / ty.back());
  }
  rows.push_back(rn);
  rows.push_back(rt);
  std::printf("\n");
}

// ---- 4. Memory -----------------------------------------------------------------------------

void memory(const Options& o, const bench::StudyFactory& factory, const fs::path& scratch) {
  std::printf("4. Memory per asperity (peak resident memory of one realisation, n = 16 and 1024, 50 us, no traces)\n");
  auto per_asperity = [&](const std::string& binary) {
    double rss[2];
    int k = 0;
    for (int n : {16, 1024}) {
      const bench::ProcessRun run = bench::run_process(
          {binary, "run", factory.file(n, 50e-6, 1).string(), "-j", "1", "--restart", "-o", (scratch / "m.h5").string()});
      if (run.exit_status != 0) throw std::runtime_error(binary + ": realisation failed");
      rss[k++] = run.max_rss_mb;
    }
    std::printf("   %s: peak %.1f MiB at n = 16, %.1f MiB at n = 1024\n", binary == o.stengmc ? "now " : "base", rss[0], rss[1]);
    return (rss[1] - rss[0]) / (1024 - 16) * 1024.0;  // KiB
  };
  const double now = per_asperity(o.stengmc);
  std::printf("   %.1f KiB per asperity", now);
  Row row{"memory per asperity (no traces)", fmt("%.1f KiB", now), "half of base or less", "", true};
  if (!o.baseline.empty()) {
    const double old = per_asperity(o.baseline);
    std::printf(", base %.1f KiB (%.1fx)", old, old / now);
    row.ratio = fmt("%.1fx less than base (%.0f KiB)", old / now, old);
    row.met = now <= 0.5 * old;
  }
  std::printf("\n\n");
  rows.push_back(row);
}

// ---- 5. voltage_response -------------------------------------------------------------------

void single_asperity(const Options& o) {
  std::printf("5. voltage_response: one asperity, 100 us at 100 MHz, Model 2, l = 50 um, R = 1 MOhm, k = 20..300 N/m\n");
  const stengmc::TimeGrid grid = stengmc::TimeGrid::covering(100e-6, 100e6);
  stengmc::CircuitParams circuit;
  stengmc::VoltageWorkspace workspace;
  std::vector<double> times, full;
  const int passes = o.quick ? 2 : 5;
  for (double vb : {5.0, 10.0}) {
    stengmc::Model2Params model;
    model.belt_velocity_m_per_s = vb;
    std::vector<double> per_call;
    for (int pass = 0; pass < passes; ++pass) {
      for (double k = 20.0; k <= 300.0; k += 20.0) {
        stengmc::Asperity a;
        a.stiffness_n_per_m = k;
        a.element.length_m = 50e-6;
        const double start = bench::thread_cpu_seconds();
        (void)stengmc::voltage_response({&a, 1}, model, circuit, grid, workspace);
        per_call.push_back(bench::thread_cpu_seconds() - start);
      }
    }
    // The same asperity through the whole pipeline (run_study), for scale.
    const std::string text = "duration_s = 100e-6\nsample_rate_hz = 100e6\n[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = " +
                             std::to_string(vb) +
                             "\n[surface]\n[[surface.asperity]]\nstiffness_n_per_m = 100\nlength_m = 50e-6\n";
    const stengmc::Study study = stengmc::parse_study(text, "single.toml");
    std::vector<double> pipeline;
    for (int r = 0; r < 3 * passes; ++r) {
      const double start = bench::thread_cpu_seconds();
      (void)stengmc::run_study(study, stengmc::RunOptions{.show_progress = false});
      pipeline.push_back(bench::thread_cpu_seconds() - start);
    }
    // With one circuit substep per sample (chain accuracy still V ~1e-6, test_chain_reference).
    stengmc::CircuitParams coarse = circuit;
    coarse.substeps = 1;
    std::vector<double> per_call_coarse;
    for (double k = 20.0; k <= 300.0; k += 20.0) {
      stengmc::Asperity a;
      a.stiffness_n_per_m = k;
      a.element.length_m = 50e-6;
      const double start = bench::thread_cpu_seconds();
      (void)stengmc::voltage_response({&a, 1}, model, coarse, grid, workspace);
      per_call_coarse.push_back(bench::thread_cpu_seconds() - start);
    }
    const double m = bench::median(per_call), p = bench::median(pipeline);
    std::printf("   v_b = %4.1f m/s: median %.3f ms per call (%zu calls; %.3f ms with circuit substeps = 1); "
                "run_study with traces %.3f ms (%.1fx)\n",
                vb, 1e3 * m, per_call.size(), 1e3 * bench::median(per_call_coarse), 1e3 * p, p / m);
    rows.push_back({fmt("single asperity 100 us, v_b = %g m/s", vb), fmt("%.3f ms per call", 1e3 * m), "cheap (no target)",
                    fmt("%.1fx a full run_study", p / m), true});
  }
  std::printf("\n");
}

// ---- 6. Tribology ------------------------------------------------------------------------

double max_relative_difference(const std::vector<double>& a, const std::vector<double>& ref) {
  double d = 0.0, s = 0.0;
  for (std::size_t j = 0; j < ref.size(); ++j) {
    d = std::max(d, std::abs(a[j] - ref[j]));
    s = std::max(s, std::abs(ref[j]));
  }
  return d / s;
}

void tribology(const Options& o) {
  std::printf("6. Model 2 tribology (Table 1, 50 us at 100 MHz, consistent form): RODAS4 alone vs with the sliding propagator\n");
  std::printf("   %-5s %-5s %12s %12s %7s %11s %11s\n", "v_b", "k", "RODAS4 [us]", "new [us]", "ratio", "err RODAS4", "err new");
  const stengmc::TimeGrid grid = stengmc::TimeGrid::covering(50e-6, 100e6);
  const int repetitions = o.quick ? 5 : 15;
  double total_old = 0.0, total_new = 0.0, worst_old = 0.0, worst_new = 0.0;
  for (double vb : {1.0, 10.0}) {
    for (double k : {25.0, 50.0, 100.0, 155.0}) {
      stengmc::Asperity a;
      a.stiffness_n_per_m = k;
      stengmc::Model2Params fast;
      fast.belt_velocity_m_per_s = vb;
      stengmc::Model2Params old = fast;
      old.sliding_propagator = false;
      stengmc::Model2Params tight = old;
      tight.relative_tolerance = 1e-12;
      const stengmc::Trajectory ref = stengmc::solve_model2(a, tight, grid);
      std::vector<double> t_old, t_new;
      stengmc::Trajectory r_old, r_new;
      for (int r = 0; r < repetitions; ++r) {
        double s = bench::thread_cpu_seconds();
        r_old = stengmc::solve_model2(a, old, grid);
        t_old.push_back(bench::thread_cpu_seconds() - s);
        s = bench::thread_cpu_seconds();
        r_new = stengmc::solve_model2(a, fast, grid);
        t_new.push_back(bench::thread_cpu_seconds() - s);
      }
      const double mo = bench::median(t_old), mn = bench::median(t_new);
      const double eo = max_relative_difference(r_old.x_m, ref.x_m), en = max_relative_difference(r_new.x_m, ref.x_m);
      total_old += mo;
      total_new += mn;
      worst_old = std::max(worst_old, eo);
      worst_new = std::max(worst_new, en);
      std::printf("   %-5g %-5g %12.1f %12.1f %6.1fx %11.2e %11.2e\n", vb, k, 1e6 * mo, 1e6 * mn, mo / mn, eo, en);
    }
  }
  std::printf("   (error: max |x - x_ref| / max |x_ref|, x_ref RODAS4 at 1e-12)\n\n");
  rows.push_back({"Model 2 tribology, 8 Table-1 cases", fmt("%.2f ms in all, worst error %.1e", 1e3 * total_new, worst_new),
                  "error <= 1e-6", fmt("%.1fx vs RODAS4 alone (worst error %.1e)", total_old / total_new, worst_old),
                  worst_new <= 1e-6});
}

// ---- 7. Circuit ------------------------------------------------------------------------------

void circuit(const Options& o) {
  std::printf("7. Circuit of the paper's four asperities (Fig. 6 v_b = 10, l = 50 um): motion-node solver vs streamed\n");
  stengmc::Study study = stengmc::read_study(std::string(STENGMC_SOURCE_DIR) + "/studies/paper/fig6_vb10_l50.toml");
  study.spectrum.reset();
  const stengmc::RunResult run = stengmc::run_study(study, stengmc::RunOptions{.show_progress = false});
  std::vector<const stengmc::Motion*> motions;
  std::vector<stengmc::StengElement> elements;
  for (std::size_t i = 0; i < study.asperities.size(); ++i) {
    motions.push_back(run.trajectories[i].motion.get());
    elements.push_back(study.asperities[i].element);
  }
  const int repetitions = o.quick ? 3 : 9;
  std::vector<double> t_old, t_new;
  for (int r = 0; r < repetitions; ++r) {
    double s = bench::thread_cpu_seconds();
    (void)stengmc::solve_circuit(elements, motions, run.times_s, study.circuit);
    t_old.push_back(bench::thread_cpu_seconds() - s);
    s = bench::thread_cpu_seconds();
    (void)stengmc::solve_circuit_streamed(elements, motions, run.times_s, study.circuit);
    t_new.push_back(bench::thread_cpu_seconds() - s);
  }
  const double mo = bench::median(t_old), mn = bench::median(t_new);
  std::printf("   motion-node solver %.2f ms, streamed %.2f ms (%.1fx); both with element currents\n\n", 1e3 * mo, 1e3 * mn,
              mo / mn);
  rows.push_back({"circuit, four asperities x 5001 samples", fmt("%.2f ms", 1e3 * mn), "", fmt("%.1fx vs motion-node solver", mo / mn), true});
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  const auto start = Clock::now();
  bench::ScratchDir scratch("bench_targets");
  const bench::StudyFactory factory(STENGMC_SOURCE_DIR, scratch.path);
  std::printf("stengmc benchmark targets (issue 12): %u hardware threads, %s build%s\n\n",
              std::thread::hardware_concurrency(), STENGMC_BUILD_TYPE,
              o.baseline.empty() ? ", no baseline given (--baseline PATH/stengmc for the ratios)" : "");
  if (o.paper_only) {
    paper_process(o, scratch.path);
  } else {
    ensemble_headline(o, factory, scratch.path);
    paper_process(o, scratch.path);
    scaling(o, factory, scratch.path);
    memory(o, factory, scratch.path);
    single_asperity(o);
    tribology(o);
    circuit(o);
  }
  std::printf("| target | value | goal | ratio | met |\n|---|---|---|---|---|\n");
  for (const Row& r : rows)
    std::printf("| %s | %s | %s | %s | %s |\n", r.target.c_str(), r.value.c_str(), r.goal.c_str(), r.ratio.c_str(),
                r.goal.empty() || r.goal == "cheap (no target)" ? "" : (r.met ? "yes" : "NO"));
  std::printf("\nTotal benchmark time %.0f s\n", std::chrono::duration<double>(Clock::now() - start).count());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench_targets: %s\n", e.what());
  return 1;
}
