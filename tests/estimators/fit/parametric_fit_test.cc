// Parametric terms in the AVAR fit: the residual functor's Jacobian (analytic in the linear terms,
// central differences in the parametric ones) against Ceres' own finite differences; exact
// recovery of Gauss-Markov and harmonic parameters from noiseless expected curves.
#include "estimators/fit/parametric_fit.h"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "estimators/fit/fit_model.h"
#include "estimators/fit/model_avar_residuals.h"
#include "sim/units.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

using testing_support::LogDense;

AvarCurve ExactCurve(const sim::SensorModel& model, std::int64_t n,
                     const std::vector<std::int64_t>& ms) {
  AvarCurve c;
  c.sample_clock = model.sample_clock;
  c.num_samples = n;
  c.m = ms;
  for (std::int64_t m : ms) c.tau_s.push_back(m * c.sample_clock.period_s());
  c.avar = ModelAvarOnCurve(model, c);
  c.edf.assign(ms.size(), 0.0);
  for (std::size_t k = 0; k < ms.size(); ++k) c.edf[k] = std::max(1.0, 0.75 * n / ms[k]);
  return c;
}

sim::SensorModel Model(std::vector<sim::NoiseTerm> terms) {
  sim::SensorModel m;
  m.sample_clock = SampleClock::FromRateHz(100.0);
  m.terms = std::move(terms);
  return m;
}

TEST(ModelAvarResiduals, DerivativesMatchFiniteDifferences) {
  const std::int64_t n = 1 << 16;
  const auto ms = LogDense(n / 8, 4.0);
  const AvarCurve curve =
      ExactCurve(Model({sim::WhiteRateNoise{units::DegPerSqrtHour(0.2)}}), n, ms);
  for (const char* name : {"GM", "H", "BW2"}) {
    const auto term = MakeParametricTerm(name);
    ModelAvarFunction f;
    f.linear = 1;
    f.nonlinear = static_cast<int>(term->parameters().size());
    f.evaluate = [&](const double* u, Eigen::MatrixXd* s, Eigen::VectorXd* e) {
      std::vector<double> p;
      for (int q = 0; q < f.nonlinear; ++q) p.push_back(std::exp(u[q]));
      sim::SensorModel base = Model({});
      if (term->modifies_other_terms()) term->ApplyTo(p, &base);
      sim::SensorModel white = base;
      white.terms = {sim::WhiteRateNoise{1.0}};
      const std::vector<double> w = ModelAvarOnCurve(white, curve);
      *s = Eigen::Map<const Eigen::VectorXd>(w.data(), static_cast<Eigen::Index>(w.size()));
      e->setZero(static_cast<Eigen::Index>(w.size()));
      if (!term->modifies_other_terms()) {
        sim::SensorModel extra = base;
        term->ApplyTo(p, &extra);
        const std::vector<double> x = ModelAvarOnCurve(extra, curve);
        *e = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
      }
    };
    const auto taus = static_cast<Eigen::Index>(curve.size());
    Eigen::VectorXd target = Eigen::Map<const Eigen::VectorXd>(curve.avar.data(), taus);
    Eigen::VectorXd sqrt_w(taus);
    for (Eigen::Index k = 0; k < taus; ++k)
      sqrt_w(k) = std::sqrt(0.5 * curve.edf[k]) / curve.avar[k];
    double theta[1] = {0.8 * units::DegPerSqrtHour(0.2) * units::DegPerSqrtHour(0.2)};
    // GM: sigma 5 deg/h, Tc 2 s; H: 5 deg/h at 0.3 Hz; BW2: fc 7 Hz.
    std::vector<double> u = term->parameters().size() == 2
                                ? std::vector<double>{std::log(units::DegPerHour(5.0)),
                                                      std::log(name[0] == 'G' ? 2.0 : 0.3)}
                                : std::vector<double>{std::log(7.0)};
    for (auto domain : {ModelAvarResiduals::Domain::kLinear, ModelAvarResiduals::Domain::kLog}) {
      Eigen::VectorXd t = target;
      if (domain == ModelAvarResiduals::Domain::kLog) t = target.array().log().matrix();
      ModelAvarResiduals cost(f, domain, t, sqrt_w.asDiagonal().toDenseMatrix());
      const double* params[2] = {theta, u.data()};
      ceres::NumericDiffOptions numeric;
      numeric.relative_step_size = 1e-4;
      numeric.ridders_relative_initial_step_size = 1e-3;
      const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
      ceres::GradientChecker checker(&cost, no_manifolds, numeric);
      ceres::GradientChecker::ProbeResults results;
      // Our own central differences too (both domains): every Jacobian column within 1e-4 of
      // its largest entry.
      {
        const std::size_t nt = curve.size();
        std::vector<double> r0(nt), jt(nt), ju(nt * u.size()), rp(nt), rm(nt);
        double* jac[2] = {jt.data(), ju.data()};
        ASSERT_TRUE(cost.Evaluate(params, r0.data(), jac));
        for (std::size_t q = 0; q <= u.size(); ++q) {
          double th[1] = {theta[0]};
          std::vector<double> uu = u;
          double* x = q == 0 ? &th[0] : &uu[q - 1];
          const double h = 1e-4 * std::abs(*x), x0 = *x;
          const double* pp[2] = {th, uu.data()};
          *x = x0 + h;
          ASSERT_TRUE(cost.Evaluate(pp, rp.data(), nullptr));
          *x = x0 - h;
          ASSERT_TRUE(cost.Evaluate(pp, rm.data(), nullptr));
          double worst = 0.0, scale = 0.0;
          for (std::size_t k = 0; k < nt; ++k) {
            const double analytic = q == 0 ? jt[k] : ju[k * u.size() + q - 1];
            worst = std::max(worst, std::abs((rp[k] - rm[k]) / (2 * h) - analytic));
            scale = std::max(scale, std::abs(analytic));
          }
          EXPECT_LE(worst, 1e-4 * scale) << name << " parameter " << q;
        }
      }
      if (domain == ModelAvarResiduals::Domain::kLog) continue;  // Ridders steps leave ln's domain
      EXPECT_TRUE(checker.Probe(params, 1e-4, &results))
          << name << " domain " << static_cast<int>(domain) << ": "
          << results.error_log.substr(0, 300);
    }
  }
}

struct ExactCase {
  const char* term;
  std::vector<sim::NoiseTerm> truth;
  std::vector<double> expected_si;
};

TEST(ParametricFit, RecoversParametersFromExactCurves) {
  const std::int64_t n = 1 << 18;
  const auto ms = LogDense(n / 8, 8.0);
  const ExactCase cases[] = {
      {"GM",
       {sim::WhiteRateNoise{units::DegPerSqrtHour(0.3)},
        sim::GaussMarkov{units::DegPerHour(20.0), 10.0}},
       {units::DegPerHour(20.0), 10.0}},
      {"H",
       {sim::WhiteRateNoise{units::DegPerSqrtHour(0.3)},
        sim::Harmonic{units::DegPerHour(40.0), 0.2, std::nullopt}},
       {units::DegPerHour(40.0), 0.2}},
  };
  for (const ExactCase& c : cases) {
    const AvarCurve curve = ExactCurve(Model(c.truth), n, ms);
    for (FitMethod method : {FitMethod::kWls, FitMethod::kGls}) {
      ParametricFitOptions o;
      o.method = method;
      o.terms = {Coefficient::kN};
      o.extra = {std::shared_ptr<const ParametricTerm>(MakeParametricTerm(c.term))};
      ParametricFitSummary s;
      ASSERT_TRUE(FitAvarModelWithTerms(o, curve, &s)) << s.base.message;
      ASSERT_TRUE(s.extra[0].fitted) << c.term << ": " << s.extra[0].note;
      EXPECT_NEAR(ToDatasheetUnit(Coefficient::kN, s.base.at(Coefficient::kN).value_si), 0.3, 3e-4)
          << c.term;
      for (std::size_t q = 0; q < c.expected_si.size(); ++q) {
        EXPECT_NEAR(s.extra[0].value_si[q] / c.expected_si[q], 1.0, 1e-3)
            << c.term << " " << s.extra[0].parameters[q].name;
        EXPECT_GT(s.extra[0].sigma_si[q], 0.0);
      }
      EXPECT_LT(s.base.chi2, 1e-3) << c.term;
    }
  }
}

// What the fit says of the band-limit when the terms are listed: a listed Gauss-Markov process is
// not one (the poor-fit route on the MTi-G record had said "as listed in the terms" with none).
TEST(ParametricFit, SaysWhetherTheListedTermsFittedABandLimit) {
  const std::int64_t n = 1 << 18;
  const AvarCurve curve = ExactCurve(Model({sim::WhiteRateNoise{units::DegPerSqrtHour(0.3)},
                                            sim::GaussMarkov{units::DegPerHour(20.0), 10.0}}),
                                     n, LogDense(n / 8, 8.0));
  ModelFitOptions o;
  o.terms = {Coefficient::kN};
  o.extra = {std::shared_ptr<const ParametricTerm>(MakeParametricTerm("GM"))};
  ModelFitSummary m;
  ASSERT_TRUE(FitModel(o, curve, &m)) << m.fit.message;
  EXPECT_EQ(m.fit.band_limit, "none among the fitted terms");
  o.extra.push_back(std::shared_ptr<const ParametricTerm>(MakeParametricTerm("BW")));
  ASSERT_TRUE(FitModel(o, curve, &m)) << m.fit.message;
  ASSERT_EQ(m.extra.size(), 2u);
  ASSERT_TRUE(m.extra[1].fitted) << m.extra[1].note;
  EXPECT_EQ(m.fit.band_limit, "fitted as listed in the terms");
}

}  // namespace
}  // namespace allanlab::estimators
