#include "inverse/line_proposals.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>

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

// How many of the map's best frequencies are tried, and how many of the candidates built on
// them are scored exactly.
constexpr std::size_t FREQUENCIES = 8;
constexpr std::size_t EXACT = 8;
// Placements at onset steps `propose` returns beside its best (LineProposals::set_step_onsets).
constexpr std::size_t STEP_PROPOSALS = 2;
// Loads tried per frequency when each atom has its own (log-spaced over the prior's).
constexpr std::size_t LOAD_GRID = 12;
// Two placements of one atom whose loads differ by less than this in ln N (and onsets by less
// than half a period) are the same to the refit that follows.
constexpr double PLACEMENT_LOG_LOAD = 0.1;
// Kernel transforms kept (LineProposals::kernel_transform): one per atom of the largest order
// the pair re-seat sees (16), 0.3 MB each at 10^4 samples.
constexpr std::size_t KERNELS_KEPT = 24;

}  // namespace

struct LineProposals::Fft {
  double* in = nullptr;
  fftw_complex* out = nullptr;
  fftw_plan plan = nullptr;
  // The sliding matched filter's complex transforms, of length `sliding`.
  std::size_t sliding = 0;
  fftw_complex* a = nullptr;
  fftw_complex* b = nullptr;
  fftw_complex* record = nullptr;  // FFT of the residual
  fftw_plan forward = nullptr, backward = nullptr;
  ~Fft() {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (plan) fftw_destroy_plan(plan);
    if (forward) fftw_destroy_plan(forward);
    if (backward) fftw_destroy_plan(backward);
    fftw_free(out);
    fftw_free(in);
    fftw_free(a);
    fftw_free(b);
    fftw_free(record);
  }
};

LineProposals::LineProposals(const RecordModel& model, const FitLayout& layout, const LoadPrior& loads, std::size_t padding)
    : model_(&model), layout_(layout), loads_(&loads) {
  const AtomLibrary& lib = model.atoms();
  const RecordGrid& grid = lib.grid();
  const KnownDevice& device = lib.device();
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
  fft_->sliding = smooth_length(2 * grid.samples);
  fft_->a = fftw_alloc_complex(fft_->sliding);
  fft_->b = fftw_alloc_complex(fft_->sliding);
  fft_->record = fftw_alloc_complex(fft_->sliding);
  if (!fft_->a || !fft_->b || !fft_->record) throw Error("line proposals: FFTW could not allocate buffers");
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fft_->forward = fftw_plan_dft_1d(static_cast<int>(fft_->sliding), fft_->a, fft_->b, FFTW_FORWARD, FFTW_ESTIMATE);
    fft_->backward = fftw_plan_dft_1d(static_cast<int>(fft_->sliding), fft_->a, fft_->b, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  if (!fft_->forward || !fft_->backward) throw Error("line proposals: FFTW could not plan the sliding filter");

  // The device's nominal envelope from breakaway, and its energy from each point on.
  const double m = device.asperity.mass_kg, v_b = device.model.belt_velocity_m_per_s;
  const double beta = device.asperity.normal_load_n * lib.ratios().reference() / (m * v_b);
  const double d = layout.nominal_damping_rate;
  envelope_.resize(grid.samples);
  lib.model().envelopes().evaluate(beta, d, 0.0, envelope_);
  envelope_energy_.assign(grid.samples + 1, 0.0);
  for (std::size_t j = 0; j < grid.samples; ++j) envelope_energy_[j + 1] = envelope_energy_[j] + envelope_[j] * envelope_[j];

  // Tail starts: half an envelope decay apart, as far as a breakaway can come.
  starts_s_ = {grid.start_s};
  if (layout.onset_free || layout.load_per_atom || layout.load_shared) {
    const double rate = d + beta * lib.ratios().linear_damping();
    const double spacing = 0.5 / std::max(rate, 1.0 / grid.duration_s());
    AtomParameters late{lib.min_stiffness(), layout.nominal_load_n * std::exp(layout.load_per_atom || layout.load_shared ? layout.max_log_load : 0.0),
                        layout.onset_max_s};
    const double last = std::min(grid.start_s + 0.8 * grid.duration_s(), lib.model().breakaway_time(late, d));
    for (double t = grid.start_s + spacing; t < last; t += spacing) starts_s_.push_back(t);
  }
  const double bin_rad_per_s = 2.0 * PI / (static_cast<double>(length_) * grid.step_s);
  first_bin_ = static_cast<std::size_t>(std::ceil(std::sqrt(lib.min_stiffness() / m) / bin_rad_per_s));
  last_bin_ = std::min(length_ / 2, static_cast<std::size_t>(std::floor(std::sqrt(lib.max_stiffness() / m) / bin_rad_per_s)));
  if (layout.load_per_atom) {
    const auto [low, high] = loads.support();
    // The inner 98 % of the loads: the search's LM reaches the tails from there.
    const double a = std::log(low) + 0.1 * std::log(high / low), b = std::log(high) - 0.1 * std::log(high / low);
    for (std::size_t i = 0; i < LOAD_GRID; ++i)
      loads_grid_.push_back(layout.nominal_load_n * std::exp(a + (b - a) * static_cast<double>(i) / static_cast<double>(LOAD_GRID - 1)));
  }
}

LineProposals::~LineProposals() = default;

LineCandidate LineProposals::score(const AtomParameters& atom, std::span<const double> r, double amplitude, double d) const {
  thread_local std::vector<double> g;
  return score(atom, r, amplitude, d, g);
}

LineCandidate LineProposals::score(const AtomParameters& atom, std::span<const double> r, double amplitude, double d,
                                   std::vector<double>& g) const {
  AtomSums sums;
  sums.reset(r.size());
  thread_local AtomValues values;
  model_->add(atom, d, sums, &values);
  // The atom alone through the circuit's first-order terms (as the record model puts it).
  g.resize(r.size());
  model_->unit_voltage(sums, g);
  double dot = 0.0, energy = 0.0;
  for (std::size_t j = 0; j < r.size(); ++j) dot += r[j] * g[j], energy += g[j] * g[j];
  return {atom, 2.0 * amplitude * dot - amplitude * amplitude * energy, amplitude * amplitude * energy};
}

struct LineProposals::Rough {
  AtomParameters atom;
  double score;
};

struct LineProposals::Residual {
  std::span<const double> r;
  std::vector<double> prefix;  // prefix sums of r
  double amplitude = 1.0, d = 0.0;
};

void LineProposals::load_residual(Residual& q) const {
  const std::size_t samples = model_->samples();
  if (q.r.size() != samples) throw Error("LineProposals: one residual value per sample expected");
  q.prefix.assign(samples + 1, 0.0);
  for (std::size_t j = 0; j < samples; ++j) q.prefix[j + 1] = q.prefix[j] + q.r[j];
  const std::size_t sliding = fft_->sliding;
  for (std::size_t j = 0; j < sliding; ++j) fft_->a[j][0] = j < samples ? q.r[j] : 0.0, fft_->a[j][1] = 0.0;
  fftw_execute_dft(fft_->forward, fft_->a, fft_->record);
}

std::complex<double> LineProposals::matched_value(std::span<const double> r, double omega, std::size_t at) const {
  // sum_tau r(at + tau) E(tau) e^{-i omega h tau}; the phase turned by a rotation between exact
  // values every ROTATION_BLOCK samples (its round-off stays ~1e-14).
  constexpr std::size_t ROTATION_BLOCK = 256;
  const std::size_t samples = model_->samples();
  const double h = model_->atoms().grid().step_s;
  const std::complex<double> turn = std::polar(1.0, -omega * h);
  std::complex<double> sum;
  for (std::size_t block = 0; at + block < samples; block += ROTATION_BLOCK) {
    std::complex<double> phase = std::polar(1.0, -omega * h * static_cast<double>(block));
    const std::size_t end = std::min(samples - at, block + ROTATION_BLOCK);
    for (std::size_t tau = block; tau < end; ++tau) {
      sum += (r[at + tau] * envelope_[tau]) * phase;
      phase *= turn;
    }
  }
  return sum;
}

const std::vector<std::complex<double>>& LineProposals::kernel_transform(double omega) {
  for (const KernelTransform& k : kernels_)
    if (k.omega == omega) return k.transform;
  const std::size_t samples = model_->samples(), sliding = fft_->sliding;
  const double h = model_->atoms().grid().step_s;
  for (std::size_t j = 0; j < sliding; ++j) {
    if (j < samples) {
      const double phase = omega * h * static_cast<double>(j);
      fft_->a[j][0] = envelope_[j] * std::cos(phase), fft_->a[j][1] = envelope_[j] * std::sin(phase);
    } else {
      fft_->a[j][0] = fft_->a[j][1] = 0.0;
    }
  }
  fftw_execute_dft(fft_->forward, fft_->a, fft_->b);
  if (kernels_.size() >= KERNELS_KEPT) kernels_.erase(kernels_.begin());
  KernelTransform& k = kernels_.emplace_back();
  k.omega = omega;
  k.transform.resize(sliding);
  for (std::size_t j = 0; j < sliding; ++j) k.transform[j] = std::complex<double>(fft_->b[j][0], fft_->b[j][1]);
  return k.transform;
}

void LineProposals::matched_filter(double omega, std::vector<std::complex<double>>& matched) {
  // K(tau) = E(tau) e^{i omega tau}; C = IFFT(FFT(r) conj(FFT(K))): the sliding matched filter
  // C(t_b) = sum_tau r(t_b + tau) E(tau) e^{-i omega tau} at every t_b at once.
  const std::size_t samples = model_->samples(), sliding = fft_->sliding;
  const std::vector<std::complex<double>>& kernel = kernel_transform(omega);
  for (std::size_t j = 0; j < sliding; ++j) {
    const std::complex<double> x(fft_->record[j][0], fft_->record[j][1]), y = kernel[j];
    const std::complex<double> z = x * std::conj(y);
    fft_->a[j][0] = z.real(), fft_->a[j][1] = z.imag();
  }
  fftw_execute_dft(fft_->backward, fft_->a, fft_->b);
  const double inverse_length = 1.0 / static_cast<double>(sliding);
  matched.resize(samples);
  for (std::size_t j = 0; j < samples; ++j) matched[j] = std::complex<double>(fft_->b[j][0], fft_->b[j][1]) * inverse_length;
}

std::vector<LineCandidate> LineProposals::propose(std::span<const double> r, double amplitude, double d, double load_factor,
                                                  std::size_t count, const std::vector<double>* step_onsets_s) {
  const std::vector<double>& onsets = step_onsets_s ? *step_onsets_s : step_onsets_s_;
  const AtomLibrary& lib = model_->atoms();
  const RecordGrid& grid = lib.grid();
  const KnownDevice& device = lib.device();
  const AtomModel& atom_model = lib.model();
  const std::size_t samples = grid.samples;
  if (r.size() != samples) throw Error("LineProposals::propose: one residual value per sample expected");
  const double h = grid.step_s, m = device.asperity.mass_kg;

  // One transform per tail start.
  const std::size_t bins = last_bin_ >= first_bin_ ? last_bin_ - first_bin_ + 1 : 0;
  std::vector<std::vector<std::complex<double>>> maps(starts_s_.size(), std::vector<std::complex<double>>(bins));
  std::vector<double> start_energy(starts_s_.size());
  const double bin_rad_per_s = 2.0 * PI / (static_cast<double>(length_) * h);
  for (std::size_t s = 0; s < starts_s_.size(); ++s) {
    const std::size_t first = index_of(starts_s_[s]);
    std::fill(fft_->in, fft_->in + length_, 0.0);
    for (std::size_t j = first; j < samples; ++j) fft_->in[j] = r[j] * envelope_[j - first];
    start_energy[s] = envelope_energy_[samples - first];
    fftw_execute(fft_->plan);
    for (std::size_t b = 0; b < bins; ++b) {
      const double omega = bin_rad_per_s * static_cast<double>(first_bin_ + b);
      // The transform counts time from the record's first sample.
      maps[s][b] = std::complex<double>(fft_->out[first_bin_ + b][0], fft_->out[first_bin_ + b][1]) *
                   std::polar(1.0, -omega * grid.start_s);
    }
  }
  // The map's best frequencies: local maxima of the free-phase gain |C_s|^2 / E_s.
  std::vector<double> gain(bins, 0.0);
  for (std::size_t b = 0; b < bins; ++b)
    for (std::size_t s = 0; s < starts_s_.size(); ++s)
      gain[b] = std::max(gain[b], std::norm(maps[s][b]) / std::max(start_energy[s], 1e-300));
  std::vector<std::size_t> peaks;
  for (std::size_t b = 0; b < bins; ++b)
    if ((b == 0 || gain[b] >= gain[b - 1]) && (b + 1 == bins || gain[b] > gain[b + 1])) peaks.push_back(b);
  std::sort(peaks.begin(), peaks.end(), [&](std::size_t x, std::size_t y) { return gain[x] > gain[y]; });
  if (peaks.size() > FREQUENCIES) peaks.resize(FREQUENCIES);

  // Candidates on those frequencies: every breakaway time t_b on the record's grid, each with
  // the loads and onsets the layout allows. For each frequency the tail's correlation with r
  // at every t_b at once: the sliding matched filter C(t_b) = sum_tau r(t_b + tau) E(tau)
  // e^{-i omega tau}, a cross-correlation by FFT.
  // Where the layout fixes an atom's placement (its onset known, its load shared), each
  // frequency has one breakaway, and C there is summed directly: the whole filter's two FFTs
  // cost ~30 times as much, for one value (they were 12 % of an ideal record's time).
  const bool one_placement = !layout_.onset_free && !layout_.load_per_atom;
  Residual q{r, {}, amplitude, d};
  if (one_placement) {
    q.prefix.assign(samples + 1, 0.0);
    for (std::size_t j = 0; j < samples; ++j) q.prefix[j + 1] = q.prefix[j] + r[j];
  } else {
    load_residual(q);
  }
  std::vector<Rough> rough, stepped;
  std::vector<std::complex<double>> matched;
  for (std::size_t peak : peaks) {
    const double omega_bin = bin_rad_per_s * static_cast<double>(first_bin_ + peak);
    const double k = std::clamp(m * (omega_bin * omega_bin + d * d), lib.min_stiffness(), lib.max_stiffness());
    AtomParameters nominal{k, layout_.nominal_load_n * (layout_.load_shared ? load_factor : 1.0), layout_.onset_min_s};
    const double omega = atom_model.tail_angular_frequency(nominal, d);
    if (one_placement) {
      // The breakaway add_breakaways puts this atom at.
      const double omega0 = std::sqrt(k / m);
      const ShapeWeights w = lib.shapes().weights(atom_model.carried_phase(nominal), d / omega0);
      const std::size_t off = std::min(samples - 1, index_of(nominal.onset_s + w.theta_b / omega0));
      matched.assign(samples, std::complex<double>());
      matched[off] = matched_value(r, omega, off);
    } else {
      matched_filter(omega, matched);
    }
    add_placements(nominal, q, matched, rough);
    for (Rough& c : step_placements(nominal, q, matched, onsets)) stepped.push_back(std::move(c));
  }
  // The best distinct ones, best first: neighbours on the grid (a breakaway a few samples on, a
  // load a grid step away) are the same atom to the LM that follows. A heap, not a sort: there
  // are 10^4-10^5 rough candidates and only the first few dozen are ever read.
  auto worse = [](const Rough& x, const Rough& y) { return x.score < y.score; };
  std::make_heap(rough.begin(), rough.end(), worse);
  std::vector<LineCandidate> out;
  std::vector<AtomParameters> kept;
  for (auto heap_end = rough.end(); heap_end != rough.begin() && out.size() < std::max(count, EXACT); --heap_end) {
    std::pop_heap(rough.begin(), heap_end, worse);
    const AtomParameters& a = (heap_end - 1)->atom;
    const double period = 2.0 * PI / std::sqrt(a.stiffness_n_per_m / m);
    bool close = false;
    for (const AtomParameters& b : kept)
      close = close || (std::abs(std::log(a.stiffness_n_per_m / b.stiffness_n_per_m)) < 1e-3 &&
                        std::abs(a.onset_s - b.onset_s) < 0.5 * period && std::abs(std::log(a.load_n / b.load_n)) < 0.15);
    if (close) continue;
    kept.push_back(a);
    out.push_back(score(a, r, amplitude, d));
  }
  // Each step onset with its best frequency and load, scored exactly beside them: a step fixes
  // an onset to a sample, which the rough score, dominated by the tail, reads a period off.
  std::stable_sort(stepped.begin(), stepped.end(), [](const Rough& x, const Rough& y) { return x.score > y.score; });
  std::vector<double> onsets_scored;
  std::vector<LineCandidate> at_steps;
  for (const Rough& c : stepped) {
    if (std::find(onsets_scored.begin(), onsets_scored.end(), c.atom.onset_s) != onsets_scored.end()) continue;
    onsets_scored.push_back(c.atom.onset_s);
    at_steps.push_back(score(c.atom, r, amplitude, d));
    at_steps.back().at_step = true;
  }
  std::sort(out.begin(), out.end(), [](const LineCandidate& x, const LineCandidate& y) { return x.score_v2 > y.score_v2; });
  std::sort(at_steps.begin(), at_steps.end(), [](const LineCandidate& x, const LineCandidate& y) { return x.score_v2 > y.score_v2; });
  if (out.size() > count) out.resize(count);
  if (at_steps.size() > STEP_PROPOSALS) at_steps.resize(STEP_PROPOSALS);
  out.insert(out.end(), at_steps.begin(), at_steps.end());
  return out;
}

std::size_t LineProposals::index_of(double t) const {
  const RecordGrid& grid = model_->atoms().grid();
  return static_cast<std::size_t>(
      std::clamp(std::round((t - grid.start_s) / grid.step_s), 0.0, static_cast<double>(grid.samples)));
}

LineProposals::TailStart LineProposals::tail_start(const ShapeWeights& w) {
  return {std::polar(1.0, w.phi), std::exp(-w.log_amplitude)};
}

void LineProposals::add_rough(const AtomParameters& atom, double pi, const TailStart& start, std::size_t breakaway, const Residual& q,
                              std::span<const std::complex<double>> matched, std::vector<Rough>& rough) const {
  // The plateau's and the tail's energies and correlations, from prefix sums.
  const std::size_t samples = model_->samples();
  const double scale = model_->volts_per_unit();
  const std::size_t on = std::min(samples, index_of(atom.onset_s));
  const std::size_t off = std::min(samples - 1, breakaway);
  const double a_b = start.amplitude;
  const double tail = a_b * scale * std::real(start.phase * std::conj(matched[off]));
  const double plateau = pi > 1.0 && off > on ? scale * (q.prefix[off] - q.prefix[on]) : 0.0;
  const double energy = scale * scale * ((pi > 1.0 && off > on ? static_cast<double>(off - on) : 0.0) +
                                         0.5 * a_b * a_b * envelope_energy_[samples - off]);
  rough.push_back({atom, 2.0 * q.amplitude * (tail + plateau) - q.amplitude * q.amplitude * energy});
}

void LineProposals::add_breakaways(AtomParameters atom, const Residual& q, std::span<const std::complex<double>> matched,
                                   std::vector<Rough>& rough) const {
  const AtomLibrary& lib = model_->atoms();
  const double omega0 = std::sqrt(atom.stiffness_n_per_m / lib.device().asperity.mass_kg);
  const double pi = lib.model().carried_phase(atom);
  const ShapeWeights w = lib.shapes().weights(pi, q.d / omega0);
  const TailStart tail = tail_start(w);
  const double carried = w.theta_b / omega0;  // onset to breakaway [s]
  if (!layout_.onset_free) {
    add_rough(atom, pi, tail, index_of(atom.onset_s + carried), q, matched, rough);
    return;
  }
  // Every breakaway on the grid whose onset the prior allows.
  const RecordGrid& grid = lib.grid();
  const std::size_t first = index_of(layout_.onset_min_s + carried), last = index_of(layout_.onset_max_s + carried);
  for (std::size_t b = first; b <= std::min(last, grid.samples - 1); ++b) {
    atom.onset_s = grid.at(b) - carried;
    add_rough(atom, pi, tail, b, q, matched, rough);
  }
}

void LineProposals::add_placements(const AtomParameters& nominal, const Residual& q, std::span<const std::complex<double>> matched,
                                   std::vector<Rough>& rough) const {
  const AtomLibrary& lib = model_->atoms();
  const AtomModel& atom_model = lib.model();
  const RecordGrid& grid = lib.grid();
  const double k = nominal.stiffness_n_per_m, m = lib.device().asperity.mass_kg, d = q.d;
  const double omega0 = std::sqrt(k / m);
  std::vector<double> loads;
  if (layout_.load_per_atom) loads = loads_grid_;
  else loads.push_back(nominal.load_n);
  for (double load : loads) add_breakaways({k, load, layout_.onset_min_s}, q, matched, rough);
  if (layout_.load_per_atom && !layout_.onset_free) {
    // The onset known, each breakaway time is a load: theta_b(Pi) = omega0 (t_b - t_on) for
    // Pi > 1 (monotone), on the grid between the prior's lightest and heaviest load's (its
    // whole support: a load the grid misses is reached by no refit, whose breakaway would
    // have to cross whole tail periods).
    const auto [low, high] = loads_->support();
    AtomParameters light{k, layout_.nominal_load_n * low, layout_.onset_min_s}, heavy{k, layout_.nominal_load_n * high, layout_.onset_min_s};
    const std::size_t first = index_of(atom_model.breakaway_time(light, d)), last = index_of(atom_model.breakaway_time(heavy, d));
    double pi_guess = std::max(1.0, atom_model.carried_phase(light));
    for (std::size_t b = first; b <= std::min(last, grid.samples - 1); ++b) {
      const double target = omega0 * (grid.at(b) - layout_.onset_min_s);
      // Newton on theta_b(Pi) - target, d theta_b / d Pi = sqrt(Pi^2 - 1) / Pi.
      double pi = std::max(pi_guess, 1.0 + 1e-9);
      for (int it = 0; it < 20; ++it) {
        const double f = AtomShapes::breakaway_phase(pi, d / omega0) - target;
        const double slope = std::sqrt(std::max(pi * pi - 1.0, 1e-12)) / pi;
        pi = std::max(1.0 + 1e-9, pi - f / slope);
        if (std::abs(f) < 1e-9) break;
      }
      pi_guess = pi;
      AtomParameters atom{k, pi * m * omega0 * lib.device().model.belt_velocity_m_per_s / lib.ratios().reference(), layout_.onset_min_s};
      add_rough(atom, pi, tail_start(lib.shapes().weights(pi, d / omega0)), b, q, matched, rough);
    }
  }
}

std::vector<LineProposals::Rough> LineProposals::step_placements(const AtomParameters& nominal, const Residual& q,
                                                                 std::span<const std::complex<double>> matched,
                                                                 const std::vector<double>& onsets_s) const {
  std::vector<Rough> out;
  if (!layout_.onset_free || onsets_s.empty()) return out;
  const AtomLibrary& lib = model_->atoms();
  const double omega0 = std::sqrt(nominal.stiffness_n_per_m / lib.device().asperity.mass_kg);
  std::vector<double> loads;
  if (layout_.load_per_atom) loads = loads_grid_;
  else loads.push_back(nominal.load_n);
  std::vector<Rough> per_load;
  for (double onset : onsets_s) {
    if (onset < layout_.onset_min_s || onset > layout_.onset_max_s) continue;
    per_load.clear();
    for (double load : loads) {
      const AtomParameters atom{nominal.stiffness_n_per_m, load, onset};
      const double pi = lib.model().carried_phase(atom);
      const ShapeWeights w = lib.shapes().weights(pi, q.d / omega0);
      add_rough(atom, pi, tail_start(w), index_of(onset + w.theta_b / omega0), q, matched, per_load);
    }
    if (!per_load.empty())
      out.push_back(*std::max_element(per_load.begin(), per_load.end(), [](const Rough& x, const Rough& y) { return x.score < y.score; }));
  }
  std::stable_sort(out.begin(), out.end(), [](const Rough& x, const Rough& y) { return x.score > y.score; });
  return out;
}

std::vector<LineCandidate> LineProposals::propose_placements(const AtomParameters& atom, std::span<const double> r, double amplitude,
                                                         double d, std::size_t count) {
  Residual q{r, {}, amplitude, d};
  load_residual(q);
  return placements(atom, q, count, nullptr);
}

std::vector<std::vector<LineProposals::Placement>> LineProposals::propose_placements_with_voltages(
    std::span<const AtomParameters> atoms, std::span<const double> r, double amplitude, double d, std::size_t count) {
  Residual q{r, {}, amplitude, d};
  load_residual(q);
  std::vector<std::vector<Placement>> out(atoms.size());
  std::vector<std::vector<double>> units;
  for (std::size_t i = 0; i < atoms.size(); ++i) {
    const std::vector<LineCandidate> found = placements(atoms[i], q, count, &units);
    for (std::size_t c = 0; c < found.size(); ++c) out[i].push_back({found[c], std::move(units[c])});
  }
  return out;
}

std::vector<LineCandidate> LineProposals::placements(const AtomParameters& atom, const Residual& q, std::size_t count,
                                                     std::vector<std::vector<double>>* units) {
  std::vector<std::complex<double>> matched;
  matched_filter(model_->atoms().model().tail_angular_frequency(atom, q.d), matched);
  std::vector<Rough> rough;
  add_placements(atom, q, matched, rough);
  // The best placements at least half a period or a load grid step apart (a period on is the
  // same tail's other phase).
  const double period = 2.0 * PI / std::sqrt(atom.stiffness_n_per_m / model_->atoms().device().asperity.mass_kg);
  // Read best first from a heap, not a sort: there are 10^4-10^5 rough placements and only
  // the first hundreds at most are ever read (a full sort was 8 % of a broadened record's time).
  auto worse = [](const Rough& x, const Rough& y) { return x.score < y.score; };
  std::make_heap(rough.begin(), rough.end(), worse);
  std::vector<LineCandidate> out;
  std::vector<std::vector<double>> g;
  for (auto heap_end = rough.end(); heap_end != rough.begin() && out.size() < count; --heap_end) {
    std::pop_heap(rough.begin(), heap_end, worse);
    const Rough& c = *(heap_end - 1);
    const bool close = std::any_of(out.begin(), out.end(), [&](const LineCandidate& o) {
      return std::abs(o.atom.onset_s - c.atom.onset_s) < 0.5 * period && std::abs(std::log(o.atom.load_n / c.atom.load_n)) < PLACEMENT_LOG_LOAD;
    });
    if (close) continue;
    thread_local std::vector<double> unused;
    out.push_back(score(c.atom, q.r, q.amplitude, q.d, units ? g.emplace_back() : unused));
  }
  // Each step onset with its best load, scored exactly too (LineProposals::propose), unless one
  // of those already is that placement; the best `count` of all are kept.
  for (const Rough& c : step_placements(atom, q, matched, step_onsets_s_)) {
    const bool close = std::any_of(out.begin(), out.end(), [&](const LineCandidate& o) {
      return std::abs(o.atom.onset_s - c.atom.onset_s) < 0.5 * model_->atoms().grid().step_s &&
             std::abs(std::log(o.atom.load_n / c.atom.load_n)) < PLACEMENT_LOG_LOAD;
    });
    if (close) continue;
    thread_local std::vector<double> unused;
    out.push_back(score(c.atom, q.r, q.amplitude, q.d, units ? g.emplace_back() : unused));
  }
  // Best first by exact score (the order std::sort gave them, kept for the units alongside).
  std::vector<std::size_t> order(out.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return out[x].score_v2 > out[y].score_v2; });
  if (order.size() > count) order.resize(count);
  std::vector<LineCandidate> sorted;
  if (units) units->clear();
  for (std::size_t i : order) {
    sorted.push_back(out[i]);
    if (units) units->push_back(std::move(g.at(i)));
  }
  return sorted;
}

}  // namespace stengmc
