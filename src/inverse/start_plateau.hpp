#pragma once
//! How many asperities are in contact when the record starts, read off its first plateau
//! (docs/tracking.md, n(t)). The known device starts every asperity at rest when the belt
//! starts (t = 0). The belt's friction F brings each one to the belt's velocity within the
//! ramp m v_b / F (18-36 ns with Table 1 values), and it stays stuck, x' = v_b, until its
//! spring holds F, at t_b = (F - c v_b) / (k v_b) (0.18-3 us for k = 20-160 N/m). Until the
//! stiffest asperity breaks away every one is stuck, and the voltage is the plateau
//! V = n R sigma w v_b (C_L = 0: V = R sum sigma w x'), an integer multiple of one stuck
//! asperity's voltage above the record's baseline. It is read as the first mean after the
//! ramp, over the time no plausible asperity can have broken away in, and believed only when
//! the record is flat there (a ring-down of a cropped capture is not) and an integer multiple
//! of the unit.
#include <cstddef>
#include <optional>
#include <span>

#include "inverse/known_device.hpp"
#include "inverse/record_grid.hpp"

namespace stengmc {

//! The start's plateau read as a count.
struct StartPlateau {
  std::size_t count = 0;  //!< asperities stuck to the belt at the start (>= 1)
  double level = 0.0;     //!< the plateau over R sigma w v_b, before rounding
  double level_se = 0.0;  //!< the level's standard error from the noise (baseline and plateau means)
  //! Whether the count may be off by one: its level further than PLATEAU_CERTAIN_OFFSET from
  //! its integer (a gain error), or its error above PLATEAU_CERTAIN_SE (the baseline is often
  //! one sample, whose noise in a crowd at 25 dB is ~0.14 unit). Its band is widened by one.
  [[nodiscard]] bool uncertain() const;
};

//! The largest distance of the plateau's level from an integer that is believed, plus the
//! level's error (a gain error, or a capture that is no plateau, moves it further) [asperities].
inline constexpr double PLATEAU_MAX_OFFSET = 0.25;
//! The distance from an integer beyond which the count's band is widened by one [asperities].
inline constexpr double PLATEAU_CERTAIN_OFFSET = 0.15;
//! The level's error beyond which the count's band is widened by one: 2.5 of them reach a
//! half [asperities].
inline constexpr double PLATEAU_CERTAIN_SE = 0.2;

//! The shortest span the plateau is read over [s]: 80 ns, ~8 samples at 100 MHz (the mean's
//! noise ~0.05 of one asperity at 25 dB in a crowd of 12), 2 at 25 MHz.
inline constexpr double PLATEAU_MIN_SPAN_S = 80e-9;

//! The number of asperities stuck to the belt at the record's start, or nothing when the
//! record cannot show it: it does not start with the belt (its first sample after t = 0 by
//! more than the ramp), the load's low pass (R C_L) or the sampling leaves no flat span
//! before the stiffest plausible asperity (`stiffest_n_per_m`) breaks away, the voltage is
//! not flat there within a few `noise_sigma_v`, or its level (above the baseline, in the sign
//! of sigma) is below one asperity or not near an integer multiple of R sigma w v_b.
std::optional<StartPlateau> asperities_at_start(const KnownDevice& device, double stiffest_n_per_m, double noise_sigma_v,
                                                const RecordGrid& grid, std::span<const double> voltage_v);

}  // namespace stengmc
