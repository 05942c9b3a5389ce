#include "inverse/line_proposals.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "spectral/fftw_planner.hpp"

namespace stengmc {

namespace {

//! Smallest 2^a 3^b 5^c >= n: lengths FFTW transforms fast.
std::size_t smooth_length(std::size_t n) {
  std::size_t best = std::size_t{1} << 62;
  for (std::size_t a = 1; a < best; a *= 2)
    for (std::size_t b = a; b < best; b *= 3)
      for (std::size_t c = b; c < best; c *= 5)
        if (c >= n) {
          best = std::min(best, c);
          break;
        }
  return best;
}

}  // namespace

struct LineProposals::Fft {
  double* in = nullptr;
  fftw_complex* out = nullptr;
  fftw_plan plan = nullptr;
  ~Fft() {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (plan) fftw_destroy_plan(plan);
    fftw_free(out);
    fftw_free(in);
  }
};

LineProposals::LineProposals(const AtomTable& atoms, std::size_t padding) : atoms_(&atoms) {
  const RecordGrid& grid = atoms.grid();
  const KnownDevice& device = atoms.device();
  length_ = smooth_length(std::max<std::size_t>(1, padding) * grid.samples);
  fft_ = std::make_unique<Fft>();
  fft_->in = fftw_alloc_real(length_);
  fft_->out = fftw_alloc_complex(length_ / 2 + 1);
  if (!fft_->in || !fft_->out) throw Error("line proposals: FFTW could not allocate buffers");
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    // ESTIMATE: a deterministic plan, so results do not depend on timing.
    fft_->plan = fftw_plan_dft_r2c_1d(static_cast<int>(length_), fft_->in, fft_->out, FFTW_ESTIMATE);
  }
  if (!fft_->plan) throw Error("line proposals: FFTW could not plan a transform of length " + std::to_string(length_));

  const double scale = device.voltage_scale_v() / device.model.belt_velocity_m_per_s;
  weight_.resize(grid.samples);
  for (std::size_t m = 0; m < grid.samples; ++m) weight_[m] = scale * atoms.envelope().at(grid.at(m));

  // Atom energies on a grid of ln k (they change slowly: plateau length and envelope start).
  const double lo = std::log(atoms.min_stiffness()), hi = std::log(atoms.max_stiffness());
  const std::size_t points = 64;
  for (std::size_t j = 0; j < points; ++j) {
    const double x = lo + (hi - lo) * static_cast<double>(j) / static_cast<double>(points - 1);
    energy_log_k_.push_back(x);
    energy_table_.push_back(atoms.energy(std::exp(x)));
  }

  // The frequency bins that belong to stiffnesses in the table.
  const double bin_rad_per_s = 2.0 * PI / (static_cast<double>(length_) * grid.step_s);
  first_bin_ = static_cast<std::size_t>(std::ceil(device.angular_frequency(atoms.min_stiffness()) / bin_rad_per_s));
  last_bin_ = std::min(length_ / 2, static_cast<std::size_t>(std::floor(device.angular_frequency(atoms.max_stiffness()) / bin_rad_per_s)));
  for (std::size_t j = first_bin_; j <= last_bin_; ++j) {
    const double omega = bin_rad_per_s * static_cast<double>(j);
    const double k = device.stiffness_for(omega);
    double shift = 0.0, phase = 0.0;
    atoms.tail_parameters(k, shift, phase);
    const double tb = atoms.breakaway_time(k);
    bin_stiffness_.push_back(k);
    // The tail is E cos(omega (t - tb) + phase) ~ E cos(omega t + phi): phi = phase - omega tb,
    // and t = start + m dt puts e^{-i omega start} on the FFT.
    bin_phase_.push_back(phase - omega * tb - omega * grid.start_s);
    bin_energy_.push_back(atom_energy(k));
    bin_breakaway_.push_back(tb);
  }
}

LineProposals::~LineProposals() = default;

double LineProposals::atom_energy(double k) const {
  const double x = std::clamp(std::log(k), energy_log_k_.front(), energy_log_k_.back());
  const double position = (x - energy_log_k_.front()) / (energy_log_k_[1] - energy_log_k_[0]);
  const auto i = std::min(static_cast<std::size_t>(position), energy_table_.size() - 2);
  const double f = position - static_cast<double>(i);
  return energy_table_[i] + f * (energy_table_[i + 1] - energy_table_[i]);
}

std::vector<LineCandidate> LineProposals::propose(std::span<const double> residual, std::size_t count) {
  const RecordGrid& grid = atoms_->grid();
  if (residual.size() != grid.samples) throw Error("LineProposals::propose: one residual value per sample expected");
  for (std::size_t m = 0; m < grid.samples; ++m) fft_->in[m] = residual[m] * weight_[m];
  std::fill(fft_->in + grid.samples, fft_->in + length_, 0.0);
  fftw_execute(fft_->plan);
  const double plateau_v = atoms_->device().voltage_scale_v();

  const std::size_t bins = bin_stiffness_.size();
  std::vector<double> score(bins);
  for (std::size_t b = 0; b < bins; ++b) {
    const fftw_complex& c = fft_->out[first_bin_ + b];
    // Re[e^{i phi} conj(C)] = cos(phi) Re C + sin(phi) Im C
    const double tail = std::cos(bin_phase_[b]) * c[0] + std::sin(bin_phase_[b]) * c[1];
    // The belt-carried plateau is shared by every asperity: it says how many there are, not
    // where their lines lie, and a residual that still holds many plateaus would draw the
    // proposals to the softest atoms (the longest plateau). The map scores the tails alone.
    const double end = std::clamp((bin_breakaway_[b] - grid.start_s) / grid.step_s, 0.0, static_cast<double>(grid.samples));
    const double plateau_energy = plateau_v * plateau_v * end;
    score[b] = 2.0 * tail - (bin_energy_[b] - plateau_energy);
  }
  std::vector<LineCandidate> out;
  for (std::size_t b = 0; b < bins; ++b) {
    const bool left = b == 0 || score[b] >= score[b - 1];
    const bool right = b + 1 == bins || score[b] > score[b + 1];
    if (left && right) out.push_back({bin_stiffness_[b], score[b]});
  }
  std::sort(out.begin(), out.end(), [](const LineCandidate& a, const LineCandidate& b) { return a.score_v2 > b.score_v2; });
  if (out.size() > count) out.resize(count);
  return out;
}

}  // namespace stengmc
