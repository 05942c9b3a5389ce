#include "inverse/atom_model.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "core/error.hpp"

namespace stengmc {

namespace {
// Tail samples between exact cosines (rotation in between, re-seeded against round-off).
constexpr std::size_t ROTATION_BLOCK = 256;
}  // namespace

AtomModel::AtomModel(const KnownDevice& device, const RecordGrid& grid, const AtomShapes& shapes, const EnvelopeFamily& envelopes)
    : device_(&device), grid_(grid), shapes_(&shapes), envelopes_(&envelopes), reference_friction_(shapes.ratios().reference()) {}

double AtomModel::carried_phase(const AtomParameters& a) const {
  const double m = device_->asperity.mass_kg;
  const double omega0 = std::sqrt(a.stiffness_n_per_m / m);
  return a.load_n * reference_friction_ / (m * omega0 * device_->model.belt_velocity_m_per_s);
}

double AtomModel::breakaway_time(const AtomParameters& a, double d) const {
  const double omega0 = std::sqrt(a.stiffness_n_per_m / device_->asperity.mass_kg);
  return a.onset_s + AtomShapes::breakaway_phase(std::max(carried_phase(a), shapes_->data().pi_nodes.front()), d / omega0) / omega0;
}

double AtomModel::displacement(const AtomParameters& a, double t) const {
  const double mean = a.load_n * reference_friction_ / a.stiffness_n_per_m;
  return std::min(mean, device_->model.belt_velocity_m_per_s * std::max(0.0, t - a.onset_s));
}

double AtomModel::tail_angular_frequency(const AtomParameters& a, double d) const {
  const double omega0 = std::sqrt(a.stiffness_n_per_m / device_->asperity.mass_kg);
  return omega0 * AtomShapes::tail_frequency_ratio(carried_phase(a), d / omega0, shapes_->ratios());
}

void AtomModel::evaluate(const AtomParameters& a, double d, AtomValues& out, bool derivatives) const {
  const double m = device_->asperity.mass_kg, v_b = device_->model.belt_velocity_m_per_s;
  const double omega0 = std::sqrt(a.stiffness_n_per_m / m);
  const double zeta = d / omega0;
  const double pi = a.load_n * reference_friction_ / (m * omega0 * v_b);
  const double beta = omega0 * pi;  // N f_ref / (m v_b)
  const ShapeWeights w = shapes_->weights(pi, zeta);
  const double theta_s = shapes_->blend_start(w), theta_e = shapes_->head_end(w);
  const double blend = theta_e - theta_s;
  const double nu = AtomShapes::tail_frequency_ratio(w.pi, zeta, shapes_->ratios());
  const double step = grid_.step_s;
  const std::size_t samples = grid_.samples;
  // The support: samples at or after the onset.
  const double first_position = (a.onset_s - grid_.start_s) / step;
  out.first = first_position <= 0.0 ? 0 : std::min(samples, static_cast<std::size_t>(std::ceil(first_position - 1e-9)));
  const std::size_t count = samples - out.first;
  // Sized, not zeroed: the head writes every sample before theta_e, the tail every one from
  // its start, which comes before theta_e (an atom is evaluated thousands of times a record).
  out.u.resize(count);
  out.slope.resize(count);
  if (derivatives)
    for (auto* v : {&out.d_lnk, &out.d_lnn, &out.d_onset, &out.d_lnd}) v->resize(count);
  if (count == 0) return;

  // d/dp of the dimensionless inputs, p = (ln k, ln N, t_on, ln d).
  const double lnpi_p[4] = {-0.5, 1.0, 0.0, 0.0};
  const double lnzeta_p[4] = {-0.5, 0.0, 0.0, 1.0};
  const double lnbeta_p[4] = {0.0, 1.0, 0.0, 0.0};
  const double lnd_p[4] = {0.0, 0.0, 0.0, 1.0};
  auto theta_p = [&](double theta, int p) { return p == 0 ? 0.5 * theta : p == 2 ? -omega0 : 0.0; };
  auto theta_b_p = [&](int p) { return w.theta_b_lnpi * lnpi_p[p] + w.theta_b_lnzeta * lnzeta_p[p]; };
  std::vector<double>* d_out[4] = {&out.d_lnk, &out.d_lnn, &out.d_onset, &out.d_lnd};

  // Head: theta < theta_e.
  const double t0 = grid_.at(out.first);
  std::size_t head_count = 0;
  for (std::size_t j = 0; j < count; ++j) {
    const double t = t0 + static_cast<double>(j) * step;
    const double theta = omega0 * (t - a.onset_s);
    if (theta >= theta_e) break;  // theta grows with j: the rest is tail (the scan went on over all 10^4)
    head_count = j + 1;
    const ShapePoint h = shapes_->head(w, theta);
    out.u[j] = h.u;
    out.slope[j] = h.u_theta * omega0;
    if (derivatives)
      for (int p = 0; p < 4; ++p) (*d_out[p])[j] = h.u_theta * theta_p(theta, p) + h.u_lnpi * lnpi_p[p] + h.u_lnzeta * lnzeta_p[p];
  }

  // Tail: theta >= theta_s, u = A(t - t_s + sigma) cos(nu (theta - theta_b) + phi).
  const double start = a.onset_s + theta_s / omega0;  // t_s
  const std::size_t tail_first = static_cast<std::size_t>(std::max(0.0, std::ceil((start - t0) / step - 1e-9)));
  if (tail_first >= count) return;
  const std::size_t tail_count = count - tail_first;
  double slope_L = 0.0, ds_dlnbeta = 0.0, ds_dd = 0.0;
  const double sigma = envelopes_->time_at(beta, d, w.log_amplitude, &slope_L, &ds_dlnbeta, &ds_dd);
  const double first_t = t0 + static_cast<double>(tail_first) * step;
  // Scratch kept per thread: an atom is evaluated thousands of times per record.
  thread_local std::vector<double> amp_buffer, amp_lnbeta_buffer, amp_d_buffer, amp_s_buffer;
  for (auto* b : {&amp_buffer, &amp_lnbeta_buffer, &amp_d_buffer, &amp_s_buffer})
    if (b->size() < tail_count) b->resize(tail_count);
  const std::span<double> amp(amp_buffer.data(), tail_count), amp_s(amp_s_buffer.data(), tail_count);
  const std::span<double> amp_lnbeta = derivatives ? std::span<double>(amp_lnbeta_buffer.data(), tail_count) : std::span<double>();
  const std::span<double> amp_d = derivatives ? std::span<double>(amp_d_buffer.data(), tail_count) : std::span<double>();
  envelopes_->evaluate(beta, d, first_t - start + sigma, amp, amp_lnbeta, amp_d, amp_s);
  // ds/dp = -dt_s/dp + dsigma/dp, sigma at fixed L = ell(Pi, zeta).
  double s_p[4], phase_p_const[4], ell_p[4];
  for (int p = 0; p < 4; ++p) {
    const double ts_p = (p == 2 ? 1.0 : 0.0) + theta_b_p(p) / omega0 - (p == 0 ? 0.5 * theta_s / omega0 : 0.0);
    ell_p[p] = w.log_amplitude_lnpi * lnpi_p[p] + w.log_amplitude_lnzeta * lnzeta_p[p];
    const double sigma_p = ell_p[p] / slope_L + ds_dlnbeta * lnbeta_p[p] + ds_dd * d * lnd_p[p];
    s_p[p] = -ts_p + sigma_p;
    // Phase = nu (theta - theta_b) + phi: its parameter derivative apart from nu dtheta/dp.
    phase_p_const[p] = -nu * theta_b_p(p) + w.phi_lnpi * lnpi_p[p] + w.phi_lnzeta * lnzeta_p[p];
  }
  const double omega_tail = nu * omega0;
  const double onset_phase_rate = nu * theta_p(0.0, 2) + phase_p_const[2];  // d phase / d t_on (theta_p(., 2) = -omega0)
  const double c_step = std::cos(omega_tail * step), s_step = std::sin(omega_tail * step);
  // Where the tail is alone (from `alone_from` on: both tests below grow true with i) and no
  // derivative is asked for, two rotation blocks are turned side by side: each keeps its own
  // exact start and the same operations in the same order (the same bits), but one block's
  // rotation, a chain of dependent products, no longer waits for the other's.
  std::size_t alone_from = tail_count;
  if (!derivatives)
    for (std::size_t i = 0; i < tail_count; ++i) {
      const double theta = omega0 * (first_t + static_cast<double>(i) * step - a.onset_s);
      if (theta >= theta_e || tail_first + i >= head_count) {
        alone_from = i;
        break;
      }
    }
  auto block_start = [&](std::size_t block, double& c, double& s) {
    const double t_block = first_t + static_cast<double>(block) * step;
    const double phase0 = nu * (omega0 * (t_block - a.onset_s) - w.theta_b) + w.phi;
    c = std::cos(phase0), s = std::sin(phase0);
  };
  auto tail_alone = [&](std::size_t i, double& c, double& s) {
    const std::size_t j = tail_first + i;
    const double A = amp[i];
    out.u[j] = A * c;
    out.slope[j] = amp_s[i] * c - A * s * omega_tail;
    const double cn = c * c_step - s * s_step;
    s = s * c_step + c * s_step;
    c = cn;
  };
  for (std::size_t block = 0; block < tail_count; block += ROTATION_BLOCK) {
    if (block >= alone_from && block + ROTATION_BLOCK < tail_count) {
      const std::size_t second = block + ROTATION_BLOCK, second_end = std::min(tail_count, second + ROTATION_BLOCK);
      double c1 = 0.0, s1 = 0.0, c2 = 0.0, s2 = 0.0;
      block_start(block, c1, s1);
      block_start(second, c2, s2);
      std::size_t k = 0;
      for (; second + k < second_end; ++k) tail_alone(block + k, c1, s1), tail_alone(second + k, c2, s2);
      for (; k < ROTATION_BLOCK; ++k) tail_alone(block + k, c1, s1);
      block = second;  // the loop's step moves past the second
      continue;
    }
    const std::size_t end = std::min(tail_count, block + ROTATION_BLOCK);
    double c = 0.0, s = 0.0;
    block_start(block, c, s);
    for (std::size_t i = block; i < end; ++i) {
      const std::size_t j = tail_first + i;
      const double t = first_t + static_cast<double>(i) * step;
      const double theta = omega0 * (t - a.onset_s);
      const double A = amp[i];
      const double tail = A * c;
      const double tail_slope = amp_s[i] * c - A * s * omega_tail;
      if (theta >= theta_e || j >= head_count) {
        // The tail alone (all but the first few hundred samples): the derivatives below written
        // out per parameter, without the general form's products by the 0s and 1s of
        // lnbeta_p, lnd_p and theta_p (the same values, but IEEE arithmetic cannot drop them).
        out.u[j] = tail;
        out.slope[j] = tail_slope;
        if (derivatives) {
          const double As = A * s;
          out.d_lnk[j] = amp_s[i] * s_p[0] * c - As * (nu * (0.5 * theta) + phase_p_const[0]);
          out.d_lnn[j] = (amp_s[i] * s_p[1] + amp_lnbeta[i]) * c - As * phase_p_const[1];
          out.d_onset[j] = amp_s[i] * s_p[2] * c - As * onset_phase_rate;
          out.d_lnd[j] = (amp_s[i] * s_p[3] + amp_d[i] * d) * c - As * phase_p_const[3];
        }
        const double cn = c * c_step - s * s_step;
        s = s * c_step + c * s_step;
        c = cn;
        continue;
      }
      double tail_p[4] = {0, 0, 0, 0};
      if (derivatives)
        for (int p = 0; p < 4; ++p) {
          const double dA = amp_s[i] * s_p[p] + amp_lnbeta[i] * lnbeta_p[p] + amp_d[i] * d * lnd_p[p];
          const double dphase = nu * theta_p(theta, p) + phase_p_const[p];
          tail_p[p] = dA * c - A * s * dphase;
        }
      if (theta >= theta_e || j >= head_count) {
        out.u[j] = tail;
        out.slope[j] = tail_slope;
        if (derivatives)
          for (int p = 0; p < 4; ++p) (*d_out[p])[j] = tail_p[p];
      } else {
        // Cross-fade: u = head + f (tail - head), f = (theta - theta_s) / blend.
        const double f = (theta - theta_s) / blend;
        const double head = out.u[j];
        out.u[j] = head + f * (tail - head);
        out.slope[j] += f * (tail_slope - out.slope[j]) + omega0 / blend * (tail - head);
        if (derivatives)
          for (int p = 0; p < 4; ++p) {
            const double f_p = (theta_p(theta, p) - theta_b_p(p)) / blend;
            double& dp = (*d_out[p])[j];
            dp += f * (tail_p[p] - dp) + f_p * (tail - head);
          }
      }
      const double cn = c * c_step - s * s_step;
      s = s * c_step + c * s_step;
      c = cn;
    }
  }
}

}  // namespace stengmc
