#pragma once
// Deterministic random streams. Every (seed, trial, stream) triple gets its own engine, seeded
// through a splitmix64 hash, so a trial's samples never depend on which thread or MPI rank ran it.
#include <cstdint>

#include <boost/random/mersenne_twister.hpp>

namespace allanlab::sim {

using Engine = boost::random::mt19937_64;

// One step of Steele, Lea & Flood's splitmix64 (2014): a bijective 64-bit mixer.
constexpr std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// Seed word of stream `stream` of trial `trial` under master seed `seed`.
constexpr std::uint64_t StreamSeed(std::uint64_t seed, std::uint64_t trial, std::uint64_t stream) {
  return SplitMix64(SplitMix64(SplitMix64(seed) ^ trial) ^ stream);
}

inline Engine MakeEngine(std::uint64_t seed, std::uint64_t trial, std::uint64_t stream) {
  return Engine(StreamSeed(seed, trial, stream));
}

}  // namespace allanlab::sim
