#pragma once
// The critical value of the profile-likelihood statistic for a parameter bounded below by 0, by
// the likelihood-ratio ordering of Feldman & Cousins (Phys. Rev. D 57, 3873, 1998), in the
// Gaussian approximation (docs/theory.md §4.8).
//
// A squared coefficient x >= 0 is estimated as z ~ N(x, sigma^2), its estimate max(z, 0). The
// statistic at a held value t is Delta(t) = chi2(t) - min over x >= 0 of chi2. With s = t / sigma
// it is (z - s)^2 for z >= 0 and s^2 - 2 z s for z < 0, so its level-`level` quantile c(s) solves
//   Phi(sqrt(c)) - Phi(-(s^2 + c) / (2 s)) = level   when s < sqrt(c),
// and is the chi2_1 quantile (1 at 68.3 %, 3.841 at 95 %) when s is that far from the boundary.
// At s = 0 it is Phi^-1(level)^2 (0.227 at 68.3 %, 2.706 at 95 %). Accepting every t with
// Delta(t) <= c(t / sigma) gives intervals that cover x at `level` whatever x is, 0 included; the
// fixed chi2_1 quantile over-covers near the boundary (all the way to 84 % at a nominal 68.3 %
// when x = 0), which is where B and K of a short record sit.
namespace allanlab::estimators {

// Preconditions: 0 < level < 1, distance_sd >= 0 (t / sigma).
double BoundedLikelihoodRatioThreshold(double level, double distance_sd);

}  // namespace allanlab::estimators
