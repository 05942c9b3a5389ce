#pragma once
//! Dense output of the Model 2 integrator: between consecutive step ends (knots) the
//! Hermite interpolant of a RODAS4 step or the exact solution of a sliding-propagator step
//! (PieceKind, model2_integrator.hpp).
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "tribology/events.hpp"
#include "model/hermite.hpp"
#include "tribology/model2_integrator.hpp"
#include "model/motion.hpp"

namespace stengmc {

class Model2Motion final : public Motion {
 public:
  //! Takes the integrator's knots (strictly increasing times, at least one) and pieces
  //! (one per pair of consecutive knots).
  //! @throws ModelError if the knots are empty or not increasing, or the counts disagree.
  explicit Model2Motion(Model2Integration integration);

  //! State at t [s], t within [first knot, last knot] (1e-9 relative slack at the ends).
  //! @throws ModelError for t outside that range.
  [[nodiscard]] PhasePoint at(double t_s, Side side = Side::right) const override;

  //! Empty: x is C^1 everywhere, C^2 inside each piece; the stiff transitions are resolved
  //! by the step sizes.
  [[nodiscard]] const std::vector<double>& breakpoints() const override { return breakpoints_; }

  //! The ends of every step shorter than a quarter of `resolution_s` (the catch of the
  //! belt, breakaway): x' turns there within picoseconds, which no interpolation through
  //! samples `resolution_s` apart follows.
  [[nodiscard]] std::vector<double> fine_structure(double resolution_s) const override;

  //! The largest of the pieces' bounds: a Hermite piece rises at most h sum_n |c_n| / (n+1)
  //! above its start (its velocity quartic integrated term by term), an oscillator piece
  //! stays within centre + sqrt((x - centre)^2 + (x'/w0)^2) at its start (the free
  //! oscillator's energy) + tau max|P| (the response to its polynomial forcing P), both
  //! times the growth e^{|zeta| tau} for zeta < 0.
  [[nodiscard]] double displacement_bound() const override;

  //! The knots and pieces that hold [t0_s, t1_s] and one piece more on either side (so that
  //! piece_of picks the same piece for every time in between): a few knots instead of the
  //! millions of a long excited run.
  [[nodiscard]] std::unique_ptr<Motion> excerpt(double t0_s, double t1_s) const override;

  //! As Motion::sample; on a uniform grid an oscillator piece is walked by repeated
  //! multiplication with its flow (sample_oscillator_piece: four interleaved walks,
  //! re-anchored in closed form every 128 points, so rounding cannot drift: ~1e-14
  //! relative), a few multiplications per sample instead of an exponential and a sine.
  void sample(std::span<const double> times_s, bool midpoints, MotionSamples& out) const override;

  //! Sign changes of v_r = v_b - x' (overtake: to negative, regrip: to positive), located
  //! to ~1e-15 of the step. A step is skipped when no sign change is possible (a bound on
  //! x' over it); otherwise it is probed (Hermite pieces at 1/4, 1/2, 3/4 and the end;
  //! oscillator pieces every 1/16 of the undamped period), so two crossings closer than
  //! the probe spacing (v_r grazing zero) can be missed. Event::asperity is 0.
  [[nodiscard]] std::vector<Event> relative_velocity_events(double belt_velocity_m_per_s) const;

  //! Hands the knots and pieces back (for reuse by the next integration); the motion is
  //! empty afterwards and must not be evaluated.
  [[nodiscard]] Model2Integration release() &&;

  [[nodiscard]] std::size_t knot_count() const { return knots_.size(); }
  [[nodiscard]] const MotionKnot& knot(std::size_t i) const { return knots_[i]; }

 private:
  //! State at t on piece i (t may lie slightly outside it: the piece is extrapolated).
  [[nodiscard]] PhasePoint on_piece(std::size_t i, double t_s) const;
  //! Index of the piece holding t (clamped to the first/last).
  [[nodiscard]] std::size_t piece_of(double t_s) const;

  std::vector<MotionKnot> knots_;
  std::vector<MotionPiece> pieces_;
  double w0_;
  std::vector<double> breakpoints_;
};

}  // namespace stengmc
