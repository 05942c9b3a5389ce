// What a new unexcited track is, judged by how strongly it rings (inverse/track_births.hpp):
// synthetic tracks whose lines ring exactly as the closed forms of inverse/event_ringing.hpp
// predict for an onset, a release, a step and a weak re-hearing, against what each must become.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "inverse/event_ringing.hpp"
#include "inverse/known_device.hpp"
#include "inverse/track_births.hpp"
#include "inverse/track_events.hpp"
#include "inverse/track_lines.hpp"
#include "inverse/track_windows.hpp"
#include "pipeline/study.hpp"
#include "support/table1_study.hpp"

namespace stengmc {
namespace {

//! The births' device; `charge` its charge density [C/m^2] and `damping` its c [N s/m].
KnownDevice test_device(const std::string& charge = "80e-6", const std::string& damping = "1e-7") {
  const Study study = parse_study("duration_s = 1e-3\nsample_rate_hz = 100e6\n" +
                                      testing::table1_device_keys({.damping_n_s_per_m = damping,
                                                                   .charge_density_c_per_m2 = charge}) +
                                      R"(
[[surface.asperity]]
stiffness_n_per_m = 60
)",
                                  "births.toml");
  return known_device_from_study(study);
}

struct Fixture {
  KnownDevice device;
  RecordGrid grid{0.0, 1e-8, 100000};
  // (The damped device's windows for every device: an undamped one has no default window.)
  std::vector<TrackWindow> windows = track_windows(grid, track_windowing(test_device(), grid));
  LinkSettings link;
  std::size_t lag = 0;  //!< windows that overlap one
  explicit Fixture(KnownDevice d = test_device()) : device(std::move(d)) {
    const TrackWindowing w = track_windowing(test_device(), grid);
    lag = (w.length + w.hop - 1) / w.hop;
    link.hold_silent = true;
    link.min_sightings = 4;
    link.drift_per_window = 0.5 * 0.3 * 5e-6 / 1e-3;
  }

  //! A free ringing of stiffness k born in window `first` with initial amplitude `a0` at the
  //! burst's estimated time (burst_event), heard in `count` consecutive windows: each line's
  //! amplitude at its window's start a0 e^{-gamma (start - t)}, its SNR 200 e^{-gamma (start -
  //! t)}, its frequency error 1 kHz.
  Track ringing(double k, std::size_t first, std::size_t count, double a0) const {
    const double t = burst_event(TrackEventKind::onset, first, windows, 0).time_s;
    Track track;
    for (std::size_t w = first; w < first + count; ++w) {
      const double decay = std::exp(-device.damping_rate_per_s() * std::max(0.0, windows[w].start_s - t));
      WindowLine l;
      l.frequency_hz = frequency_at(device, k);
      l.frequency_se_hz = 1e3;
      l.amplitude_v = std::abs(a0) * decay;  // (a line's amplitude is a magnitude)
      l.snr = 200.0 * decay;
      l.stiffness_n_per_m = k;
      l.detected = true;
      track.sightings.push_back({w, l});
    }
    return track;
  }
  //! A 60 N/m asperity heard from the record's start for 20 windows, then silent (held).
  Track held() const { return ringing(60.0, 0, 20, onset_ringing_v(device, 60.0)); }
};

// Heard as loud as a release on a held track's line: that track's release, not an onset.
TEST(TrackBirths, AReleaseLoudLineOnAHeldTrackIsItsRelease) {
  Fixture f;
  std::vector<Track> tracks{f.held(), f.ringing(60.0, 80, 20, release_ringing_v(f.device, 60.0))};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_TRUE(tracks[0].released);
  EXPECT_EQ(tracks[0].sightings[tracks[0].release_sighting].window, 80u);
}

// As loud as an onset, far from any held line and ringing ~100 us: an onset, kept.
TEST(TrackBirths, AnOnsetLoudLineIsAnOnset) {
  Fixture f;
  std::vector<Track> tracks{f.held(), f.ringing(100.0, 80, 20, onset_ringing_v(f.device, 100.0))};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[1].birth, TrackBirth::onset);
  EXPECT_FALSE(tracks[1].released);
}

// A tenth of an onset's ringing on the held line: the held track re-heard (no event), and far
// from it, late: a line no event explains (not held).
TEST(TrackBirths, AWeakLineIsNoOnset) {
  Fixture f;
  std::vector<Track> tracks{f.held(), f.ringing(60.0, 80, 20, 0.1 * onset_ringing_v(f.device, 60.0)),
                            f.ringing(120.0, 90, 20, 0.1 * onset_ringing_v(f.device, 120.0))};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_FALSE(tracks[0].released);
  EXPECT_TRUE(tracks[0].step_sightings.empty());
  EXPECT_EQ(tracks[0].sightings.back().window, 99u);
  EXPECT_EQ(tracks[1].birth, TrackBirth::unexplained);
}

// 60 -> 62 N/m heard 55 us after the held line's last window (beyond the gate with the wear
// drift, within a step's reach), ringing as that step does: a step of the held track. The same
// line ringing at a fifth of that (below half the weakest the step can ring, its stiffness
// before worn by up to w_max since) is too weak for the jump it claims: no step of it.
TEST(TrackBirths, ALineRingingAsTheJumpPredictsIsAStep) {
  Fixture f;
  const double step_v = step_ringing_v(f.device, 60.0, 62.0);
  std::vector<Track> tracks{f.held(), f.ringing(62.0, 30, 20, step_v)};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 1u);
  ASSERT_EQ(tracks[0].step_sightings.size(), 1u);
  EXPECT_EQ(tracks[0].sightings[tracks[0].step_sightings[0]].window, 30u);

  std::vector<Track> weaker{f.held(), f.ringing(62.0, 30, 20, 0.2 * step_v)};
  classify_track_births(f.device, weaker, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(weaker.size(), 2u);
  EXPECT_TRUE(weaker[0].step_sightings.empty());
  EXPECT_EQ(weaker[1].birth, TrackBirth::unexplained);
}

// An onset in the record's last 25 us (the probe's late.toml, issue 26 F6: 90 N/m at 975 us of
// 1 ms), heard as loud as an onset to the record's end: an onset, though a free ringing of its
// level rings ~90 us (half of it was asked, more than the record has left: unexplained before).
TEST(TrackBirths, AnOnsetHeardToTheRecordsEndIsAnOnset) {
  Fixture f;
  const std::size_t last = f.windows.size() - 1, first = last - 4;
  std::vector<Track> tracks{f.held(), f.ringing(90.0, first, last - first + 1, onset_ringing_v(f.device, 90.0))};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[1].birth, TrackBirth::onset);
}

// A negative charge density (the probe's dev10_neg.toml, issue 26 F7) makes R sigma w negative,
// not the lines' amplitudes: a line ringing as a 60 -> 62 N/m step predicts is still a step of
// the held track, and a release-loud line on it still its release (before: every prediction
// negative, and no step ever fitted).
TEST(TrackBirths, ANegativeChargeDensityJudgesByMagnitude) {
  Fixture f(test_device("-80e-6"));
  std::vector<Track> tracks{f.held(), f.ringing(62.0, 30, 20, step_ringing_v(f.device, 60.0, 62.0)),
                            f.ringing(62.0, 80, 20, release_ringing_v(f.device, 62.0))};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 1u);
  ASSERT_EQ(tracks[0].step_sightings.size(), 1u);
  EXPECT_EQ(tracks[0].sightings[tracks[0].step_sightings[0]].window, 30u);
  EXPECT_TRUE(tracks[0].released);
  EXPECT_EQ(tracks[0].sightings[tracks[0].release_sighting].window, 80u);
}

// An undamped device (c = 0, the probe's dev10_c0.toml, issue 26 F8): a free ringing never
// decays, so an onset-loud line heard from its birth to the record's end is an onset, even one
// heard at the threshold (ln(1) / gamma was 0 / 0: unexplained before).
TEST(TrackBirths, AnUndampedOnsetHeardToTheEndIsAnOnset) {
  Fixture f(test_device("80e-6", "0"));
  const std::size_t first = 80, count = f.windows.size() - first;
  Track born = f.ringing(100.0, first, count, onset_ringing_v(f.device, 100.0));
  for (TrackSighting& s : born.sightings) s.line.snr = 5.0;
  std::vector<Track> tracks{f.held(), born};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[1].birth, TrackBirth::onset);
}

// The probe's sparse record (issue 26, F1): the window that straddles a release reads the
// held line 3.9 % low and is linked to the held track as its last sighting; the release's
// ringing is heard from the next window on. It is that track's release (the straddling
// sighting dropped), not an asperity in contact since before the record and never heard.
TEST(TrackBirths, AReleaseAfterAStraddlingSightingIsTheHeldTracksRelease) {
  Fixture f;
  Track held = f.held();
  Track straddle = f.ringing(60.0, 80 - f.lag + 1, 1, 0.5 * release_ringing_v(f.device, 60.0));
  straddle.sightings[0].line.frequency_hz *= 0.961;
  held.sightings.push_back(straddle.sightings[0]);
  std::vector<Track> tracks{held, f.ringing(60.0, 80, 20, release_ringing_v(f.device, 60.0))};
  classify_track_births(f.device, tracks, f.windows, f.link, 0.3, 5.0, f.lag);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_NE(tracks[0].birth, TrackBirth::before_record);
  EXPECT_TRUE(tracks[0].released);
  EXPECT_EQ(tracks[0].sightings[tracks[0].release_sighting].window, 80u);
  EXPECT_EQ(tracks[0].sightings[tracks[0].release_sighting - 1].window, 19u);
}

}  // namespace
}  // namespace stengmc
