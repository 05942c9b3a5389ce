#pragma once
//! High-resolution line estimation: ESPRIT (Roy & Kailath 1989) on a Hankel data matrix
//! with Eigen's SVD, the model order chosen by an information criterion. Resolves lines
//! closer than 1/T, where FFT peaks merge.
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

namespace stengmc {

enum class OrderCriterion {
  mdl,    //!< minimum description length (Wax & Kailath 1985): the default; on noise-free signals it
          //!< runs towards max_lines (weak extra lines, which a dynamic-range cut removes)
  aic,    //!< Akaike: tends to over-estimate at high SNR
  ester,  //!< ESTimation ERror (Badeau, David & Richard 2006): from the shift invariance itself; fewest
          //!< wrong orders on exponential lines, but finds none when lines are not exponentials
          //!< (stick-modulated, e.g. Fig. 6 at v_b = 1 m/s)
};

OrderCriterion parse_order_criterion(std::string_view text, std::string_view where);
std::string_view order_criterion_name(OrderCriterion criterion);

struct EspritOptions {
  std::size_t max_lines = 16;         //!< largest number of real lines considered
  OrderCriterion criterion = OrderCriterion::mdl;
  std::size_t fixed_lines = 0;        //!< > 0: skip the criterion and use this many lines
  std::size_t max_samples = 16384;    //!< longer signals: only the first max_samples samples are analysed
  std::size_t max_hankel_rows = 256;  //!< cap on the Hankel rows L (~N/3 otherwise): cost O(L^3 + L N)
  double min_frequency_hz = 0.0;      //!< drop lines below (DC, drift)
  bool refine = true;                 //!< polish ESPRIT's lines by nonlinear least squares on all analysed samples
};

//! One real line a e^{-d t} cos(2 pi f t + phi).
struct Line {
  double frequency_hz = 0.0;
  double amplitude = 0.0;     //!< a at the first sample, signal unit
  double damping_per_s = 0.0; //!< d (>= 0 decays)
  double phase_rad = 0.0;
};

//! Lines of a real signal, sorted by frequency (positive frequencies only).
std::vector<Line> estimate_lines(std::span<const double> signal, double sample_rate_hz, const EspritOptions& options);

}  // namespace stengmc
