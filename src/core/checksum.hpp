#pragma once
//! The one checksum stengmc writes into its files: 64-bit FNV-1a. Journals and shard files
//! frame each record with it (ensemble/journal.hpp), calibration banks carry it for each
//! table (io/calibration_bank_file.hpp), and identities hash what they depend on with it.
//! Not a cryptographic hash: it detects damage (a flipped byte, a torn write), not forgery.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace stengmc {

//! 64-bit FNV-1a over bytes (Fowler, Noll & Vo; offset basis 0xcbf29ce484222325, prime
//! 0x100000001b3). Chainable: pass the previous hash as `basis`.
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t basis = 0xcbf29ce484222325ULL);

//! FNV-1a of a table of numbers as a file stores them: each value's IEEE-754 bit pattern as
//! a little-endian u64 (the journal's encoding of a double), so it is the same on every
//! machine and a value that changes by one bit changes it.
std::uint64_t fnv1a64_of_values(std::span<const double> values);

//! `value` as 16 lower-case hex digits (how files and messages show a checksum).
std::string checksum_text(std::uint64_t value);

}  // namespace stengmc
