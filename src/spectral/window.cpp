#include "spectral/window.hpp"

#include <cmath>
#include <iterator>
#include <string>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

// Generalised cosine windows w_n = sum_j (-1)^j a_j cos(2 pi j n / N) in the periodic
// (DFT-even) form of Harris (1978), "On the use of windows for harmonic analysis with the
// discrete Fourier transform", Proc. IEEE 66(1), 51-83: dividing by N rather than N - 1
// makes the window one period of a periodic sequence, so its DFT has zeros on the bins
// (exact on-bin amplitudes) and a Hann STFT with hop N/2 sums to a constant.
constexpr double HANN[] = {0.5, 0.5};
// 4-term Blackman-Harris, -92 dB side lobes (Harris 1978, Table 1).
constexpr double BLACKMAN_HARRIS[] = {0.35875, 0.48829, 0.14128, 0.01168};

template <std::size_t Terms>
std::vector<double> cosine_window(const double (&a)[Terms], std::size_t n) {
  std::vector<double> w(n);
  const double step = 2.0 * PI / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    double value = 0.0;
    double sign = 1.0;
    for (std::size_t j = 0; j < Terms; ++j) {
      // j * i is reduced modulo n in integers so the cosine argument stays in [0, 2 pi)
      // and the window is symmetric (w_i = w_{n-i}) to rounding.
      value += sign * a[j] * std::cos(step * static_cast<double>((j * i) % n));
      sign = -sign;
    }
    w[i] = value;
  }
  return w;
}

}  // namespace

std::vector<double> make_window(WindowKind kind, std::size_t n) {
  if (n == 0) throw InputError("window: length must be at least 1 sample");
  // A one-sample periodic Hann or Blackman-Harris would be zero (or 6e-5): use the
  // identity as scipy.signal.get_window does, so sum w > 0 always.
  if (n == 1) return {1.0};
  switch (kind) {
    case WindowKind::rectangular: return std::vector<double>(n, 1.0);
    case WindowKind::hann: return cosine_window(HANN, n);
    case WindowKind::blackman_harris: return cosine_window(BLACKMAN_HARRIS, n);
  }
  throw InputError("window: unknown window kind");
}

std::vector<double> cosine_coefficients(WindowKind kind) {
  switch (kind) {
    case WindowKind::rectangular: return {1.0};
    case WindowKind::hann: return {std::begin(HANN), std::end(HANN)};
    case WindowKind::blackman_harris: return {std::begin(BLACKMAN_HARRIS), std::end(BLACKMAN_HARRIS)};
  }
  throw InputError("window: unknown window kind");
}

WindowKind parse_window(std::string_view text, std::string_view where) {
  for (WindowKind kind : {WindowKind::rectangular, WindowKind::hann, WindowKind::blackman_harris}) {
    if (text == window_name(kind)) return kind;
  }
  throw InputError(std::string(where) + ": window = \"" + std::string(text) +
                   "\" is not one of \"rectangular\", \"hann\", \"blackman_harris\"");
}

std::string_view window_name(WindowKind kind) {
  switch (kind) {
    case WindowKind::rectangular: return "rectangular";
    case WindowKind::hann: return "hann";
    case WindowKind::blackman_harris: return "blackman_harris";
  }
  return "unknown";
}

}  // namespace stengmc
