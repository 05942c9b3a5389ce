#pragma once
//! How strongly an event makes a free (unexcited) asperity ring (docs/tracking.md, event
//! amplitudes): the initial voltage amplitude, at the event, of the line a e^{-gamma t}
//! cos(2 pi f t + phi) an onset, a release or a stiffness step starts, from the model's
//! equations (docs/model.md 1.3, 1.4, 2.2) for the known device's load, friction and element.
//!
//! With C_L = 0 the terminal voltage follows the elements' velocities, V = R sum sigma w x'
//! (R sum C_i ~ 1e-11 s per element, five orders below the ringing's period), so a ringing of
//! velocity amplitude u shows as R sigma w u. While sliding the friction is F = N (mu_k +
//! (mu_s - mu_k) e^{-c_s v_b}) (the belt is ~v_b faster than the asperity) and the asperity
//! oscillates about x = F / k; the `consistent` friction law never lets it overtake the belt
//! (docs/model.md, 1.3): a swing that would exceed v_b sticks to the belt and breaks away
//! again at x' = v_b, so no ringing in contact exceeds u = v_b.
#include "inverse/known_device.hpp"

namespace stengmc {

//! Onset: from rest the belt drags the asperity at v_b until the spring holds F (k x = F), and
//! it breaks away there moving at v_b about its sliding equilibrium: u = v_b, the swing of
//! F / sqrt(k m) that a step force from rest would give being cut at the belt's velocity
//! (F / sqrt(k m) ~ 22-63 m/s > v_b for k = 20-160 N/m, Table 1 values) [V].
double onset_ringing_v(const KnownDevice& device, double stiffness_n_per_m);

//! Release: the load goes at once, so the asperity rings about x = 0 from x = F / k at rest,
//! u = F / sqrt(k m) (nothing limits the swing: no belt holds it any more) [V].
double release_ringing_v(const KnownDevice& device, double stiffness_n_per_m);

//! Stiffness step k -> k' while sliding at x = F / k: the equilibrium moves to F / k', so it
//! rings with u = F |1/k' - 1/k| sqrt(k'/m), at most v_b (the belt's limit above) [V].
double step_ringing_v(const KnownDevice& device, double stiffness_before_n_per_m, double stiffness_after_n_per_m);

//! The voltage a ringing of velocity amplitude u at stiffness k shows, |R sigma w| u through the
//! load's low pass 1 / sqrt(1 + (omega R C_L)^2) (the elements' own capacitance neglected): a
//! magnitude, as the lines' amplitudes are (a negative sigma only turns the ringing over) [V].
double ringing_voltage_v(const KnownDevice& device, double stiffness_n_per_m, double velocity_amplitude_m_per_s);

}  // namespace stengmc
