#pragma once
// Whether a spectral line moves along the record: a resonance whose frequency drifts (a MEMS
// gyro's drive or structural mode follows its temperature) or whose power grows as the sensor warms
// up. Neither the resonance nor the harmonic candidate can model it (both are stationary), and
// what it leaves is scattered OAVAR and PSD residuals near the line's period; this says why
// (docs/theory.md §6.4).
//
// The record is cut into kLineDriftBlocks consecutive blocks. In each, the Welch PSD (Hann,
// segments of the largest power of two up to a quarter of the block, 50 % overlap) gives the line's
// centroid (the power-weighted mean frequency of the bins above the local floor within W of the
// centroid, W = max(3 half-widths, 4 bins), re-centred twice from the line's frequency and kept
// within 2W of it; the floor is the median of the bins 2W to 3W from the line on both sides)
// and its power (the bins' excess over the floor times the bin width). A straight line fitted to
// each against the block index: its slope over its standard error from the scatter about the
// line is Student's t on kLineDriftBlocks - 2 degrees of freedom for a stationary line. On 1200
// records of the independent generator's stationary oscillator in a MEMS gyro's noise (4e5
// samples at 100 Hz; lines at 2 and 20 Hz, dampings 0.005-0.05, line rms 1e-3 to 4.5e-3 rad/s
// over 7.5e-3 rad/s of white noise per sample) both statistics had the spread of t_18 (sd
// 0.99-1.11) and the largest |t| was 3.61.
#include <optional>
#include <span>

namespace allanlab::experiments {

inline constexpr int kLineDriftBlocks = 20;
// |t| a drift must reach to be reported: P(|t_18| > 5) = 9e-5.
inline constexpr double kLineDriftT = 5.0;

// A straight line fitted to one quantity against the block index.
struct LineTrend {
  double first = 0.0, last = 0.0;  // at the first and the last block's centre
  double t = 0.0;                  // the slope over its standard error
};

struct LineDrift {
  double block_s = 0.0;    // length of each block
  LineTrend frequency_hz;  // the line's centroid
  LineTrend power;         // the line's power [(rad/s)^2]
  bool FrequencyDrifts() const;  // |frequency_hz.t| >= kLineDriftT
  bool PowerDrifts() const;      // |power.t| >= kLineDriftT
};

// The line near `frequency_hz` (half-power half-width `halfwidth_hz`) in the record `rate`
// (sample period tau0_s). nullopt when the record is too short for kLineDriftBlocks blocks of
// 1024 samples, the band or its floor leaves (0, Nyquist), or some block shows no power above
// its floor there.
std::optional<LineDrift> MeasureLineDrift(std::span<const double> rate, double tau0_s, double frequency_hz,
                                          double halfwidth_hz);

}  // namespace allanlab::experiments
