#include "tribology/model2_motion.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "core/constants.hpp"
#include "core/error.hpp"
#include "tribology/oscillator_flow.hpp"
#include "tribology/oscillator_sampling.hpp"
#include "tribology/time_grid.hpp"

namespace stengmc {

namespace {

// Root of r on [sa, sb] (r(sa), r(sb) of opposite signs) by the Illinois variant of regula
// falsi (Dowell & Jarratt 1971): superlinear, and never leaves the bracket.
template <class Function>
double locate_sign_change(const Function& r, double sa, double fa, double sb, double fb) {
  int side = 0;
  for (int iter = 0; iter < 100 && (sb - sa) > 1e-15; ++iter) {
    const double sc = (fa * sb - fb * sa) / (fa - fb);
    const double fc = r(sc);
    if (fc == 0.0) return sc;
    if ((fc < 0.0) == (fb < 0.0)) {
      sb = sc;
      fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      sa = sc;
      fa = fc;
      if (side == +1) fb *= 0.5;
      side = +1;
    }
  }
  return 0.5 * (sa + sb);
}

// Oscillator pieces are probed for v_r sign changes this often per undamped period.
constexpr double PROBES_PER_PERIOD = 16.0;

//! x_p and x_p' / w0 of a propagator piece at scaled time tau [m].
void particular_at(const MotionPiece& piece, double tau, double& x, double& dx) {
  const auto& a = piece.particular_m;
  constexpr std::size_t top = MOTION_PIECE_TERMS - 1;
  x = a[top];
  for (std::size_t j = top; j-- > 0;) x = x * tau + a[j];
  dx = static_cast<double>(top) * a[top];
  for (std::size_t j = top; j-- > 1;) dx = dx * tau + static_cast<double>(j) * a[j];
}

}  // namespace

Model2Motion::Model2Motion(Model2Integration integration)
    : knots_(std::move(integration.knots)),
      pieces_(std::move(integration.pieces)),
      w0_(integration.natural_frequency_rad_per_s) {
  if (knots_.empty()) throw ModelError("Model 2 motion needs at least one knot");
  if (pieces_.size() + 1 != knots_.size()) throw ModelError("Model 2 motion: one piece per step is needed");
  for (std::size_t i = 1; i < knots_.size(); ++i) {
    if (!(knots_[i].t_s > knots_[i - 1].t_s)) {
      std::ostringstream msg;
      msg << "Model 2 motion knot times must increase: t[" << i - 1 << "] = " << knots_[i - 1].t_s << " s, t[" << i
          << "] = " << knots_[i].t_s << " s";
      throw ModelError(msg.str());
    }
  }
}

Model2Integration Model2Motion::release() && {
  Model2Integration out;
  out.knots = std::move(knots_);
  out.pieces = std::move(pieces_);
  out.natural_frequency_rad_per_s = w0_;
  return out;
}

std::size_t Model2Motion::piece_of(double t_s) const {
  if (pieces_.empty()) return 0;
  // First knot with time > t; the piece starts one before it.
  const auto it = std::upper_bound(knots_.begin(), knots_.end(), t_s,
                                   [](double t, const MotionKnot& k) { return t < k.t_s; });
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - knots_.begin() - 1, 0));
  return std::min(i, pieces_.size() - 1);
}

PhasePoint Model2Motion::on_piece(std::size_t i, double t_s) const {
  if (pieces_.empty()) return {knots_[0].x_m, knots_[0].v_m_per_s};
  const MotionKnot& a = knots_[i];
  const MotionPiece& piece = pieces_[i];
  if (piece.kind == PieceKind::quintic) return quintic_hermite(a, knots_[i + 1], t_s);
  if (piece.kind == PieceKind::cubic) return cubic_hermite(a, knots_[i + 1], t_s);
  const double tau = w0_ * (t_s - a.t_s);
  double z = 0.0, dz = 0.0, zp = 0.0, dzp = 0.0;
  free_oscillator_start(a, piece, w0_, z, dz);
  OscillatorFlow::over(piece.zeta, tau).apply(z, dz);
  particular_at(piece, tau, zp, dzp);
  return {piece.centre_m + z + zp, w0_ * (dz + dzp)};
}

PhasePoint Model2Motion::at(double t_s, Side /*side*/) const {
  const double t0 = knots_.front().t_s;
  const double t1 = knots_.back().t_s;
  const double slack = 1e-9 * std::max(t1 - t0, std::abs(t1));
  if (!(t_s >= t0 - slack && t_s <= t1 + slack)) {
    std::ostringstream msg;
    msg << "Model 2 motion asked for t = " << t_s << " s outside its range [" << t0 << ", " << t1 << "] s";
    throw ModelError(msg.str());
  }
  const double t = std::clamp(t_s, t0, t1);
  return on_piece(piece_of(t), t);
}

std::unique_ptr<Motion> Model2Motion::excerpt(double t0_s, double t1_s) const {
  if (pieces_.empty()) return std::make_unique<Model2Motion>(Model2Integration{.knots = knots_, .pieces = {}, .natural_frequency_rad_per_s = w0_});
  // piece_of(t) is the last knot at or before t (clamped to the pieces): with the pieces of
  // t0 and t1 and one more on either side, upper_bound meets the same knot in the excerpt,
  // and at()'s clamp to the ends changes nothing inside (the ends are the motion's own
  // whenever the excerpt reaches them).
  const std::size_t p0 = piece_of(t0_s);
  const std::size_t first = p0 > 0 ? p0 - 1 : 0;
  const std::size_t last = std::min(piece_of(std::max(t0_s, t1_s)) + 1, pieces_.size() - 1);
  Model2Integration part;
  part.knots.assign(knots_.begin() + static_cast<std::ptrdiff_t>(first), knots_.begin() + static_cast<std::ptrdiff_t>(last) + 2);
  part.pieces.assign(pieces_.begin() + static_cast<std::ptrdiff_t>(first), pieces_.begin() + static_cast<std::ptrdiff_t>(last) + 1);
  part.natural_frequency_rad_per_s = w0_;
  return std::make_unique<Model2Motion>(std::move(part));
}

double Model2Motion::displacement_bound() const {
  double bound = knots_.front().x_m;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    const MotionKnot& a = knots_[i];
    const MotionKnot& b = knots_[i + 1];
    const double h = b.t_s - a.t_s;
    const MotionPiece& piece = pieces_[i];
    double top = 0.0;
    if (piece.kind == PieceKind::oscillator) {
      // x - centre = the free oscillator from the piece's start state (its energy
      // (x - c)^2 + (x'/w0)^2 does not grow for zeta >= 0) plus its response to the forcing
      // P = x_p'' + 2 zeta x_p' + x_p from rest, at most tau max|P| times the impulse
      // response's bound e^{-zeta s} |sin(w s)| / w <= 1 / w, w = sqrt(1 - zeta^2)
      // (s for zeta >= 1); for zeta < 0 both grow at most as e^{|zeta| tau}.
      const double z = a.x_m - piece.centre_m;
      const double dz = a.v_m_per_s / w0_;
      const double tau_end = w0_ * h;
      const double growth = piece.zeta >= 0.0 ? 1.0 : std::exp(-piece.zeta * tau_end);
      const auto& x = piece.particular_m;
      double forcing = 0.0, power = 1.0;
      for (std::size_t j = 0; j < MOTION_PIECE_TERMS; ++j, power *= std::max(1.0, tau_end)) {
        const double c2 = j + 2 < MOTION_PIECE_TERMS ? static_cast<double>((j + 2) * (j + 1)) * x[j + 2] : 0.0;
        const double c1 = j + 1 < MOTION_PIECE_TERMS ? 2.0 * piece.zeta * static_cast<double>(j + 1) * x[j + 1] : 0.0;
        forcing += std::abs(c2 + c1 + x[j]) * power;
      }
      const double impulse = piece.zeta < 1.0 ? 1.0 / std::sqrt((1.0 - piece.zeta) * (1.0 + piece.zeta)) : tau_end;
      top = piece.centre_m + (std::sqrt(z * z + dz * dz) + tau_end * forcing * impulse) * growth;
    } else {
      const std::array<double, 5> c =
          piece.kind == PieceKind::quintic ? quintic_hermite_velocity(a, b) : cubic_hermite_velocity(a, b);
      double rise = 0.0;
      for (std::size_t n = 0; n < c.size(); ++n) rise += std::abs(c[n]) / static_cast<double>(n + 1);
      top = a.x_m + h * rise;
    }
    if (!(top <= bound)) bound = std::isnan(top) ? INFINITY : top;
  }
  return bound;
}

std::vector<double> Model2Motion::fine_structure(double resolution_s) const {
  std::vector<double> cuts;
  for (std::size_t i = 0; i + 1 < knots_.size(); ++i) {
    if (!(knots_[i + 1].t_s - knots_[i].t_s < 0.25 * resolution_s)) continue;
    if (cuts.empty() || cuts.back() < knots_[i].t_s) cuts.push_back(knots_[i].t_s);
    cuts.push_back(knots_[i + 1].t_s);
  }
  return cuts;
}

void Model2Motion::sample(std::span<const double> times_s, bool midpoints, MotionSamples& out) const {
  const std::size_t count = times_s.size();
  // The walk needs a uniform grid (one flow for every half step); anything else is sampled
  // point by point.
  const double step = count >= 2 ? (times_s.back() - times_s.front()) / static_cast<double>(count - 1) : 0.0;
  if (!evenly_spaced(times_s, step)) {
    Motion::sample(times_s, midpoints, out);
    return;
  }
  out.x_m.resize(count);
  out.v_m_per_s.resize(count);
  out.v_left_m_per_s.clear();  // x' is continuous
  out.mid_x_m.resize(midpoints && count > 0 ? count - 1 : 0);
  out.mid_v_m_per_s.resize(out.mid_x_m.size());
  if (count == 0) return;

  const double t_first = knots_.front().t_s;
  const double t_last = knots_.back().t_s;
  const double slack = 1e-9 * std::max(t_last - t_first, std::abs(t_last));
  if (!(times_s.front() >= t_first - slack && times_s.back() <= t_last + slack)) {
    std::ostringstream msg;
    msg << "Model 2 motion sampled on [" << times_s.front() << ", " << times_s.back() << "] s outside its range ["
        << t_first << ", " << t_last << "] s";
    throw ModelError(msg.str());
  }
  auto store_mid = [&](std::size_t j, const PhasePoint& p) {
    out.mid_x_m[j] = p.x_m;
    out.mid_v_m_per_s[j] = p.v_m_per_s;
  };

  const double inverse_step = step > 0.0 ? 1.0 / step : 0.0;
  std::size_t piece = piece_of(times_s.front());
  std::size_t j = 0;
  while (j < count) {
    // Samples on this piece: up to its end knot (the last piece takes the rest). A midpoint
    // belongs to the piece of the sample before it, evaluated there (extrapolating a
    // Hermite piece is exact: it is one polynomial), unless it lies beyond the piece end.
    const double piece_end = piece + 1 < pieces_.size() ? knots_[piece + 1].t_s : INFINITY;
    // First sample after the piece end: guessed from the uniform spacing, then settled by
    // the same comparisons a scan from j would make.
    std::size_t end = j;
    if (!(piece_end < times_s[count - 1])) {
      end = count;
    } else if (step > 0.0) {
      // Truncation is the floor here (the quotient >= 0), and a product does for the
      // division: the loops below settle the guess either way.
      const double spacings = (piece_end - times_s[0]) * inverse_step;  // < count - 1 here
      end = std::clamp(spacings >= 0.0 ? static_cast<std::size_t>(spacings) + 1 : 0, j, count);
      while (end > j && times_s[end - 1] > piece_end) --end;
    }
    while (end < count && times_s[end] <= piece_end) ++end;
    if (end == j) {  // the piece holds no sample: the next one
      ++piece;
      continue;
    }
    auto midpoint = [&](std::size_t i) {
      const double t = 0.5 * (times_s[i] + times_s[i + 1]);
      return t <= piece_end ? on_piece(piece, t) : on_piece(piece + 1, t);
    };
    if (pieces_.empty()) {
      for (; j < end; ++j) {
        out.x_m[j] = knots_[0].x_m;
        out.v_m_per_s[j] = knots_[0].v_m_per_s;
        if (midpoints && j + 1 < count) store_mid(j, {knots_[0].x_m, knots_[0].v_m_per_s});
      }
    } else if (pieces_[piece].kind != PieceKind::oscillator) {
      // A Hermite piece as polynomials in s = (t - t_a) / h: x' = sum_n c_n s^n, and
      // x = x_a + h sum_n c_n s^(n+1) / (n+1), by Horner.
      const MotionKnot& a = knots_[piece];
      const MotionKnot& b = knots_[piece + 1];
      const std::array<double, 5> c =
          pieces_[piece].kind == PieceKind::quintic ? quintic_hermite_velocity(a, b) : cubic_hermite_velocity(a, b);
      const double h = b.t_s - a.t_s;
      const std::array<double, 5> xc{h * c[0], h * c[1] / 2.0, h * c[2] / 3.0, h * c[3] / 4.0, h * c[4] / 5.0};
      // Copies of the knot's time and displacement: read through `a`, they would be reloaded
      // after every store to the output (which could alias them), and the loop below would
      // not become SIMD pairs.
      const double t_a = a.t_s, x_a = a.x_m;
      auto at_s = [&](double s_) {
        const double v = c[0] + s_ * (c[1] + s_ * (c[2] + s_ * (c[3] + s_ * c[4])));
        const double x = x_a + s_ * (xc[0] + s_ * (xc[1] + s_ * (xc[2] + s_ * (xc[3] + s_ * xc[4]))));
        return PhasePoint{x, v};
      };
      const double inv_h = 1.0 / h;
      if (!midpoints) {
        const double* t = times_s.data();
        double* x_out = out.x_m.data();
        double* v_out = out.v_m_per_s.data();
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
        for (std::size_t i = j; i < end; ++i) {
          const PhasePoint p = at_s((t[i] - t_a) * inv_h);
          x_out[i] = p.x_m;
          v_out[i] = p.v_m_per_s;
        }
        j = end;
      }
      for (; j < end; ++j) {
        const PhasePoint p = at_s((times_s[j] - t_a) * inv_h);
        out.x_m[j] = p.x_m;
        out.v_m_per_s[j] = p.v_m_per_s;
        if (midpoints && j + 1 < count) {
          const double t_mid = 0.5 * (times_s[j] + times_s[j + 1]);
          store_mid(j, t_mid <= piece_end ? at_s((t_mid - t_a) / h) : midpoint(j));
        }
      }
    } else {
      // Midpoints up to mid_end lie on this piece; a later one (the last sample's, just
      // before the piece end) belongs to the next.
      std::size_t mid_end = midpoints ? end : j;
      while (mid_end > j && !(mid_end < count && 0.5 * (times_s[mid_end - 1] + times_s[mid_end]) <= piece_end)) --mid_end;
      OscillatorSamplingTask task{&knots_[piece], &pieces_[piece], w0_, step, times_s.data(), j, end,
                                  out.x_m.data(), out.v_m_per_s.data()};
      if (midpoints) {
        task.mid_x_m = out.mid_x_m.data();
        task.mid_v_m_per_s = out.mid_v_m_per_s.data();
        task.mid_end = mid_end;
      }
      sample_oscillator_piece(task, widest_sampling_lanes());
      if (midpoints) {
        for (std::size_t i = mid_end; i < end && i + 1 < count; ++i) store_mid(i, midpoint(i));
      }
      j = end;
    }
    if (piece + 1 < pieces_.size()) ++piece;
  }
}

std::vector<Event> Model2Motion::relative_velocity_events(double belt_velocity) const {
  std::vector<Event> events;
  auto crossing = [&](double t, double fb) {
    events.push_back({t, 0, fb < 0.0 ? EventKind::overtake : EventKind::regrip});
  };
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    const MotionKnot& a = knots_[i];
    const MotionKnot& b = knots_[i + 1];
    const double h = b.t_s - a.t_s;
    double fa = belt_velocity - a.v_m_per_s;
    if (pieces_[i].kind != PieceKind::oscillator) {
      const std::array<double, 5> c =
          pieces_[i].kind == PieceKind::quintic ? quintic_hermite_velocity(a, b) : cubic_hermite_velocity(a, b);
      // No zero possible when |v_r| at the start exceeds the bound sum_{n>=1} |c_n| on the
      // change of x' over the step (most steps).
      const double change_bound = std::abs(c[1]) + std::abs(c[2]) + std::abs(c[3]) + std::abs(c[4]);
      if (std::abs(fa) > change_bound) continue;
      auto vr = [&](double s) { return belt_velocity - (c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * c[4])))); };
      double sa = 0.0;
      constexpr std::array<double, 3> PROBES{0.25, 0.5, 0.75};
      for (std::size_t p = 0; p <= PROBES.size(); ++p) {
        // The step end is taken from the knot itself, as the next step's start will be, so
        // a crossing exactly at a knot is counted once.
        const double sb = p < PROBES.size() ? PROBES[p] : 1.0;
        const double fb = p < PROBES.size() ? vr(sb) : belt_velocity - b.v_m_per_s;
        if ((fa < 0.0) != (fb < 0.0)) crossing(a.t_s + locate_sign_change(vr, sa, fa, sb, fb) * h, fb);
        sa = sb;
        fa = fb;
      }
      continue;
    }
    // Propagator piece: the free oscillator's energy x_h^2 + (x_h'/w0)^2 never grows for
    // zeta >= 0 (it falls at -4 zeta (x_h'/w0)^2) and grows at most as e^{4 |zeta| w0 t}
    // otherwise, so |x_h'| <= w0 sqrt(energy); the polynomial part's velocity is bounded
    // by its coefficients' magnitudes at the piece end.
    const MotionPiece& osc = pieces_[i];
    double z0 = 0.0, dz0 = 0.0;
    free_oscillator_start(a, osc, w0_, z0, dz0);
    const double growth = osc.zeta >= 0.0 ? 1.0 : std::exp(2.0 * -osc.zeta * w0_ * h);
    const double tau_end = w0_ * h;
    double particular_bound = 0.0, power = 1.0;
    for (std::size_t j = 1; j < MOTION_PIECE_TERMS; ++j, power *= tau_end)
      particular_bound += static_cast<double>(j) * std::abs(osc.particular_m[j]) * power;
    const double speed_bound = w0_ * (std::sqrt(z0 * z0 + dz0 * dz0) * growth + particular_bound);
    if (std::abs(belt_velocity) > speed_bound && (fa < 0.0) == (belt_velocity < 0.0)) continue;
    auto vr = [&](double s) { return belt_velocity - on_piece(i, a.t_s + s * h).v_m_per_s; };
    const auto probes = static_cast<std::size_t>(std::ceil(w0_ * h / (2.0 * PI) * PROBES_PER_PERIOD)) + 1;
    // The probes walk the free oscillator with its flow over one probe spacing (as
    // sample() does); only a bracketed root is refined in closed form.
    const OscillatorFlow probe_step = OscillatorFlow::over(osc.zeta, w0_ * h / static_cast<double>(probes));
    double z = z0, dz = dz0;
    double sa = 0.0;
    for (std::size_t p = 1; p <= probes; ++p) {
      const double sb = p < probes ? static_cast<double>(p) / static_cast<double>(probes) : 1.0;
      probe_step.apply(z, dz);
      double zp = 0.0, dzp = 0.0;
      particular_at(osc, w0_ * sb * h, zp, dzp);
      const double fb = p < probes ? belt_velocity - w0_ * (dz + dzp) : belt_velocity - b.v_m_per_s;
      if ((fa < 0.0) != (fb < 0.0)) crossing(a.t_s + locate_sign_change(vr, sa, fa, sb, fb) * h, fb);
      sa = sb;
      fa = fb;
    }
  }
  return events;
}

}  // namespace stengmc
