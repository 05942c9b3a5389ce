#include "inverse/bank_identity.hpp"

#include <cmath>
#include <sstream>

#include "core/build_info.hpp"
#include "core/checksum.hpp"

namespace stengmc {

namespace {

//! The lines of `a` not in `b`, joined (for messages).
std::string changed_lines(const std::string& a, const std::string& b) {
  std::istringstream in(a);
  std::string line, out;
  while (std::getline(in, line))
    if (("\n" + b).find("\n" + line + "\n") == std::string::npos) out += (out.empty() ? "" : ", ") + line;
  return out;
}

}  // namespace

BankIdentity bank_identity(const KnownDevice& device, const InversePrior& prior, const RecordGrid& grid) {
  BankIdentity id;
  id.device = device.describe();
  // The calibration size and seed are part of the prior's text but not of what the bank
  // describes: a bigger bank of the same prior is the same bank, better estimated.
  InversePrior what = prior;
  what.calibration_records = 0;
  what.seed = 0;
  id.prior = what.describe();
  std::ostringstream g;
  g.precision(17);
  g << "start_s = " << grid.start_s << "\nstep_s = " << grid.step_s << "\nsamples = " << grid.samples << "\n";
  id.grid = g.str();
  id.estimator = std::string("program_version = ") + program_version() + "\nestimator_version = " +
                 std::to_string(ESTIMATOR_VERSION) + "\n";
  id.hash = fnv1a64(id.estimator, fnv1a64(id.grid, fnv1a64(id.prior, fnv1a64(id.device))));
  return id;
}

std::string BankIdentity::differences(const BankIdentity& other) const {
  std::string out;
  auto part = [&](const char* what, const std::string& mine, const std::string& theirs) {
    if (mine == theirs) return;
    out += (out.empty() ? "" : "; ") + std::string(what) + " (bank: " + changed_lines(mine, theirs) +
           "; here: " + changed_lines(theirs, mine) + ")";
  };
  part("known parameters", device, other.device);
  part("prior", prior, other.prior);
  part("record grid", grid, other.grid);
  part("estimator", estimator, other.estimator);
  return out;
}

RecordGrid device_grid(const KnownDevice& device) {
  const auto intervals = static_cast<std::size_t>(std::llround(device.duration_s * device.sample_rate_hz));
  return {0.0, 1.0 / device.sample_rate_hz, intervals + 1};
}

}  // namespace stengmc
