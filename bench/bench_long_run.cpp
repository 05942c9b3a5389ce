// Long records (issue 26, "Long records"): peak memory and time of `stengmc run` on 50
// excited asperities (Model 2, v_b = 5 m/s, [counterface] eps = 0.01, lambda = 0.5 um,
// 100 MHz, `[output] traces = []`) over 1 ms and 10 ms; the target is 10 ms within 2 GB.
// Each duration is run several times and the medians printed, with where the time goes
// (the run's own "time: tribology .., circuit .., spectra .." line) and the ratio
// 10 ms / 1 ms; with `--baseline PATH/stengmc` (a build of the revision before the
// motions were dropped) the 1 ms run against it (its 10 ms run would need ~18 GB).
//
//   build/bench/bench_long_run [--quick] [--baseline PATH/stengmc] [--binary PATH/stengmc]
//
// --quick: the 10 ms run once instead of three times.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.hpp"

namespace {

struct Options {
  bool quick = false;
  std::string binary = STENGMC_BINARY;
  std::string baseline;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") o.quick = true;
    else if (a == "--baseline" && i + 1 < argc) o.baseline = argv[++i];
    else if (a == "--binary" && i + 1 < argc) o.binary = argv[++i];
    else throw std::runtime_error("usage: bench_long_run [--quick] [--baseline PATH/stengmc] [--binary PATH/stengmc]");
  }
  return o;
}

//! 50 asperities, k = 40 .. 157.6 N/m (lines 1.0 .. 2.0 MHz), every one excited from t = 0.
std::string study_text(double duration_s, const std::string& out) {
  char head[512];
  std::snprintf(head, sizeof head,
                "duration_s = %.17g\nsample_rate_hz = 100e6\nseed = 7\n[model]\nkind = \"model2\"\n"
                "belt_velocity_m_per_s = 5\n[counterface]\nfriction_modulation_rms = 0.01\n"
                "correlation_length_m = 0.5e-6\n[output]\nfile = \"%s\"\ntraces = []\n",
                duration_s, out.c_str());
  std::string text = std::string(head) +
                     "[surface]\n[surface.defaults]\nmass_kg = 1e-12\nnormal_load_n = 1e-3\nheight_m = 110e-6\n"
                     "charge_density_c_per_m2 = 80e-6\neffective_thickness_m = 50e-6\nwidth_m = 10e-6\nlength_m = 50e-6\n";
  for (int i = 0; i < 50; ++i) {
    char line[96];
    std::snprintf(line, sizeof line, "[[surface.asperity]]\nstiffness_n_per_m = %.1f\n", 40.0 + 2.4 * i);
    text += line;
  }
  return text;
}

struct Measured {
  double wall_s = 0.0, cpu_s = 0.0, rss_mb = 0.0;
  double tribology_s = 0.0, circuit_s = 0.0, spectra_s = 0.0;  // the run's own split
};

//! One `run` under GNU time, its output kept for the run's own time split.
Measured measure(const std::string& binary, const bench::fs::path& study, const bench::fs::path& scratch) {
  const bench::fs::path log = scratch / "run.log";
  const std::string command = "/usr/bin/time -f 'RESOURCES %e %U %S %M' " + binary + " run " + study.string() + " > " +
                              log.string() + " 2>&1";
  if (std::system(command.c_str()) != 0) throw std::runtime_error(binary + " run " + study.string() + " failed: see " + log.string());
  const std::string text = bench::read_text(log);
  Measured m;
  const auto resources = text.rfind("RESOURCES ");
  double user = 0.0, system = 0.0, kib = 0.0;
  if (resources == std::string::npos ||
      std::sscanf(text.c_str() + resources, "RESOURCES %lf %lf %lf %lf", &m.wall_s, &user, &system, &kib) != 4)
    throw std::runtime_error("no resource line from /usr/bin/time in " + log.string());
  m.cpu_s = user + system;
  m.rss_mb = kib / 1024.0;
  const auto split = text.find("time: tribology ");
  if (split != std::string::npos)
    std::sscanf(text.c_str() + split, "time: tribology %lf s, circuit %lf s, spectra %lf s", &m.tribology_s, &m.circuit_s,
                &m.spectra_s);
  return m;
}

//! Medians of `repeats` runs.
Measured median_of(const std::string& binary, const bench::fs::path& study, const bench::fs::path& scratch, int repeats) {
  std::vector<double> wall, cpu, rss, tribology, circuit, spectra;
  for (int r = 0; r < repeats; ++r) {
    const Measured m = measure(binary, study, scratch);
    wall.push_back(m.wall_s);
    cpu.push_back(m.cpu_s);
    rss.push_back(m.rss_mb);
    tribology.push_back(m.tribology_s);
    circuit.push_back(m.circuit_s);
    spectra.push_back(m.spectra_s);
  }
  return {bench::median(wall), bench::median(cpu), bench::median(rss), bench::median(tribology), bench::median(circuit),
          bench::median(spectra)};
}

void print(const char* label, const Measured& m, int repeats) {
  std::printf("%-22s %9.2f %9.2f %10.0f %11.2f %9.3f   (median of %d)\n", label, m.wall_s, m.cpu_s, m.rss_mb, m.tribology_s,
              m.circuit_s, repeats);
  std::fflush(stdout);  // a row as soon as it is measured: the 10 ms series takes minutes
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    bench::ScratchDir scratch("long_run");
    const bench::fs::path short_study = scratch.path / "long_1ms.toml";
    const bench::fs::path long_study = scratch.path / "long_10ms.toml";
    bench::write_text(short_study, study_text(1e-3, (scratch.path / "long_1ms.h5").string()));
    bench::write_text(long_study, study_text(10e-3, (scratch.path / "long_10ms.h5").string()));
    const int short_repeats = 3, long_repeats = o.quick ? 1 : 3;

    std::printf("50 excited asperities (eps = 0.01, lambda = 0.5 um, v_b = 5 m/s), 100 MHz, traces = []\n");
    std::printf("%-22s %9s %9s %10s %11s %9s\n", "run", "wall [s]", "CPU [s]", "peak [MB]", "tribology", "circuit");
    const Measured one = median_of(o.binary, short_study, scratch.path, short_repeats);
    print("1 ms (1e5 samples)", one, short_repeats);
    const Measured ten = median_of(o.binary, long_study, scratch.path, long_repeats);
    print("10 ms (1e6 samples)", ten, long_repeats);
    std::printf("10 ms / 1 ms: %.1fx wall, %.2fx peak memory; 10 ms within 2 GB: %s (%.2f GB)\n", ten.wall_s / one.wall_s,
                ten.rss_mb / one.rss_mb, ten.rss_mb * 1048576.0 <= 2e9 ? "yes" : "NO", ten.rss_mb * 1048576.0 / 1e9);
    std::printf("time: %.0f %% in the tribology (RODAS4, a step per node of the modulation's grid), %.1f %% in the circuit\n",
                100.0 * ten.tribology_s / ten.wall_s, 100.0 * ten.circuit_s / ten.wall_s);
    if (!o.baseline.empty()) {
      const Measured base = median_of(o.baseline, short_study, scratch.path, short_repeats);
      print("1 ms, base revision", base, short_repeats);
      std::printf("1 ms against the base: %.2fx peak memory, %.2fx wall\n", base.rss_mb / one.rss_mb, base.wall_s / one.wall_s);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_long_run: %s\n", e.what());
    return 1;
  }
}
