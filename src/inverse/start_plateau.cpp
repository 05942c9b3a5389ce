#include "inverse/start_plateau.hpp"

#include <algorithm>
#include <cmath>

namespace stengmc {

bool StartPlateau::uncertain() const {
  return std::abs(level - static_cast<double>(count)) > PLATEAU_CERTAIN_OFFSET || level_se > PLATEAU_CERTAIN_SE;
}

std::optional<StartPlateau> asperities_at_start(const KnownDevice& device, double stiffest_n_per_m, double noise_sigma_v,
                                                const RecordGrid& grid, std::span<const double> v) {
  // One asperity stuck to the belt: R sigma w v_b, signed as sigma (a negative charge density
  // makes every plateau negative).
  const double scale = device.voltage_scale_v();
  const double unit = std::abs(scale);
  const double friction = device.sliding_friction_n();
  const double v_b = device.model.belt_velocity_m_per_s;
  if (!(unit > 0.0) || !(friction > 0.0) || !(stiffest_n_per_m > 0.0) || v.size() < 2 || grid.step_s <= 0.0) return std::nullopt;
  const double ramp_s = device.asperity.mass_kg * v_b / friction;
  if (grid.start_s > ramp_s) return std::nullopt;

  // The plateau: from twice the ramp (each asperity accelerated at F/m until it moves with the
  // belt), plus 7 R C_L for the load's low pass to settle within e^-7 ~ 1e-3 of its step,
  // until the stiffest plausible asperity breaks away (t_b), or over PLATEAU_MIN_SPAN_S when
  // the prior's tail puts that earlier (an asperity that breaks away inside it drops the
  // voltage by one unit within sqrt(2 m / k) ~ 40-110 ns: the flatness below refuses it).
  // Spanned in time, not samples: a slower sampling has fewer samples in it, and fewer than
  // two show no flatness.
  const double rc_s = device.circuit.load_resistance_ohm * device.circuit.load_capacitance_f;
  const double from_s = 2.0 * ramp_s + 7.0 * rc_s;
  const double breakaway_s = std::max((friction - device.model.damping_n_s_per_m * v_b) / (stiffest_n_per_m * v_b),
                                      2.0 * ramp_s + PLATEAU_MIN_SPAN_S);
  std::size_t first = 0;
  while (first < v.size() && grid.at(first) < from_s) ++first;
  std::size_t last = first;
  while (last < v.size() && grid.at(last) < breakaway_s) ++last;
  if (last < first + 2) return std::nullopt;

  // Flat: every sample within 4 noise sds of the mean, and the two halves' means within 4 of
  // their difference's sds (a ring-down's slope or peak is not a plateau).
  const std::size_t count = last - first, half = first + count / 2;
  double sum = 0.0, sum_a = 0.0;
  for (std::size_t i = first; i < last; ++i) sum += v[i], sum_a += i < half ? v[i] : 0.0;
  const double mean = sum / static_cast<double>(count);
  const auto n_a = static_cast<double>(half - first), n_b = static_cast<double>(last - half);
  const double halves = sum_a / n_a - (sum - sum_a) / n_b;
  if (std::abs(halves) > 4.0 * noise_sigma_v * std::sqrt(1.0 / n_a + 1.0 / n_b)) return std::nullopt;
  for (std::size_t i = first; i < last; ++i)
    if (std::abs(v[i] - mean) > 4.0 * noise_sigma_v) return std::nullopt;

  // The baseline (an amplifier's offset): the samples before the belt starts, if the record
  // has any, else its first sample (at rest at t = 0: V = 0 but for the offset). (Not the
  // ramp's samples: the simulated ramp lags its closed form by ~0.4 unit at 10 ns.)
  double baseline = 0.0;
  std::size_t at_rest = 0;
  while (at_rest < v.size() && grid.at(at_rest) <= 0.25 * grid.step_s) baseline += v[at_rest++];
  baseline = at_rest > 0 ? baseline / static_cast<double>(at_rest) : v.front();
  at_rest = std::max<std::size_t>(at_rest, 1);

  StartPlateau p;
  p.level = (mean - baseline) / scale;
  p.level_se = noise_sigma_v * std::sqrt(1.0 / static_cast<double>(at_rest) + 1.0 / static_cast<double>(count)) / unit;
  const double n = std::round(p.level);
  // (The level's own noise, mostly the baseline's single sample, may move it by its error.)
  if (!(n >= 1.0) || std::abs(p.level - n) > PLATEAU_MAX_OFFSET + p.level_se) return std::nullopt;
  p.count = static_cast<std::size_t>(n);
  return p;
}

}  // namespace stengmc
