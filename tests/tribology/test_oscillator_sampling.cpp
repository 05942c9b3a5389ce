// Sampling a sliding-propagator piece on a uniform grid (tribology/oscillator_sampling.hpp)
// and the grid test that decides when that walk is used (tribology/time_grid.hpp).
// References: the closed form of each piece evaluated in long double (independent of the
// walk: no flow is multiplied, every point is exp/cos/sin of its own time), and the two
// SIMD widths against each other (promised bit for bit).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/processor_features.hpp"
#include "tribology/model2.hpp"
#include "tribology/model2_integrator.hpp"
#include "tribology/oscillator_sampling.hpp"
#include "tribology/time_grid.hpp"

namespace stengmc {
namespace {

struct Exact {
  long double x, v;
};

//! x and x' of an oscillator piece at t, in long double: x = centre + z_h + x_p, z_h the
//! free damped oscillator from the piece's start state (MotionPiece's definition).
Exact exact_on_piece(const MotionKnot& a, const MotionPiece& piece, double w0, double t_s) {
  const long double tau = static_cast<long double>(w0) * (static_cast<long double>(t_s) - a.t_s);
  long double xp = 0.0L, dxp = 0.0L;
  for (std::size_t j = MOTION_PIECE_TERMS; j-- > 0;) xp = xp * tau + piece.particular_m[j];
  for (std::size_t j = MOTION_PIECE_TERMS; j-- > 1;) dxp = dxp * tau + static_cast<long double>(j) * piece.particular_m[j];
  const long double z0 = static_cast<long double>(a.x_m) - piece.centre_m - piece.particular_m[0];
  const long double dz0 = static_cast<long double>(a.v_m_per_s) / w0 - piece.particular_m[1];
  const long double zeta = piece.zeta;  // the tests' pieces are under-damped
  const long double w = std::sqrt((1.0L - zeta) * (1.0L + zeta));
  const long double decay = std::exp(-zeta * tau);
  const long double c = decay * std::cos(w * tau), s = decay * std::sin(w * tau) / w;
  // exp(tau M) = e^{-zeta tau} [C I + S (M + zeta I)], M = [[0, 1], [-1, -2 zeta]].
  const long double z = (c + zeta * s) * z0 + s * dz0;
  const long double dz = -s * z0 + (c - zeta * s) * dz0;
  return {piece.centre_m + z + xp, static_cast<long double>(w0) * (dz + dxp)};
}

//! The k = 25 N/m Table-1 asperity at v_b = 1 m/s over 50 us: ~60 oscillator pieces.
Model2Integration sliding_run() {
  Model2Params params;
  params.belt_velocity_m_per_s = 1.0;
  Asperity asperity;
  asperity.stiffness_n_per_m = 25.0;
  return integrate_model2(asperity, params, 50e-6);
}

//! Every oscillator piece's share of `times` sampled with `lanes` into x, v (and the
//! midpoints into mx, mv), as Model2Motion::sample does.
void sample_all(const Model2Integration& run, const std::vector<double>& times, double step, SamplingLanes lanes,
                std::vector<double>& x, std::vector<double>& v, std::vector<double>& mx, std::vector<double>& mv) {
  x.assign(times.size(), std::numeric_limits<double>::quiet_NaN());
  v = x;
  mx = x;
  mv = x;
  std::size_t j = 0;
  for (std::size_t p = 0; p < run.pieces.size(); ++p) {
    std::size_t end = j;
    while (end < times.size() && times[end] <= run.knots[p + 1].t_s) ++end;
    if (run.pieces[p].kind == PieceKind::oscillator && end > j) {
      OscillatorSamplingTask task{&run.knots[p], &run.pieces[p], run.natural_frequency_rad_per_s, step,
                                  times.data(), j, end, x.data(), v.data()};
      task.mid_x_m = mx.data();
      task.mid_v_m_per_s = mv.data();
      task.mid_end = end;
      sample_oscillator_piece(task, lanes);
    }
    j = end;
  }
}

// Each sample and midpoint of every oscillator piece against the piece's closed form in
// long double. The walk multiplies by a rounded flow up to 32 times between closed-form
// anchors; measured 3e-16 of max|x| and 1.5e-14 of max|x'| (x' loses more: it is a
// difference of swings ~w0 x large). The bounds, 1e-14 and 1e-13, are what the
// re-anchoring interval was chosen to hold.
TEST(OscillatorSampling, SamplesAndMidpointsMatchTheClosedForm) {
  const Model2Integration run = sliding_run();
  const TimeGrid grid = TimeGrid::covering(50e-6, 100e6);
  const std::vector<double> times = grid.times();
  std::vector<double> x, v, mx, mv;
  sample_all(run, times, grid.step_s, widest_sampling_lanes(), x, v, mx, mv);
  double x_scale = 0.0, v_scale = 0.0;
  for (const MotionKnot& k : run.knots) {
    x_scale = std::max(x_scale, std::abs(k.x_m));
    v_scale = std::max(v_scale, std::abs(k.v_m_per_s));
  }
  std::size_t checked = 0, j = 0;
  for (std::size_t p = 0; p < run.pieces.size(); ++p) {
    for (; j < times.size() && times[j] <= run.knots[p + 1].t_s; ++j) {
      if (run.pieces[p].kind != PieceKind::oscillator) continue;
      const double w0 = run.natural_frequency_rad_per_s;
      const Exact e = exact_on_piece(run.knots[p], run.pieces[p], w0, times[j]);
      ASSERT_NEAR(x[j], static_cast<double>(e.x), 1e-14 * x_scale) << "t = " << times[j];
      ASSERT_NEAR(v[j], static_cast<double>(e.v), 1e-13 * v_scale) << "t = " << times[j];
      const Exact m = exact_on_piece(run.knots[p], run.pieces[p], w0, times[j] + 0.5 * grid.step_s);
      ASSERT_NEAR(mx[j], static_cast<double>(m.x), 1e-14 * x_scale) << "t = " << times[j];
      ASSERT_NEAR(mv[j], static_cast<double>(m.v), 1e-13 * v_scale) << "t = " << times[j];
      ++checked;
    }
  }
  EXPECT_GT(checked, 3000u);  // most of the run slides
}

// The widths promise the same bits (no fused multiply-add; the same operations lane by
// lane): what keeps results identical between machines with and without AVX2.
TEST(OscillatorSampling, WidthsGiveTheSameBits) {
  if (widest_sampling_lanes() != SamplingLanes::four) GTEST_SKIP() << "this processor has no AVX2: one width only";
  const Model2Integration run = sliding_run();
  const TimeGrid grid = TimeGrid::covering(50e-6, 100e6);
  const std::vector<double> times = grid.times();
  std::vector<double> x2, v2, mx2, mv2, x4, v4, mx4, mv4;
  sample_all(run, times, grid.step_s, SamplingLanes::two, x2, v2, mx2, mv2);
  sample_all(run, times, grid.step_s, SamplingLanes::four, x4, v4, mx4, mv4);
  const std::size_t bytes = times.size() * sizeof(double);
  EXPECT_EQ(std::memcmp(x2.data(), x4.data(), bytes), 0);  // NaN where no piece sampled: same bits too
  EXPECT_EQ(std::memcmp(v2.data(), v4.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(mx2.data(), mx4.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(mv2.data(), mv4.data(), bytes), 0);
}

// A piece whose free part is ~1000 times its motion (the polynomial cancels it) is
// re-anchored every sample, so its rounding stays a few ulp of the free part (1e-3 m:
// ulp 2.2e-19 m): measured 1.1e-18 m over 400 samples, against 2.3e-17 m when walked 128
// samples between anchors as an ordinary piece is. Counts 1..9 exercise every tail of a
// four-sample pass.
TEST(OscillatorSampling, CancellingPiecesStayAccurateRelativeToTheMotion) {
  MotionKnot start{0.0, 1e-6, 0.0, 0.0};
  MotionPiece piece;
  piece.kind = PieceKind::oscillator;
  piece.zeta = 0.05;
  piece.centre_m = 0.0;
  piece.particular_m = {1e-3, 0.0, 2e-7, -1e-9, 0.0, 0.0, 0.0};  // z_h(0) = 1e-6 - 1e-3
  const double w0 = 5e6;
  const double step = 1e-8;
  for (const std::size_t count : {1, 2, 3, 4, 5, 6, 7, 8, 9, 400}) {
    std::vector<double> times(count);
    for (std::size_t j = 0; j < count; ++j) times[j] = static_cast<double>(j) * step;
    std::vector<double> x(count), v(count), mx(count), mv(count);
    for (const SamplingLanes lanes : {SamplingLanes::two, SamplingLanes::four}) {
      OscillatorSamplingTask task{&start, &piece, w0, step, times.data(), 0, count, x.data(), v.data()};
      task.mid_x_m = mx.data();
      task.mid_v_m_per_s = mv.data();
      task.mid_end = count;
      sample_oscillator_piece(task, lanes);
      for (std::size_t j = 0; j < count; ++j) {
        const Exact e = exact_on_piece(start, piece, w0, times[j]);
        const Exact m = exact_on_piece(start, piece, w0, times[j] + 0.5 * step);
        EXPECT_NEAR(x[j], static_cast<double>(e.x), 3e-18) << "count " << count << ", j " << j;
        EXPECT_NEAR(mx[j], static_cast<double>(m.x), 3e-18) << "count " << count << ", j " << j;
        EXPECT_NEAR(v[j], static_cast<double>(e.v), 3e-18 * w0) << "count " << count << ", j " << j;
        EXPECT_NEAR(mv[j], static_cast<double>(m.v), 3e-18 * w0) << "count " << count << ", j " << j;
      }
    }
  }
}

// The grid test behind the walk: every spacing within 1e-9 of the step, whichever lane
// or tail position a bad one falls on, and a NaN anywhere fails it; in its AVX and its
// scalar version.
TEST(EvenlySpaced, EverySpacingIsCheckedAndNaNFails) {
  const double step = 1e-8;
  for (const bool baseline : {false, true}) {
    use_baseline_instructions_only(baseline);
    for (std::size_t count = 0; count <= 11; ++count) {
      std::vector<double> t(count);
      for (std::size_t j = 0; j < count; ++j) t[j] = static_cast<double>(j) * step;
      EXPECT_TRUE(evenly_spaced(t, step)) << count;
      for (std::size_t bad = 1; bad < count; ++bad) {
        std::vector<double> shifted = t;
        shifted[bad] += 1e-6 * step;  // far above 1e-9 of the step
        EXPECT_FALSE(evenly_spaced(shifted, step)) << count << " " << bad;
        std::vector<double> nan = t;
        nan[bad] = std::numeric_limits<double>::quiet_NaN();
        EXPECT_FALSE(evenly_spaced(nan, step)) << count << " " << bad;
        std::vector<double> slight = t;
        slight[bad] += 1e-10 * step;  // within tolerance
        EXPECT_TRUE(evenly_spaced(slight, step)) << count << " " << bad;
      }
    }
  }
  use_baseline_instructions_only(false);
}

}  // namespace
}  // namespace stengmc
