#include "tribology/oscillator_sampling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "core/processor_features.hpp"
#include "tribology/oscillator_flow.hpp"

namespace stengmc {

namespace {

static_assert(MOTION_PIECE_TERMS == 7, "Estrin's scheme below is written for degree 6");

// Samples of a walk between re-anchorings in closed form: the flow's rounding (a few ulp
// of the free oscillator's state per multiplication, 32 multiplications at most with four
// walks) then stays ~1e-14 of the length scale (against the closed form in long double,
// test_oscillator_sampling.cpp: 3e-16 of max|x|, 1.5e-14 of max|x'|; anchoring more often
// costs an exp and a sincos each). A propagator piece whose free part is r times larger
// than the motion (its polynomial part cancels it, sliding_propagator.hpp) re-anchors r
// times as often.
constexpr std::size_t REANCHOR_POINTS = 128;
// Interleaved walks: each sample is the flow applied to the sample this many before it.
// One walk would chain a multiply and an add per sample (~8 cycles of latency); four
// chain them once per four samples, and the four fill one AVX register or two SSE2 ones.
constexpr int WALKS = 4;

// GCC/Clang vector extensions: element-wise IEEE arithmetic in `Lanes` lanes (SSE2 or
// AVX registers, whichever the function is compiled for), a scalar operand broadcast.
template <int Lanes>
struct LaneVector {
  typedef double type __attribute__((vector_size(8 * Lanes)));
};

//! Samples between closed-form anchors: where the free part is r times the motion's
//! scale, its rounding is too, so the walk re-anchors r times as often.
std::size_t reanchor_points(const OscillatorSamplingTask& task) {
  double z = 0.0, dz = 0.0;
  free_oscillator_start(*task.start, *task.piece, task.w0_rad_per_s, z, dz);
  const double scale =
      std::abs(task.start->x_m - task.piece->centre_m) + std::abs(task.start->v_m_per_s / task.w0_rad_per_s);
  const double cancellation = (std::abs(z) + std::abs(dz)) / std::max(scale, 1e-300);
  if (cancellation <= 1.0) return REANCHOR_POINTS;
  return std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(REANCHOR_POINTS) / cancellation));
}

//! Lanes [0, valid) of `value` to out[0 ..): one unaligned vector store when all are.
template <int Lanes, class V>
[[gnu::always_inline]] inline void store(double* out, const V& value, std::size_t valid) {
  if (valid >= static_cast<std::size_t>(Lanes)) {
    std::memcpy(out, &value, sizeof value);
    return;
  }
  for (std::size_t i = 0; i < valid; ++i) out[i] = value[i];
}

//! x = centre + z_h + x_p and x' = w0 (z_h' / w0 + x_p' / w0) at the lanes' tau, stored
//! to x_out, v_out (lanes [0, valid)); x_p and x_p' / w0 by Estrin's scheme (Knuth, TAOCP
//! vol. 2, Sec. 4.6.4: three levels of independent multiply-adds where Horner's rule
//! chains six). Vectors by reference, inlined: a by-value AVX vector would cross a non-AVX
//! call.
template <int Lanes, class V>
[[gnu::always_inline]] inline void store_state(const std::array<double, MOTION_PIECE_TERMS>& px,
                                               const std::array<double, MOTION_PIECE_TERMS - 1>& pv, double centre,
                                               double w0, const V& z, const V& dz, const V& tau, double* x_out,
                                               double* v_out, std::size_t valid) {
  const V t2 = tau * tau;
  const V t4 = t2 * t2;
  const V xp = ((px[0] + px[1] * tau) + (px[2] + px[3] * tau) * t2) + ((px[4] + px[5] * tau) + px[6] * t2) * t4;
  const V vp = ((pv[0] + pv[1] * tau) + (pv[2] + pv[3] * tau) * t2) + (pv[4] + pv[5] * tau) * t4;
  store<Lanes>(x_out, (centre + z) + xp, valid);
  store<Lanes>(v_out, w0 * (dz + vp), valid);
}

//! The walk for a width of `Lanes` samples (2 or 4): WALKS / Lanes vectors per pass, each
//! lane doing exactly what a one-lane walk would. Helpers are always_inline functions, not
//! lambdas: a lambda would not inherit walk_four's target and would pass AVX vectors
//! through a non-AVX call.
template <int Lanes>
[[gnu::always_inline]] inline void walk(const OscillatorSamplingTask& task) {
  using V = typename LaneVector<Lanes>::type;
  constexpr int VECTORS = WALKS / Lanes;
  static_assert(VECTORS * Lanes == WALKS);
  const MotionKnot& a = *task.start;
  const MotionPiece& osc = *task.piece;
  const double w0 = task.w0_rad_per_s;
  const double w0_step = w0 * task.step_s;
  const OscillatorFlow half_step = OscillatorFlow::over(osc.zeta, 0.5 * w0_step);
  const OscillatorFlow full_step = half_step.doubled();
  const OscillatorFlow double_step = full_step.doubled();
  const OscillatorFlow walk_step = double_step.doubled();  // over WALKS spacings
  // x_p and x_p' / w0 as polynomials in tau (x_p' / w0 one degree lower: a term fewer).
  std::array<double, MOTION_PIECE_TERMS> px{};
  std::array<double, MOTION_PIECE_TERMS - 1> pv{};
  for (std::size_t k = 0; k < MOTION_PIECE_TERMS; ++k) px[k] = osc.particular_m[k];
  for (std::size_t k = 0; k + 1 < MOTION_PIECE_TERMS; ++k) pv[k] = static_cast<double>(k + 1) * osc.particular_m[k + 1];
  std::array<V, VECTORS> offsets{};
  for (int g = 0; g < VECTORS; ++g)
    for (int i = 0; i < Lanes; ++i) offsets[static_cast<std::size_t>(g)][i] = static_cast<double>(g * Lanes + i);
  const double centre = osc.centre_m;
  const bool midpoints = task.mid_x_m != nullptr;
  const std::size_t reanchor = reanchor_points(task);
  std::size_t j = task.first;
  while (j < task.end) {
    // Anchor in closed form; samples 1, 2, 3 of the block one, two and three spacings on.
    const double tau0 = w0 * (task.times_s[j] - a.t_s);
    std::array<double, WALKS> z0{}, dz0{};
    free_oscillator_start(a, osc, w0, z0[0], dz0[0]);
    OscillatorFlow::over(osc.zeta, tau0).apply(z0[0], dz0[0]);
    z0[1] = z0[0];
    dz0[1] = dz0[0];
    full_step.apply(z0[1], dz0[1]);
    for (std::size_t i = 2; i < static_cast<std::size_t>(WALKS); ++i) {
      z0[i] = z0[i - 2];
      dz0[i] = dz0[i - 2];
      double_step.apply(z0[i], dz0[i]);
    }
    std::array<V, VECTORS> z{}, dz{};
    for (int g = 0; g < VECTORS; ++g) {
      for (int i = 0; i < Lanes; ++i) {
        z[static_cast<std::size_t>(g)][i] = z0[static_cast<std::size_t>(g * Lanes + i)];
        dz[static_cast<std::size_t>(g)][i] = dz0[static_cast<std::size_t>(g * Lanes + i)];
      }
    }
    const std::size_t block_end = std::min(task.end, j + reanchor);
    const std::size_t mid_block_end = std::min(block_end, task.mid_end);
    for (std::size_t k = 0; j < block_end; j += WALKS, k += WALKS) {
      for (std::size_t g = 0; g < static_cast<std::size_t>(VECTORS); ++g) {
        V& zg = z[g];
        V& dzg = dz[g];
        if (k > 0) {
          const V z1 = walk_step.m00 * zg + walk_step.m01 * dzg;
          dzg = walk_step.m10 * zg + walk_step.m11 * dzg;
          zg = z1;
        }
        const std::size_t at = j + g * Lanes;
        if (at >= block_end) break;
        const V tau = tau0 + (static_cast<double>(k) + offsets[g]) * w0_step;
        store_state<Lanes>(px, pv, centre, w0, zg, dzg, tau, task.x_m + at, task.v_m_per_s + at, block_end - at);
        if (midpoints && at < mid_block_end) {
          const V zm = half_step.m00 * zg + half_step.m01 * dzg;
          const V dzm = half_step.m10 * zg + half_step.m11 * dzg;
          const V tm = tau + 0.5 * w0_step;
          store_state<Lanes>(px, pv, centre, w0, zm, dzm, tm, task.mid_x_m + at, task.mid_v_m_per_s + at,
                             mid_block_end - at);
        }
      }
    }
    j = block_end;
  }
}

void walk_two(const OscillatorSamplingTask& task) { walk<2>(task); }

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define STENGMC_FOUR_LANES 1
// AVX2 alone, not FMA: a fused multiply-add rounds once where the two-lane code rounds
// twice, and the widths would no longer agree bit for bit.
[[gnu::target("avx2")]] void walk_four(const OscillatorSamplingTask& task) { walk<4>(task); }
#endif

}  // namespace

SamplingLanes widest_sampling_lanes() {
#ifdef STENGMC_FOUR_LANES
  if (processor_has_avx2()) return SamplingLanes::four;
#endif
  return SamplingLanes::two;
}

void sample_oscillator_piece(const OscillatorSamplingTask& task, SamplingLanes lanes) {
#ifdef STENGMC_FOUR_LANES
  if (lanes == SamplingLanes::four && widest_sampling_lanes() == SamplingLanes::four) {
    walk_four(task);
    return;
  }
#endif
  walk_two(task);
}

}  // namespace stengmc
