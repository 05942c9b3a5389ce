#pragma once
#include <memory>
#include <span>
#include <vector>

namespace stengmc {

//! Displacement and velocity of an asperity at one instant.
struct PhasePoint {
  double x_m = 0.0;          //!< displacement [m]
  double v_m_per_s = 0.0;    //!< velocity [m/s]
};

//! Which one-sided limit to take where the velocity jumps (piecewise-linear input).
enum class Side { left, right };

//! A motion sampled on increasing times t_j and at the midpoints (t_j + t_j+1) / 2: what
//! the streamed circuit (circuit/element_sums.hpp) interpolates, and what files, summaries
//! and the domain check read. Buffers keep their capacity between uses.
struct MotionSamples {
  std::vector<double> x_m;          //!< x(t_j) [m]
  std::vector<double> v_m_per_s;    //!< x'(t_j), right limit [m/s]
  //! x'(t_j), left limit [m/s]; empty when it equals the right limit at every sample
  //! (x' jumps only at breakpoints, and none of them is a sample time)
  std::vector<double> v_left_m_per_s;
  std::vector<double> mid_x_m;        //!< x at the midpoints, one fewer [m]
  std::vector<double> mid_v_m_per_s;  //!< x' at the midpoints [m/s]

  //! x'(t_j) from the left.
  [[nodiscard]] double v_left(std::size_t j) const { return v_left_m_per_s.empty() ? v_m_per_s[j] : v_left_m_per_s[j]; }
};

//! Continuous-time motion x(t), x'(t) of one asperity: the dense output of a tribology
//! solver or an interpolant through samples. The circuit solver evaluates it between
//! output samples, so its own accuracy is what the circuit sees (MODEL.md §2).
class Motion {
 public:
  virtual ~Motion() = default;

  //! State at time t [s]; `side` selects the one-sided limit where x' jumps.
  [[nodiscard]] virtual PhasePoint at(double t_s, Side side = Side::right) const = 0;

  //! Sorted times [s] where x' or x'' is not smooth (stick/slip transitions, sample
  //! knots of a linear interpolant). The circuit solver never steps across one.
  [[nodiscard]] virtual const std::vector<double>& breakpoints() const = 0;

  //! Sorted times where the motion changes on a finer scale than samples `resolution_s`
  //! apart resolve, though it has no breakpoint there (Model 2 catching the belt within
  //! picoseconds). The streamed circuit evaluates the motion exactly in the sample
  //! intervals holding one, with finer steps (circuit/element_sums.hpp). None by default.
  [[nodiscard]] virtual std::vector<double> fine_structure(double resolution_s) const {
    (void)resolution_s;
    return {};
  }

  //! An upper bound on x over the whole motion [m], +inf when unknown (the default). Where
  //! it is below an element's l, x cannot reach l and the domain check has nothing to do.
  [[nodiscard]] virtual double displacement_bound() const;

  //! A motion equal to this one, bit for bit, at every time in [t0_s, t1_s] (either side),
  //! holding only what it needs there; nullptr (the default) when the motion has no smaller
  //! form. The streamed circuit keeps one for the few sample intervals where it evaluates a
  //! motion exactly (a kink inside: circuit/element_sums.hpp), so that a long run need not
  //! keep every asperity's whole dense output until the circuit is solved.
  [[nodiscard]] virtual std::unique_ptr<Motion> excerpt(double t0_s, double t1_s) const;

  //! The motion at `times_s` (strictly increasing) and, when `midpoints`, at the midpoints
  //! between them, into `out` (resized). The default evaluates at() at each; a motion
  //! with a cheaper way along a uniform grid (Model 2's oscillator pieces) overrides it.
  virtual void sample(std::span<const double> times_s, bool midpoints, MotionSamples& out) const;
};

}  // namespace stengmc
