#pragma once
// The Welch PSD estimate through which the diagnosis reads a record's spectrum (the psd view,
// the resonance's start, the moving line's blocks): Hann segments of n samples with 50 % overlap,
// each less its own mean, their periodograms averaged.
#include <cstddef>
#include <span>
#include <vector>

namespace allanlab::experiments {

// One-sided density [(rad/s)^2/Hz] at bins b = 0 .. n/2, frequency b / (n tau0): 2 tau0 |X_b|^2 /
// sum(w^2), averaged over the segments that fit in `y`. Empty when none does. Precondition: n a
// power of two, n >= 4.
std::vector<double> WelchPsd(std::span<const double> y, std::size_t n, double tau0_s);

// How many segments of n samples WelchPsd averages over `length` samples (0 when none fits).
inline std::size_t WelchSegments(std::size_t length, std::size_t n) {
  return length < n ? 0 : (length - n) / (n / 2) + 1;
}

}  // namespace allanlab::experiments
