#pragma once
// A spectral line's width at the record's full frequency resolution 1/T, which tells a sinusoid
// (the harmonic) from a narrow resonance when both close the gap: the diagnosis's views (OAVAR,
// Welch PSD at ~1e3 times coarser resolution) see the same power at the same frequency for both,
// while the whole record's periodogram keeps a sinusoid inside its window's main lobe and spreads
// a resonance over its line width 2 zeta f0 (docs/theory.md §6.4).
#include <span>
#include <vector>

namespace allanlab::experiments {

// The Hann-windowed periodogram |X_b|^2, b = 0 .. n/2, of the record's first n samples less their
// mean, n the largest power of two <= min(size, 2^20); bin b is at b / (n tau0). Empty when
// n < 256.
std::vector<double> HannPeriodogram(std::span<const double> rate, std::size_t* n);

// Share of the line's power above the local floor that lies in the window's main lobe (+-2 bins)
// around the largest bin within W bins of `frequency_hz`, W = max(8, `line_halfwidth_hz` in
// bins) (a frequency fitted to the Allan variance may be tens of bins off): the power is summed
// over +-2W bins about that peak, and the floor is the median over 2W..4W bins either side. About 1 for a sinusoid (the Hann lobe holds all but ~1e-3 of it); for a Lorentzian line
// of half-power half-width g bins, about atan(2.5 / g) / atan(2W / g), 0.03 at g = 60.
// 0 when the record is too short or no power stands above the floor.
double LineLobeShare(std::span<const double> rate, double tau0_s, double frequency_hz, double line_halfwidth_hz);

// A line whose lobe share reaches this is a sinusoid at the record's resolution.
inline constexpr double kSinusoidLobeShare = 0.5;

}  // namespace allanlab::experiments
