// Counter-based random numbers for the simulator: every draw is a pure function of
// (seed, stream, indices), so a packet's noise does not depend on which packets were
// simulated before it, in which order, or on which thread, and a run is byte-identical
// for the same seed on any platform (no std:: distributions, whose algorithms the
// standard leaves to the library).
//
// Steps: mix the key words with the SplitMix64 finaliser (Steele, Lea, Flood 2014), take 53
// bits for a uniform in [0, 1) and two 32-bit halves for a Box-Muller normal (or pair).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace flat2d::hal::sim {

inline std::uint64_t MixBits(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

// A well-mixed 64-bit value for a key of up to four words.
inline std::uint64_t HashKey(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0,
                             std::uint64_t c = 0) {
  return MixBits(MixBits(MixBits(MixBits(seed) ^ a) ^ b) ^ c);
}

// Uniform in [0, 1) from the top 53 bits.
inline double UniformFromBits(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

// Standard normal (Box-Muller) from the two 32-bit halves; |value| < 6.7.
inline double NormalFromBits(std::uint64_t bits) {
  const double u1 = (static_cast<double>(bits >> 32) + 1.0) * 0x1.0p-32;  // (0, 1]
  const double u2 = static_cast<double>(bits & 0xFFFFFFFFULL) * 0x1.0p-32;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// Two independent standard normals (both Box-Muller outputs) from one draw: half the cost.
inline std::array<double, 2> NormalPairFromBits(std::uint64_t bits) {
  const double u1 = (static_cast<double>(bits >> 32) + 1.0) * 0x1.0p-32;  // (0, 1]
  const double angle = 2.0 * std::numbers::pi * static_cast<double>(bits & 0xFFFFFFFFULL) * 0x1.0p-32;
  const double radius = std::sqrt(-2.0 * std::log(u1));
  return {radius * std::cos(angle), radius * std::sin(angle)};
}

}  // namespace flat2d::hal::sim
