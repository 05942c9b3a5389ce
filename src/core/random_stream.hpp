#pragma once
//! Named, per-realisation random streams (MODEL.md §5, STYLE.md "Numerics").
//!
//! Every stream is a pure function of (seed, realisation, kind, index): no shared state,
//! no dependence on thread id or call order, so realisation r drawn alone is bit-identical
//! to realisation r drawn inside a batch, whatever the number of threads or processes.
//! Kinds carry fixed numeric tags, so adding a kind never shifts another kind's stream.
//!
//! Engine: boost::random::mt19937_64, whose output is fixed by its specification.
//! Seeding: the 4-tuple is hashed with SplitMix64's finaliser (Steele, Lea & Flood 2014,
//! "Fast splittable pseudorandom number generators", OOPSLA), and the whole 312-word
//! Mersenne-Twister state is filled from a SplitMix64 sequence started at that hash
//! (the seeding Vigna recommends for large-state engines), so nearby tuples give
//! unrelated states. Draw variates with Boost.Random distributions, never std:: ones:
//! the std:: algorithms differ between standard libraries, Boost's are fixed.
#include <boost/random/mersenne_twister.hpp>
#include <cstdint>
#include <string_view>

namespace stengmc {

//! The engine every stream uses.
using RandomEngine = boost::random::mt19937_64;

//! What a stream is for. The numeric tags are part of the file format of every result:
//! never renumber; give a new kind the next free number.
enum class StreamKind : std::uint64_t {
  heights = 1,      //!< asperity heights
  stiffnesses = 2,  //!< asperity stiffnesses
  positions = 3,    //!< spot positions on the nominal area
  phases = 4,       //!< drive phases
  noise = 5,        //!< measurement / signal noise
  count = 6,        //!< the (Poisson) number of asperities
  bootstrap = 7,    //!< bootstrap resampling of ensemble statistics (stats/ensemble_statistics)
  draws = 8,        //!< per-realisation parameter draws of an ensemble ([[ensemble.draw]]; index = the draw)
  onsets = 9,       //!< Model 2 contact onsets of a random surface's asperities ([onset])
  counterface = 10, //!< the counterface's friction modulation eps_i(t) ([counterface]; index = the asperity)
  lifetimes = 11,   //!< Model 2 contact lifetimes (release - onset) of a random surface's asperities ([lifetime])
  wear = 12,        //!< Model 2 wear rates of a random surface's asperities ([wear])
  steps = 13,       //!< Model 2 stiffness steps of a random surface's asperities ([steps])
};

//! The kind's name, for messages and file attributes ("heights").
std::string_view to_string(StreamKind kind);

//! SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
std::uint64_t splitmix64_mix(std::uint64_t x);

//! The 64-bit key of a stream: a hash of the tuple (different for every tuple in practice).
std::uint64_t stream_key(std::uint64_t seed, std::uint64_t realisation, StreamKind kind, std::uint64_t index = 0);

//! A fresh generator for the stream (seed, realisation, kind, index).
//! @param index a sub-stream within the kind (e.g. an asperity id); 0 when unused.
RandomEngine random_stream(std::uint64_t seed, std::uint64_t realisation, StreamKind kind, std::uint64_t index = 0);

}  // namespace stengmc
