#pragma once
//! Unexcited: what each new track's first line is, told by how strongly it rings
//! (docs/tracking.md, linking). The known device fixes every asperity's load, so the physics
//! predicts the initial amplitude of the free ringing each kind of event starts
//! (inverse/event_ringing.hpp): an onset rings at the belt's limit R sigma w v_b, a release at
//! R sigma w F / sqrt(k m) (2-12 x louder in the validation's prior), a step in proportion to
//! its jump and at most at the belt's limit. A track born after the record's first window is
//! judged by its first line that starts after its birth, extrapolated back to the birth along
//! e^{-gamma t}:
//!  - as loud as a release: a held track's release (its line within the gate), or the release
//!    of an asperity never heard before (in contact from the record's start);
//!  - as loud as an onset: an onset, as before, when it is heard about as long as a free
//!    ringing of its level stays above the threshold (else the fit's artefact of a partial
//!    ringing in the windows that straddle someone's onset: unexplained, below);
//!  - much weaker than an onset: no onset. A held track's line re-heard (within the gate), a
//!    step of a held track within a step's reach when the ringing fits the jump, a ringing that
//!    began at the record's start (its amplitude there that of an onset: the crowded start
//!    resolved late), or else a line no event explains (leakage, beats, a step of an asperity
//!    never heard): kept while it is heard, not held.
#include <vector>

#include "inverse/known_device.hpp"
#include "inverse/track_linking.hpp"
#include "inverse/track_windows.hpp"

namespace stengmc {

//! The factor within which a measured ringing must match its prediction: the birth time is
//! known to about +-0.65 window (an onset heard from a 30 % share of its first window), which
//! is e^{+-gamma 6.5 us} = x/1.4 on the extrapolated amplitude, and a line within 1/T of a
//! neighbour has its window amplitude biased by up to ~30 %: 1.4 x 1.3 ~ 2.
inline constexpr double RINGING_TOLERANCE = 2.0;

//! Unexcited: a held track's release is a burst as loud as a release (R sigma w F / sqrt(k m),
//! within RINGING_TOLERANCE, and nearer it than an onset's). A burst as loud as an onset on its
//! line is a new asperity's onset there: split off as a track of its own; a weaker one is the
//! held line re-heard: the track is not released. `lag`: windows that overlap one.
void confirm_releases(const KnownDevice& device, std::vector<Track>& tracks, const std::vector<TrackWindow>& windows,
                      std::size_t lag);

//! Re-reads the births of `tracks` (unexcited) as above: merges re-heard lines, steps and
//! releases into the held tracks they belong to (the merged track left empty and dropped),
//! and sets each remaining track's `birth`. `link` gives the gate and the wear drift;
//! `threshold_snr` is the detection threshold; `lag`: windows that overlap one (a held track's
//! sightings in the `lag` windows before a birth straddle it and are not its line before it).
void classify_track_births(const KnownDevice& device, std::vector<Track>& tracks, const std::vector<TrackWindow>& windows,
                           const LinkSettings& link, double max_wear_per_ms, double threshold_snr, std::size_t lag);

}  // namespace stengmc
