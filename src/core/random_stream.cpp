#include "core/random_stream.hpp"

#include <array>

namespace stengmc {

namespace {
// Golden-ratio increment of SplitMix64 (Steele, Lea & Flood 2014).
constexpr std::uint64_t GOLDEN_GAMMA = 0x9E3779B97F4A7C15ULL;
}  // namespace

std::string_view to_string(StreamKind kind) {
  switch (kind) {
    case StreamKind::heights: return "heights";
    case StreamKind::stiffnesses: return "stiffnesses";
    case StreamKind::positions: return "positions";
    case StreamKind::phases: return "phases";
    case StreamKind::noise: return "noise";
    case StreamKind::count: return "count";
    case StreamKind::bootstrap: return "bootstrap";
    case StreamKind::draws: return "draws";
    case StreamKind::onsets: return "onsets";
    case StreamKind::counterface: return "counterface";
    case StreamKind::lifetimes: return "lifetimes";
    case StreamKind::wear: return "wear";
    case StreamKind::steps: return "steps";
  }
  return "unknown";
}

std::uint64_t splitmix64_mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

std::uint64_t stream_key(std::uint64_t seed, std::uint64_t realisation, StreamKind kind, std::uint64_t index) {
  // Absorb one field at a time through the bijective mix, so the key depends on every
  // field and on their order (a sponge-like chain; swapping realisation and index
  // gives a different key).
  std::uint64_t h = splitmix64_mix(seed + GOLDEN_GAMMA);
  h = splitmix64_mix(h ^ splitmix64_mix(realisation + 1 * GOLDEN_GAMMA));
  h = splitmix64_mix(h ^ splitmix64_mix(static_cast<std::uint64_t>(kind) + 2 * GOLDEN_GAMMA));
  h = splitmix64_mix(h ^ splitmix64_mix(index + 3 * GOLDEN_GAMMA));
  return h;
}

RandomEngine random_stream(std::uint64_t seed, std::uint64_t realisation, StreamKind kind, std::uint64_t index) {
  // Fill the full state from a SplitMix64 sequence rather than the engine's own 64-bit
  // seeding, which would leave only 2^64 reachable states and correlate nearby seeds
  // through its linear initialiser.
  // Boost's iterator seeding reads 32-bit words, low half first, two per state word.
  std::array<std::uint32_t, 2 * RandomEngine::state_size> state{};
  std::uint64_t s = stream_key(seed, realisation, kind, index);
  for (std::size_t i = 0; i < RandomEngine::state_size; ++i) {
    s += GOLDEN_GAMMA;
    const std::uint64_t word = splitmix64_mix(s);
    state[2 * i] = static_cast<std::uint32_t>(word);
    state[2 * i + 1] = static_cast<std::uint32_t>(word >> 32);
  }
  RandomEngine engine;
  auto first = state.begin();
  engine.seed(first, state.end());
  return engine;
}

}  // namespace stengmc
