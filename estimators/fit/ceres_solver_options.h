#pragma once
// The one Ceres solver set-up of the fits (fit_avar_model.cc's log-WLS solve, parametric_fit.cc's
// pilot and final stages): dense QR (a few parameters, tens of taus), silent, and the stopping
// tolerances of the problem's kind. The log-WLS sum model in c^2 alone is cheap and its cost is
// not convex in c^2, so it is solved to near machine precision (a looser stop left nested fits
// looking better than the full one); the parametric stages evaluate an exact band-limited AVAR per
// step and stop at relative changes of 1e-12 in the cost.
#include <ceres/ceres.h>

namespace allanlab::estimators {

enum class SolveKind { kLinearTerms, kParametric };

inline ceres::Solver::Options FitSolverOptions(SolveKind kind, int max_iterations) {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.max_num_iterations = max_iterations;
  o.logging_type = ceres::SILENT;
  const bool linear = kind == SolveKind::kLinearTerms;
  o.function_tolerance = linear ? 1e-15 : 1e-12;
  o.gradient_tolerance = linear ? 1e-16 : 1e-14;
  o.parameter_tolerance = linear ? 1e-13 : 1e-10;
  return o;
}

}  // namespace allanlab::estimators
