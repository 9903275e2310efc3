#pragma once
// The independent generator's own random numbers: xoshiro256** (Blackman & Vigna 2018) seeded by
// splitmix64, with the Marsaglia polar method for normals. Deliberately not sim/'s engine
// (Boost mt19937_64 and Boost distributions), so that a test record never shares a random stream
// or a transformation with the code it checks. Every value is a pure function of (seed, stream,
// component) on every platform and thread count.
#include <cstdint>

namespace allanlab::independent {

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t stream, std::uint64_t component);
  std::uint64_t Next();
  double Uniform();            // [0, 1), 53 bits
  double UniformOpen();        // (0, 1)
  double Normal();             // N(0, 1)
  double Exponential();        // mean 1
  double StudentT(double dof);  // Student's t with `dof` degrees of freedom (variance dof/(dof-2))
  double Laplace();            // variance 2 (scale 1)

 private:
  std::uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace allanlab::independent
