#pragma once
//! The largest voltage the analyses of a record can take (spectra, noise levels, the inverse
//! estimator): they square and sum it over up to ~1e9 samples, and 1e100^2 x 1e9 stays far
//! below the largest double (1.8e308). A measured record beyond it is refused where it is
//! read; a device whose one-asperity voltage scale is beyond it, where it is checked.
namespace stengmc {

//! Largest |V| the analyses square and sum [V].
inline constexpr double MAX_ANALYSED_VOLTAGE_V = 1e100;

}  // namespace stengmc
