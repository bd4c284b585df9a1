#include "tools/world/portable_random.h"

#include <cmath>

namespace slammtt {

uint64_t DeriveSeed(uint64_t seed, uint64_t stream) {
  // splitmix64 (Steele, Lea, Flood: "Fast splittable pseudorandom number generators", 2014)
  // applied twice, so that nearby (seed, stream) pairs give unrelated engine seeds.
  uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (stream + 1);
  for (int round = 0; round < 2; ++round) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z = z ^ (z >> 31);
  }
  return z;
}

double UniformUnit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);  // 2^-53
}

double UniformBetween(std::mt19937_64& rng, double low, double high) {
  return low + (high - low) * UniformUnit(rng);
}

double StandardNormal(std::mt19937_64& rng) {
  // 1 - U lies in (0, 1], so the logarithm is finite.
  const double u1 = 1.0 - UniformUnit(rng);
  const double u2 = UniformUnit(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

double GaussianNoise(std::mt19937_64& rng, double sigma) {
  if (sigma == 0.0) return 0.0;
  return sigma * StandardNormal(rng);
}

}  // namespace slammtt
