#pragma once
//! Analysis windows for spectra and spectrograms (MODEL.md §3).
#include <cstddef>
#include <string_view>
#include <vector>

namespace stengmc {

enum class WindowKind {
  rectangular,      //!< no taper: best resolution, worst leakage
  hann,             //!< raised cosine: the usual compromise (default)
  blackman_harris,  //!< 4-term, -92 dB side lobes: for weak lines beside strong ones
};

//! The n window weights (periodic / DFT-even form, so a Hann STFT with hop n/2 sums to a constant).
std::vector<double> make_window(WindowKind kind, std::size_t n);

//! a_j of the window as w_n = sum_j (-1)^j a_j cos(2 pi j n / n_total) (Harris 1978), for
//! closed-form window responses: {1}, {0.5, 0.5}, or the four Blackman-Harris terms.
std::vector<double> cosine_coefficients(WindowKind kind);

//! Parses "rectangular" | "hann" | "blackman_harris"; InputError naming `where` otherwise.
WindowKind parse_window(std::string_view text, std::string_view where);
std::string_view window_name(WindowKind kind);

}  // namespace stengmc
