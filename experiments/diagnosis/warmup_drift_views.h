#pragma once
// The views of a Gaussian model plus one warm-up drift (sim::ExponentialDrift), from theory as a
// Gaussian model's are (gaussian_views.h), in place of a Monte Carlo envelope (docs/theory.md
// §6.1 "A warm-up drift").
//
// On the output samples the drift is p_k = a' rho^k, rho = e^{-tau0 / tau_w}
// (sim::ExponentialDrift::OutputAmplitude). A view's quadratic statistic
// S = (1 / (K T)) sum_{i<T} d_i^2, d_i the n-th difference at step m of the phase Y (the running
// sum of the rate; Allan: n = 2, K = 2 m^2; Hadamard: n = 3, K = 6 m^2), takes the noise g and the
// drift p as S(g) + S(p) + (2 / (K T)) sum_i d_i(p) d_i(g):
//   * d_i(p) = D rho^i with D = a' (1 - rho^m)^n / (1 - rho) up to sign, so
//     S(p) = D^2 (1 - rho^{2T}) / ((1 - rho^2) K T) exactly;
//   * the cross term has mean 0 and variance
//     (4 D^2 / (K T)^2) sum_{|h|<T} C(h) rho^|h| (1 - rho^{2(T-|h|)}) / (1 - rho^2),
//     C(h) = Cov(d_i(g), d_{i+h}(g)) = -1/2 sum_{|j|<=n} (-1)^j binom(2n, n + j) V(|h + j m|), V
//     the phase variogram; it is uncorrelated with S(g) (a Gaussian's odd moments vanish), so
//     the variances add: E = E_g + S(p), Var = Var_g + the cross term's.
// Hence each hadamard point's mean and EDF 2 E^2 / Var, and each half's and window's: the halves
// view then reads ln F(nu_1, nu_2) about ln(E_1 / E_2), the dynamic view the range of unequal
// chi-squares (gap.h). A PSD band adds the drift's own Welch value P to its mean and, its bins
// being noncentral chi-squares, has EDF nu (E + P)^2 / (E^2 + 2 E P). The kurtosis of the block
// increments G_i + P_i (P the drift's, centred; s^2 = Var G_i = 4 V(m) - V(2m)) moves by
// (mu4_P - 3 v_P^2) / (s^2 + v_P)^2, and its sd by the ratio of the delta-method sds with and
// without P (the increments taken as independent there), both applied to the Gaussian law at
// n_eff.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "estimators/exact_avar_variance.h"
#include "experiments/diagnosis/gaussian_views.h"
#include "experiments/diagnosis/record_views.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

// The drift on the output samples: a' e^{-decay k}, k = 0 .. N-1.
struct WarmupDriftPath {
  double output_amplitude_rad_per_s = 0.0;
  double decay_per_sample = 0.0;  // tau0 / tau_w
};

// The path of the model's one exponential drift, with the model less that drift in
// *gaussian_part, when that rest is Gaussian (IsGaussianModel for records of `num_samples`);
// nullopt when the model has no drift, more than one, or another term that is not Gaussian.
std::optional<WarmupDriftPath> SplitWarmupDrift(const sim::SensorModel& model, std::int64_t num_samples,
                                                sim::SensorModel* gaussian_part);

// What the drift adds to one quadratic statistic (the header's S) on a segment of the record
// whose drift starts at `amplitude_rad_per_s` (a' rho^{first sample}): its own value and the
// variance of the cross term, both (rad/s)^4 and (rad/s)^2 as S is. `order` n (2: Allan, 3:
// Hadamard); T = `differences`. With an empty variogram, the own value alone. Precondition:
// variogram.size() > T - 1 + n m otherwise.
struct DriftShift {
  double own = 0.0;
  double cross_variance = 0.0;
};
DriftShift QuadraticStatisticShift(std::span<const long double> variogram, int order, std::int64_t m,
                                   std::int64_t differences, double amplitude_rad_per_s, double decay_per_sample);

// The cross term's variance with the amplitude taken out: sum_{|h|<T} C(h) rho^|h|
// (1 - rho^{2(T-|h|)}) / (1 - rho^2) (header). It depends on a segment only through T, so segments
// of one length (the two halves, the dynamic view's windows) share it. Preconditions as above.
// Its T values C(h) are formed once and kept for its two passes when T <= keep_up_to (16 bytes
// each: 16 MB at the default), else formed in each pass, as a 1e7-sample record's 160 MB would
// be too much to add; the same bits either way.
inline constexpr std::int64_t kKeptDifferences = std::int64_t{1} << 20;
long double DriftCrossSum(std::span<const long double> variogram, int order, std::int64_t m,
                          std::int64_t differences, double decay_per_sample,
                          std::int64_t keep_up_to = kKeptDifferences);
// QuadraticStatisticShift from that sum (the own value alone when cross_sum is null): the same bits.
DriftShift DriftShiftFromCrossSum(const long double* cross_sum, int order, std::int64_t m, std::int64_t differences,
                                  double amplitude_rad_per_s, double decay_per_sample);

// The sample excess kurtosis (m4 / m2^2 - 3) of n independent values u_i + Z_i, Z standard normal
// and u centred (the drift's increments in units of the noise's sd): its shift from the Gaussian
// value and its variance, by the delta method; 0 and 24/n with u = 0.
struct KurtosisMoments {
  double shift = 0.0, variance = 0.0;
};
KurtosisMoments ShiftedKurtosis(std::span<const double> u);

// The Gaussian part's moments that GaussianViewTheory was built from, per layout point.
struct GaussianPartMoments {
  std::vector<estimators::AvarMoments> hadamard, halves, dynamic;  // halves: N/2; dynamic: N/8
};

// The drift's share added to the Gaussian part's theory `t` (gaussian_views.h), in place.
void AddWarmupDrift(const WarmupDriftPath& drift, const ViewLayout& layout, std::span<const long double> variogram,
                    const GaussianPartMoments& moments, GaussianViewTheory* t);

}  // namespace allanlab::experiments
