// Random numbers that give the same values with every C++ standard library.
//
// std::mt19937_64 is fully specified by the standard, but std::normal_distribution and
// std::uniform_real_distribution are not: libstdc++ and libc++ turn the same engine output into
// different numbers. The world's logs must be byte-identical for a given seed on any machine, so
// every draw goes through these functions, which use only the engine's raw 64-bit output.
#pragma once

#include <cstdint>
#include <random>

namespace slammtt {

// An independent seed for one random stream of a simulation (odometry, laser, features, one
// random walk per object, ...): splitmix64 of `seed` mixed with `stream`. Streams with different
// `stream` values are uncorrelated, so adding a consumer never changes another one's numbers.
uint64_t DeriveSeed(uint64_t seed, uint64_t stream);

// Uniform in [0, 1): the top 53 bits of one engine draw.
double UniformUnit(std::mt19937_64& rng);

// Uniform in [low, high).
double UniformBetween(std::mt19937_64& rng, double low, double high);

// Standard normal N(0, 1) by the Box-Muller transform of two UniformUnit draws. Stateless (the
// second value of the pair is discarded), so the number of engine draws per call is always two.
double StandardNormal(std::mt19937_64& rng);

// N(0, sigma^2); returns exactly 0 without drawing when sigma == 0, so a noise-free
// configuration consumes no random numbers.
double GaussianNoise(std::mt19937_64& rng, double sigma);

}  // namespace slammtt
