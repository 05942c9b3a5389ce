#pragma once
// What the shard and MPI tests share: small studies and the comparison of two output
// files by scripts/golden_digest.py's rule (every dataset and attribute, text attributes
// included, except those that record when, where or how fast a file was made).
#include <cstdlib>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"

namespace stengmc::testing {

//! Short Model 2 runs of the lognormal-count surface (4 asperities, random stiffnesses)
//! with noise and spectra; realisation 3 keeps its traces, so traces are merged too.
//! `ensemble` adds keys to [ensemble] (a sweep, a target).
inline std::string distributed_study(int realisations, const std::string& ensemble = "") {
  return "seed = 11\nduration_s = 10e-6\nsample_rate_hz = 100e6\n"
         "[model]\nkind = \"model2\"\nbelt_velocity_m_per_s = 10\n"
         "[surface]\nfile = \"" + std::string(STENGMC_SOURCE_DIR) + "/surfaces/lognormal_count.toml\"\n"
         "[domain]\npolicy = \"flag\"\n"
         "[spectrum]\nwindow = \"hann\"\nhigh_resolution = false\nmin_frequency_hz = 100e3\n"
         "[noise]\nsnr_db = 20\n"
         "[ensemble]\nrealisations = " + std::to_string(realisations) + "\ntrace_realisations = [3]\n" + ensemble;
}

//! A two-point sweep of the summit count for distributed_study.
inline const char* TWO_POINT_SWEEP = "[[ensemble.sweep]]\nparameter = \"surface.summits.count\"\nvalues = [2, 5]\n";

//! "" when `a` and `b` agree by golden_digest.py's `same`, else its report. `ignored`:
//! objects not compared ("/records/seconds", "/@threads").
inline std::string file_differences(const std::string& a, const std::string& b, const ScratchDir& scratch,
                                    const std::vector<std::string>& ignored = {}) {
  const std::string log = scratch.file("same.log");
  std::string command = "/usr/bin/python3 " + std::string(STENGMC_PYTHON_SCRIPTS) + "/golden_digest.py same " + a + " " + b;
  for (const std::string& object : ignored) command += " --ignore " + object;
  command += " > " + log + " 2>&1";
  const int status = std::system(command.c_str());
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return "golden_digest.py same: " + text.str();
}

}  // namespace stengmc::testing
