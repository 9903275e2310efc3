#include "app/commands/fit_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/reports/allan_plot.h"
#include "common/atomic_file.h"
#include "app/reports/avar_report.h"
#include "app/reports/kalibr_yaml.h"
#include "app/reports/output_paths.h"
#include "app/reports/provenance.h"
#include "app/input/rate_units.h"
#include "app/reports/imu_report.h"
#include "app/input/record_support.h"
#include "app/reports/sensor_coefficients.h"
#include "estimators/fit/bandwidth_estimate.h"
#include "estimators/fit/fit_model.h"
#include "common/number_text.h"

namespace allanlab::app {
namespace {

constexpr const char* kCommand = "fit";
using estimators::kIdentificationMaxAverages;
using estimators::Coefficient;
using estimators::FitMethod;

using Failure = CommandFailure;

bool ParseMethod(const std::string& text, FitMethod* method) {
  if (text == "slope") *method = FitMethod::kSlope;
  else if (text == "wls") *method = FitMethod::kWls;
  else if (text == "logwls") *method = FitMethod::kLogWls;
  else if (text == "gls") *method = FitMethod::kGls;
  else return false;
  return true;
}

bool ParseTerms(const std::string& text, sim::OutputSampling bw_sampling, int bw_oversampling,
                std::vector<Coefficient>* terms,
                std::vector<std::shared_ptr<const estimators::ParametricTerm>>* extra, std::string* why) {
  std::stringstream ss(text);
  std::string id;
  while (std::getline(ss, id, ',')) {
    Coefficient c;
    if (estimators::ParseCoefficient(id, &c)) {
      terms->push_back(c);
    } else if (id == "BW" || id == "BW2") {
      extra->push_back(estimators::MakeBandLimitTerm(
          id == "BW" ? sim::LowPassKind::kFirstOrder : sim::LowPassKind::kButterworth2, bw_sampling,
          bw_oversampling));
    } else if (auto t = estimators::MakeParametricTerm(id); t && id.size() <= 3) {
      extra->push_back(std::move(t));
    } else {
      *why = "unknown term '" + id + "' (expected a comma list of Q, N, B, K, R, GM, H, RTS, BW, BW2)";
      return false;
    }
  }
  if (terms->empty() && extra->empty()) {
    *why = "no terms";
    return false;
  }
  return true;
}


// Which sigma the outputs carry, in words.
std::string UncertaintyText(const estimators::FitSummary& s, const FitCommandOptions& o) {
  std::ostringstream os;
  if (s.uncertainty == estimators::FitUncertainty::kBootstrap) {
    os << "parametric bootstrap (" << s.bootstrap_used << " of " << s.bootstrap_trials
       << " replicates of the fitted model, seed " << o.seed << ")";
  } else if (o.uncertainty == "bootstrap") {
    os << "fit covariance (the bootstrap did not run; see the fit message)";
  } else {
    os << "fit covariance";
  }
  return os.str();
}

// The fitted band-limit cutoff among the parametric estimates, or nullptr.
const estimators::ParametricEstimate* FittedBandLimit(const std::vector<estimators::ParametricEstimate>& extra) {
  for (const auto& e : extra) {
    if (e.id == "bandwidth" && e.fitted) return &e;
  }
  return nullptr;
}

// What the extended terms did on a poor fit, in one line ("" when the fit is not poor).
std::string PoorFitLine(const estimators::ModelFitSummary& m, ImuSensor sensor) {
  if (!m.poor_fit) return "";
  std::ostringstream os;
  os << "POOR FIT: chi2 " << SignificantDigits(m.poor_chi2, 4) << " on " << m.poor_dof << " dof is above its "
     << SignificantDigits(100.0 * (1.0 - estimators::kPoorFitP), 4) << " % quantile (p < " << SignificantDigits(estimators::kPoorFitP, 4)
     << "): the fitted model does not describe this record";
  if (m.best_extended < 0) {
    os << (m.extended.empty() ? "" : "; no extra term (GM, H, BW, BW2) lowers its AIC");
    return os.str();
  }
  const estimators::ExtendedFit& x = m.extended[static_cast<std::size_t>(m.best_extended)];
  os << "; best with an extra term: " << x.name << " (";
  bool first = true;
  for (const auto& e : x.extra) {
    for (std::size_t q = 0; q < e.parameters.size(); ++q) {
      const ParameterUnit u = SensorParameterUnit(sensor, e.parameters[q]);
      os << (first ? "" : ", ") << e.short_name << " " << e.parameters[q].name << " "
         << SignificantDigits(e.value_si[q] / u.si_per_unit, 4) << " " << u.unit;
      first = false;
    }
  }
  os << "), chi2 " << SignificantDigits(x.fit.gof_chi2, 4) << " on " << x.fit.dof << " dof (p = " << SignificantDigits(x.fit.gof_p_value, 4) << "): "
     << (x.fits ? std::string("that model fits and is the one reported above")
                : std::string("it does not fit either; the coefficients above are those of the closest wrong model"));
  return os.str();
}

void WriteTable(std::ostream& os, const FitCommandOptions& o, const estimators::ModelFitSummary& m,
                const estimators::BandwidthEstimate& bw, ImuSensor sensor = ImuSensor::kGyro) {
  const estimators::FitSummary& s = m.fit;
  const std::vector<estimators::ParametricEstimate>& extra = m.extra;
  os << "coefficient  value          +- sigma      95 % interval         unit            slope method\n";
  for (Coefficient c : estimators::kAllCoefficients) {
    const auto& e = s.at(c);
    if (!e.asked) continue;
    const auto& slope = s.slope.at(c);
    auto unit = [c, sensor](double si) { return SignificantDigits(SensorDatasheetValue(sensor, c, si), 4); };
    std::string value = "-", sigma, interval;
    if (e.fitted) {
      value = unit(e.value_si);
      if (e.sigma_si > 0) sigma = "+- " + unit(e.sigma_si);
      if (e.has_intervals) {
        // An upper end the profile never reached: the data bound the term from below only.
        const std::string upper = std::isfinite(e.interval95_si[1]) ? unit(e.interval95_si[1]) : "unbounded";
        interval = "[" + unit(e.interval95_si[0]) + ", " + upper + "]";
      }
    } else if (e.has_upper_limit) {
      value = "< " + unit(e.upper_limit_si);
      interval = "(95 % upper limit)";
    }
    char line[320];
    std::snprintf(line, sizeof line, "%-12s %-14s %-13s %-21s %-15s %s\n",
                  std::string(estimators::CoefficientId(c)).c_str(), value.c_str(), sigma.c_str(),
                  interval.c_str(), std::string(SensorDatasheetUnit(sensor, c)).c_str(),
                  slope.found ? unit(slope.value_si).c_str() : "-");
    os << line;
    if (!e.note.empty()) os << "             (" << e.note << ")\n";
    if (e.fitted && e.has_intervals && e.interval95_si[0] <= 0.0 && e.value_si > 2.0 * e.sigma_si) {
      // The sigma is the curvature at the fit; the profile shows that zero is still allowed.
      os << "             (the 95 % interval reaches 0: the data do not exclude "
         << estimators::CoefficientId(c) << " = 0; +- sigma is the curvature at the fit, not a bound)\n";
    }
  }
  for (const auto& e : extra) {
    for (std::size_t q = 0; q < e.parameters.size(); ++q) {
      const auto& spec = e.parameters[q];
      const ParameterUnit u = SensorParameterUnit(sensor, spec);
      char line[256];
      std::snprintf(line, sizeof line, "%-12s %-14s %-13s %-21s %-15s %s\n", (e.short_name + " " + spec.name).c_str(),
                    e.fitted ? SignificantDigits(e.value_si[q] / u.si_per_unit, 4).c_str() : "-",
                    e.fitted ? ("+- " + SignificantDigits(e.sigma_si[q] / u.si_per_unit, 4)).c_str() : "",
                    e.fitted && q < e.interval95_si.size()
                        ? ("[" + SignificantDigits(e.interval95_si[q][0] / u.si_per_unit, 4) + ", " +
                           SignificantDigits(e.interval95_si[q][1] / u.si_per_unit, 4) + "]")
                              .c_str()
                        : "",
                    u.unit.c_str(), "-");
      os << line;
    }
    if (!e.note.empty()) os << "             (" << e.note << ")\n";
  }
  os << "uncertainty: " << UncertaintyText(s, o) << "\n";
  os << "fit: chi2 " << SignificantDigits(s.gof_chi2, 4) << " on " << s.dof << " dof (p = " << SignificantDigits(s.gof_p_value, 4) << "), "
     << s.taus_used << " taus; " << s.message << "\n";
  if (m.poor_fit) os << PoorFitLine(m, sensor) << "\n";
  if (!m.method_disagreement.empty()) {
    os << "method check: GLS and log-WLS differ by more than 3 sigma: " << m.method_disagreement
       << " (the curve departs from the model's shape; the GLS sigmas are too small)\n";
  }
  os << "taus: " << s.taus_used << " from " << SignificantDigits(s.tau_min_s, 4) << " s to " << SignificantDigits(s.tau_max_s, 4)
     << " s\n";
  if (!s.band_limit.empty()) os << "band-limit: " << s.band_limit << "\n";
  if (const auto* f = FittedBandLimit(extra)) {
    os << "bandwidth: fitted fc " << SignificantDigits(f->value_si[0], 4) << " +- " << SignificantDigits(f->sigma_si[0], 4);
    if (!f->interval95_si.empty()) {
      os << " (95 % profile range " << SignificantDigits(f->interval95_si[0][0], 4) << " to "
         << SignificantDigits(f->interval95_si[0][1], 4) << ")";
    }
    os << " Hz ("
       << (f->short_name == "BW2" ? "2nd-order Butterworth" : "first order") << "); ";
  } else {
    os << "bandwidth: ";
  }
  if (bw.found) {
    os << "inflection (ADEV peak) at " << SignificantDigits(bw.peak_tau_s, 4) << " +- " << SignificantDigits(bw.peak_tau_sigma_s, 4)
       << " s -> fc " << SignificantDigits(bw.cutoff_first_order_hz, 4) << " +- "
       << SignificantDigits(bw.cutoff_first_order_sigma_hz, 4) << " Hz (first order; time constant "
       << SignificantDigits(bw.time_constant_s, 4) << " s) or " << SignificantDigits(bw.cutoff_butterworth2_hz, 4)
       << " Hz (2nd-order Butterworth)\n";
  } else {
    os << "inflection not found (" << bw.note << ")\n";
  }
}

}  // namespace

nlohmann::ordered_json FitJson(const FitCommandOptions& o, const estimators::ModelFitSummary& m,
                               const estimators::BandwidthEstimate& bw, const Provenance& p,
                               ImuSensor sensor) {
  const estimators::FitSummary& s = m.fit;
  const std::vector<estimators::ParametricEstimate>& extra = m.extra;
  nlohmann::ordered_json j;
  j["method"] = o.method;
  const bool bootstrapped = s.uncertainty == estimators::FitUncertainty::kBootstrap;
  nlohmann::ordered_json uncertainty;
  uncertainty["method"] = bootstrapped ? "bootstrap" : "covariance";
  uncertainty["requested"] = o.uncertainty;
  if (o.uncertainty == "bootstrap") {
    uncertainty["replicates"] = s.bootstrap_trials;
    uncertainty["replicates_used"] = s.bootstrap_used;
    uncertainty["seed"] = o.seed;
  }
  j["uncertainty"] = uncertainty;
  nlohmann::ordered_json coefficients = nlohmann::ordered_json::object();
  for (Coefficient c : estimators::kAllCoefficients) {
    const auto& e = s.at(c);
    if (!e.asked) continue;
    nlohmann::ordered_json entry;
    auto unit = [c, sensor](double si) { return SensorDatasheetValue(sensor, c, si); };
    if (e.fitted || !e.has_upper_limit) {
      entry["value"] = e.fitted ? unit(e.value_si) : 0.0;
      entry["sigma"] = unit(e.sigma_si);
    } else {
      // Not determined by the data: no value, its one-sided 95 % upper limit instead.
      entry["value"] = nullptr;
      entry["sigma"] = nullptr;
      entry["upper_limit"] = unit(e.upper_limit_si);
      entry["upper_limit_level"] = 0.95;
    }
    if (e.has_intervals) {
      entry["interval_68"] = {unit(e.interval68_si[0]), unit(e.interval68_si[1])};
      entry["interval_95"] = {unit(e.interval95_si[0]), unit(e.interval95_si[1])};
    }
    if (e.has_intervals || e.has_upper_limit) entry["interval_method"] = "profile likelihood";
    if (bootstrapped && e.fitted) {
      entry["covariance_sigma"] = unit(e.covariance_sigma_si);
      entry["bootstrap_bias"] = unit(e.bootstrap_bias_si);
    }
    entry["unit"] = std::string(SensorDatasheetUnit(sensor, c));
    if (sensor == ImuSensor::kAccelerometer) entry["name"] = std::string(SensorCoefficientName(sensor, c));
    entry["fitted"] = e.fitted;
    if (!e.note.empty()) entry["note"] = e.note;
    const auto& slope = s.slope.at(c);
    if (slope.found) entry["slope_method"] = unit(slope.value_si);
    coefficients[std::string(estimators::CoefficientId(c))] = entry;
  }
  for (const auto& e : extra) {
    nlohmann::ordered_json entry;
    entry["id"] = e.id;
    entry["fitted"] = e.fitted;
    for (std::size_t q = 0; q < e.parameters.size(); ++q) {
      const auto& spec = e.parameters[q];
      const ParameterUnit u = SensorParameterUnit(sensor, spec);
      entry[spec.name] = {{"value", e.fitted ? e.value_si[q] / u.si_per_unit : 0.0},
                          {"sigma", e.fitted ? e.sigma_si[q] / u.si_per_unit : 0.0},
                          {"unit", u.unit}};
      if (e.fitted && q < e.interval95_si.size()) {
        entry[spec.name]["interval95"] = {e.interval95_si[q][0] / u.si_per_unit, e.interval95_si[q][1] / u.si_per_unit};
      }
      if (bootstrapped && e.fitted && q < e.bootstrap_bias_si.size()) {
        entry[spec.name]["covariance_sigma"] = e.covariance_sigma_si[q] / u.si_per_unit;
        entry[spec.name]["bootstrap_bias"] = e.bootstrap_bias_si[q] / u.si_per_unit;
      }
    }
    if (!e.note.empty()) entry["note"] = e.note;
    coefficients[e.short_name] = entry;
  }
  j["coefficients"] = coefficients;
  nlohmann::ordered_json bandwidth;
  bandwidth["found"] = bw.found;
  if (bw.found) {
    bandwidth["peak_tau_s"] = bw.peak_tau_s;
    bandwidth["first_order"] = {{"value", bw.cutoff_first_order_hz}, {"sigma", bw.cutoff_first_order_sigma_hz}};
    bandwidth["butterworth2"] = {{"value", bw.cutoff_butterworth2_hz}, {"sigma", bw.cutoff_butterworth2_sigma_hz}};
    bandwidth["time_constant_s"] = {{"value", bw.time_constant_s}, {"sigma", bw.time_constant_sigma_s}};
  } else {
    bandwidth["note"] = bw.note;
  }
  if (const auto* f = FittedBandLimit(extra)) {
    bandwidth["fitted"] = {{"filter", f->short_name == "BW2" ? "butterworth2" : "first_order"},
                           {"value", f->value_si[0]},
                           {"sigma", f->sigma_si[0]},
                           {"sampling", o.bw_sampling},
                           {"oversampling", o.bw_oversampling}};
    if (!f->interval95_si.empty()) bandwidth["fitted"]["interval95"] = {f->interval95_si[0][0], f->interval95_si[0][1]};
  } else {
    bandwidth["fitted"] = nullptr;
  }
  j["bandwidth_hz"] = bandwidth;
  j["fit"] = {{"chi2", s.gof_chi2},
              {"dof", s.dof},
              {"p_value", s.gof_p_value},
              {"converged", s.converged},
              {"taus_used", s.taus_used},
              {"tau_min_s", s.tau_min_s},
              {"tau_max_s", s.tau_max_s},
              {"band_limit", s.band_limit},
              {"poor_fit", m.poor_fit},
              {"poor_fit_rule", estimators::PoorFitRule()},
              {"message", s.message}};
  if (m.poor_fit) {
    nlohmann::ordered_json tried = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < m.extended.size(); ++i) {
      const estimators::ExtendedFit& x = m.extended[i];
      nlohmann::ordered_json t = {{"terms", x.name}, {"chi2", x.fit.gof_chi2}, {"dof", x.fit.dof},
                                  {"p_value", x.fit.gof_p_value}, {"fits", x.fits},
                                  {"best", static_cast<int>(i) == m.best_extended}};
      for (const auto& e : x.extra) {
        for (std::size_t q = 0; q < e.parameters.size(); ++q) {
          const ParameterUnit u = SensorParameterUnit(sensor, e.parameters[q]);
          t[e.short_name + " " + e.parameters[q].name] = {{"value", e.value_si[q] / u.si_per_unit}, {"unit", u.unit}};
        }
      }
      tried.push_back(t);
    }
    j["fit"]["extended_models"] = tried;
    j["fit"]["poor_fit_summary"] = PoorFitLine(m, sensor);
    const bool swapped = m.best_extended >= 0 && m.extended[static_cast<std::size_t>(m.best_extended)].fits;
    j["fit"]["reported_model"] =
        swapped ? "IEEE terms + " + m.extended[static_cast<std::size_t>(m.best_extended)].name : std::string("IEEE terms");
  }
  if (!m.method_disagreement.empty()) j["fit"]["method_disagreement"] = m.method_disagreement;
  j["provenance"] = ProvenanceJson(p);
  return j;
}

namespace {

AllanPlot FitPlot(const AvarReport& report, const estimators::AvarCurve& curve,
                  const estimators::FitSummary& s, const sim::SensorModel* fitted_model) {
  AllanPlot plot = AvarPlot(report);  // data with interval bars
  plot.title = "allanlab fit: " + report.record.path;
  const double unit = DeviationFactor(report);
  std::vector<double> total(curve.size(), 0.0);
  for (Coefficient c : estimators::kAllCoefficients) {
    const auto& e = s.at(c);
    if (!e.fitted) continue;
    const std::vector<double> shape = estimators::TermShape(c, curve, true);
    PlotSeries term{std::string(estimators::CoefficientId(c)) + " term", PlotStyle::kDashedLine,
                    curve.tau_s, {}};
    for (std::size_t k = 0; k < curve.size(); ++k) {
      const double v = e.value_si * e.value_si * shape[k];
      total[k] += v;
      term.y.push_back(std::sqrt(v) * unit);
    }
    plot.series.push_back(term);
  }
  if (fitted_model) {  // parametric terms: each sim term of the fitted model, and its exact total
    total = estimators::ModelAvarOnCurve(*fitted_model, curve);
    for (const sim::NoiseTerm& t : fitted_model->terms) {
      const std::string_view id = sim::TermId(t);
      if (id != sim::GaussMarkov::kId && id != sim::Harmonic::kId) continue;
      sim::SensorModel one = *fitted_model;
      one.terms = {t};
      const std::vector<double> v = estimators::ModelAvarOnCurve(one, curve);
      PlotSeries term{std::string(id) + " term", PlotStyle::kDashedLine, curve.tau_s, {}};
      for (double x : v) term.y.push_back(std::sqrt(std::max(x, 0.0)) * unit);
      plot.series.push_back(term);
    }
  }
  PlotSeries fitted{"fitted total", PlotStyle::kLine, curve.tau_s, {}};
  for (double v : total) fitted.y.push_back(std::sqrt(v) * unit);
  plot.series.push_back(fitted);
  return plot;
}

// The Kalibr keys from the fit: the estimate and its sigma, or its 95 % upper bound when the term
// is not determined (never 0: a filter would take the bias as constant); on a poor fit the 95 %
// upper ends of both and a warning (the sigmas of a wrong model mean nothing).
KalibrGyroNoise KalibrNoise(const estimators::ModelFitSummary& m, double rate_hz) {
  auto value = [&m](Coefficient c) {
    const estimators::CoefficientEstimate& e = m.fit.at(c);
    KalibrValue v;
    if (e.fitted && !m.poor_fit) {
      v.value = e.value_si;
      if (e.sigma_si > 0) v.sigma = e.sigma_si;
    } else if (e.fitted && e.has_intervals && std::isfinite(e.interval95_si[1])) {
      v.value = e.interval95_si[1];
      v.upper_bound = true;
    } else if (e.has_upper_limit) {
      v.value = e.upper_limit_si;
      v.upper_bound = true;
    } else if (e.fitted) {
      v.value = e.value_si;
    }
    return v;
  };
  KalibrGyroNoise noise;
  noise.noise_density = value(Coefficient::kN);
  noise.random_walk = value(Coefficient::kK);
  noise.update_rate_hz = rate_hz;
  if (m.poor_fit) {
    noise.warning = "poor fit (chi2 " + SignificantDigits(m.poor_chi2, 4) + " on " + std::to_string(m.poor_dof) +
                    " dof): the fitted model does not describe this record; the values are 95 % upper "
                    "bounds, not estimates. Check the record (allanlab diagnose) before trusting them.";
  }
  return noise;
}

// The curve to fit: the record's, computed as `avar` does, or a published one (--curve).
int FitInput(const FitCommandOptions& o, const RecordCurveOptions& curve_options, AvarReport* report,
             std::string* why) {
  if (o.published.path.empty()) return ComputeCurveFromFile(curve_options, kCommand, report, why);
  CurveTable table;
  if (const int code = ReadCurveFromOptions(o.published, o.curve.rate_hz, &table, why); code != kExitOk) {
    return code;
  }
  *report = ReportOfCurve(o.published, table);
  for (const std::string& s : table.skipped) {
    std::cerr << "allanlab fit: warning: " << report->record.path << ": " << s << "; row not used\n";
  }
  return kExitOk;
}

// The record, and the column when several are fitted, for messages.
std::string Where(const AvarReport& report) {
  return report.record.columns.size() > 1 ? report.record.path + ": column " + report.record.column
                                          : report.record.path;
}

}  // namespace

std::optional<CommandFailure> FitAxis(const FitCommandOptions& o, const estimators::ModelFitOptions& fit,
                                      double max_tau, const AvarReport* report, FittedAxis* axis) {
  std::string why;
  int parameters = static_cast<int>(fit.terms.size());
  for (const auto& t : fit.extra) parameters += static_cast<int>(t->parameters().size());
  if (!CheckRecordSupportsFit(report->summary.num_samples, report->record.sample_clock.rate_hz(), parameters, &why)) {
    return Failure{kExitRuntimeError, Where(*report) + ": " + why};
  }
  const estimators::AvarCurve full_curve = estimators::CurveFromSummary(report->summary);
  if (full_curve.size() < 2) {
    return Failure{kExitRuntimeError, Where(*report) + ": the record gives " +
                                          std::to_string(full_curve.size()) +
                                          " usable taus (constant or too short): nothing to fit"};
  }
  axis->curve = estimators::TauRange(full_curve, o.min_tau_s, max_tau);
  const estimators::AvarCurve& curve = axis->curve;
  if (curve.size() < 2) {
    std::ostringstream os;
    os << Where(*report) << ": " << curve.size() << " of the curve's " << full_curve.size()
       << " taus (" << full_curve.tau_s.front() << " s to " << full_curve.tau_s.back()
       << " s) lie in the --min-tau/--max-tau range: nothing to fit";
    return Failure{kExitRuntimeError, os.str()};
  }
  estimators::ModelFitSummary& fitted = axis->fitted;
  if (!estimators::FitModel(fit, curve, &fitted)) {
    return Failure{kExitRuntimeError, Where(*report) + ": " + fitted.fit.message};
  }
  const estimators::FitSummary& summary = fitted.fit;
  if (!fitted.extra_terms.empty()) axis->fitted_model = estimators::FittedModel(curve, fitted);
  axis->bandwidth = estimators::EstimateBandwidth(curve);
  std::vector<FittedTermAvar> fitted_terms;
  for (Coefficient c : estimators::kAllCoefficients) {
    const auto& e = summary.at(c);
    if (!e.fitted) continue;
    FittedTermAvar& t = fitted_terms.emplace_back(FittedTermAvar{std::string(estimators::CoefficientId(c)),
                                                                 estimators::TermShape(c, curve, true)});
    for (double& v : t.avar) v *= e.value_si * e.value_si;
  }
  for (const std::string& w : WeaklySupportedTerms(curve.tau_s, curve.m, curve.num_samples, fitted_terms)) {
    std::cerr << "allanlab fit: warning: " << Where(*report) << ": " << w << std::endl;
  }
  return std::nullopt;
}

Provenance FitProvenance(const FitCommandOptions& o, const AvarReport& report, const estimators::FitSummary& summary,
                         const std::string& command_line) {
  Provenance p = MakeProvenance(kCommand, command_line);
  p.Add("input", report.record.path);
  p.Add("column", report.record.column);
  p.Add("units", report.input_units + " (" + report.record.units_source + ")");
  if (!o.published.path.empty()) p.Add("curve", DescribeCurve(o.published, report.record.sample_clock.rate_hz()));
  p.Add("sample_rate", ShortestDecimal(report.record.sample_clock.rate_hz()) + " Hz (" + report.record.rate_source + ")");
  p.Add("samples", std::to_string(report.summary.num_samples));
  p.Add("taus", o.published.path.empty() ? o.curve.taus : "the curve's own");
  p.Add("noise_identification", "per tau, from at most " + std::to_string(kIdentificationMaxAverages) +
                                    " averages (the middle of the record; EDFs of the pilot fit)");
  p.Add("method", o.method);
  p.Add("terms", o.terms + (o.select_terms ? " (with term selection)" : ""));
  p.Add("uncertainty", UncertaintyText(summary, o));
  p.Add("band_limit", o.band_limit + " (" + o.bw_sampling + " output, L = " + std::to_string(o.bw_oversampling) + ")");
  if (o.min_tau_s > 0.0 || o.max_tau_s > 0.0) {
    p.Add("tau_range", ShortestDecimal(o.min_tau_s) + " s to " +
                           (o.max_tau_s > 0.0 ? ShortestDecimal(o.max_tau_s) + " s" : std::string("end")));
  }

  return p;
}

std::optional<CommandFailure> MakeModelFitOptions(const FitCommandOptions& o, estimators::ModelFitOptions* fit_out,
                                                  double* max_tau_out) {
  std::string why;
  estimators::ModelFitOptions& fit = *fit_out;
  fit = estimators::ModelFitOptions();
  if (!ParseMethod(o.method, &fit.method)) {
    return Failure{kExitUsageError, "--method: unknown '" + o.method + "' (expected slope, wls, logwls or gls)"};
  }
  fit.terms.clear();
  if (o.band_limit == "auto") fit.band_limit = estimators::BandLimitPolicy::kAuto;
  else if (o.band_limit == "off") fit.band_limit = estimators::BandLimitPolicy::kOff;
  else return Failure{kExitUsageError, "--band-limit: unknown '" + o.band_limit + "' (expected auto or off)"};
  if (o.bw_sampling == "average") fit.bw_sampling = sim::OutputSampling::kAverage;
  else if (o.bw_sampling == "point") fit.bw_sampling = sim::OutputSampling::kPoint;
  else return Failure{kExitUsageError, "--bw-sampling: unknown '" + o.bw_sampling + "' (expected average or point)"};
  if (o.bw_oversampling < 1 || o.bw_oversampling > 256) {
    return Failure{kExitUsageError, "--bw-oversampling: must be an integer in [1, 256], got " +
                                        std::to_string(o.bw_oversampling)};
  }
  fit.bw_oversampling = o.bw_oversampling;
  if (!std::isfinite(o.min_tau_s) || o.min_tau_s < 0.0) {
    return Failure{kExitUsageError, "--min-tau: must be a finite number >= 0 s"};
  }
  if (!std::isfinite(o.max_tau_s) || o.max_tau_s < 0.0) {
    return Failure{kExitUsageError, "--max-tau: must be a finite number > 0 s (0: no limit)"};
  }
  const double max_tau = o.max_tau_s > 0.0 ? o.max_tau_s : std::numeric_limits<double>::infinity();
  if (o.min_tau_s >= max_tau) {
    return Failure{kExitUsageError, "--min-tau must be below --max-tau"};
  }
  *max_tau_out = max_tau;
  if (!ParseTerms(o.terms, fit.bw_sampling, fit.bw_oversampling, &fit.terms, &fit.extra, &why)) {
    return Failure{kExitUsageError, "--terms: " + why};
  }
  if (!fit.extra.empty() && fit.method == FitMethod::kSlope) {
    return Failure{kExitUsageError, "--terms: H, GM, RTS and BW need a fit method (gls, wls or logwls), not slope"};
  }
  fit.select_terms = o.select_terms;
  fit.try_extended_on_poor_fit = true;
  fit.cross_check_log_wls = true;
  if (o.uncertainty == "bootstrap") {
    fit.uncertainty = estimators::FitUncertainty::kBootstrap;
  } else if (o.uncertainty != "covariance") {
    return Failure{kExitUsageError, "--uncertainty: unknown '" + o.uncertainty + "' (expected covariance or bootstrap)"};
  }
  fit.bootstrap.trials = o.bootstrap_trials;
  fit.bootstrap.seed = o.seed;
  if (fit.uncertainty == estimators::FitUncertainty::kBootstrap && !fit.bootstrap.IsValid(&why)) {
    return Failure{kExitUsageError, "--bootstrap-trials: " + why};
  }
  return std::nullopt;
}

RecordCurveOptions FitCurveOptions(const FitCommandOptions& o) {
  RecordCurveOptions curve_options = o.curve;
  curve_options.estimator = "overlapping";
  // The curve's EDFs only seed the pilot fit (GLS weighs by the covariance model): identify the
  // noise type per tau from at most 2^15 averages instead of the whole record at every short tau
  // (results/benchmarks/fit.md: the CPU it spares, and that the fitted values do not move).
  curve_options.identification_max_averages = kIdentificationMaxAverages;
  return curve_options;
}

namespace {

// Several columns of one record (an IMU): a table per column, one JSON, one Kalibr YAML for the
// whole IMU and one plot with every axis (app/reports/imu_report.h).
std::optional<Failure> FitSeveral(const FitCommandOptions& o, const estimators::ModelFitOptions& fit, double max_tau,
                                  const RecordCurveOptions& curve_options, const std::string& command_line,
                                  AtomicFile* json, AtomicFile* kalibr, AtomicFile* png) {
  std::string why;
  std::vector<AvarReport> reports;
  if (const int code = ComputeCurvesFromFile(curve_options, kCommand, &reports, &why); code != kExitOk) {
    return Failure{code, why};
  }
  std::vector<FittedAxis> axes(reports.size());
  for (std::size_t k = 0; k < reports.size(); ++k) {
    if (auto failure = FitAxis(o, fit, max_tau, &reports[k], &axes[k])) return failure;
  }
  Provenance p = FitProvenance(o, reports.front(), axes.front().fitted.fit, command_line);
  p.Add("columns", DescribeColumns(reports));
  nlohmann::ordered_json columns = nlohmann::ordered_json::array();
  std::vector<KalibrAxisNoise> noise;
  std::vector<ImuFitCurve> curves;
  bool any_poor = false;
  for (std::size_t k = 0; k < reports.size(); ++k) {
    const AvarReport& r = reports[k];
    const FittedAxis& a = axes[k];
    std::cout << (k ? "\n" : "") << "# column " << r.record.column << " (" << ImuSensorName(r.sensor) << ", "
              << r.input_units << " in)\n";
    if (r.sensor == ImuSensor::kAccelerometer) std::cout << "# " << AccelerometerTermsLine() << "\n";
    WriteTable(std::cout, o, a.fitted, a.bandwidth, r.sensor);
    nlohmann::ordered_json one = FitJson(o, a.fitted, a.bandwidth, p, r.sensor);
    one.erase("provenance");
    nlohmann::ordered_json entry = {{"column", r.record.column}, {"sensor", ImuSensorName(r.sensor)},
                                    {"units", r.input_units}};
    entry.update(one);
    columns.push_back(std::move(entry));
    noise.push_back({r.record.column, r.sensor, KalibrNoise(a.fitted, r.record.sample_clock.rate_hz())});
    if (png->is_open()) {
      const AllanPlot plot = FitPlot(r, a.curve, a.fitted.fit, a.fitted_model ? &*a.fitted_model : nullptr);
      curves.push_back({&r, plot.series.front(), plot.series.back()});
    }
    any_poor |= a.fitted.poor_fit;
  }
  std::cout.flush();
  if (json->is_open()) {
    nlohmann::ordered_json j;
    j["provenance"] = ProvenanceJson(p);
    j["columns"] = std::move(columns);
    json->stream() << j.dump(2) << "\n";
  }
  if (kalibr->is_open()) kalibr->stream() << KalibrImuYaml(noise, p);
  if (png->is_open() && !RenderAllanPlots(ImuFitPlots(curves, "allanlab fit"), png, &why)) {
    return Failure{kExitRuntimeError, why};
  }
  for (AtomicFile* file : {json, kalibr, png}) {
    if (file->is_open() && !file->Commit(&why)) return Failure{kExitRuntimeError, why};
  }
  if (o.strict && any_poor) {
    std::string poor;
    for (std::size_t k = 0; k < reports.size(); ++k) {
      if (axes[k].fitted.poor_fit) poor += (poor.empty() ? "" : ", ") + reports[k].record.column;
    }
    return Failure{kExitRuntimeError, o.curve.path + ": poor fit (--strict) of column(s) " + poor};
  }
  return std::nullopt;
}

std::optional<Failure> Fit(const FitCommandOptions& o, const std::string& command_line) {
  std::string why;
  if (o.published.path.empty() == o.curve.path.empty()) {
    return Failure{kExitUsageError, "give FILE or --curve CSV (with --record-length and --rate), one of them"};
  }
  estimators::ModelFitOptions fit;
  double max_tau = 0.0;
  if (auto failure = MakeModelFitOptions(o, &fit, &max_tau)) return failure;

  std::vector<std::pair<std::string, std::string>> outputs = {
      {"FILE", o.published.path.empty() ? o.curve.path : o.published.path}};
  if (!o.json_path.empty()) outputs.emplace_back("--json", o.json_path);
  if (!o.kalibr_path.empty()) outputs.emplace_back("--kalibr", o.kalibr_path);
  if (!o.plot_path.empty()) outputs.emplace_back("--plot", o.plot_path);
  if (!CheckDistinctOutputs(outputs, &why)) return Failure{kExitUsageError, why};
  if (!o.plot_path.empty() && !FindGnuplot(&why)) return Failure{kExitRuntimeError, why};
  AtomicFile json, kalibr, png;
  if (!o.json_path.empty() && !json.Open(o.json_path, &why)) return Failure{kExitRuntimeError, why};
  if (!o.kalibr_path.empty() && !kalibr.Open(o.kalibr_path, &why)) return Failure{kExitRuntimeError, why};
  if (!o.plot_path.empty() && !png.Open(o.plot_path, &why)) return Failure{kExitRuntimeError, why};

  const RecordCurveOptions curve_options = FitCurveOptions(o);
  if (SeveralColumns(o.curve)) {
    if (!o.published.path.empty()) return Failure{kExitUsageError, "--curve is one curve: drop --columns/--imu"};
    return FitSeveral(o, fit, max_tau, curve_options, command_line, &json, &kalibr, &png);
  }
  AvarReport report;
  if (const int code = FitInput(o, curve_options, &report, &why); code != kExitOk) return Failure{code, why};
  FittedAxis axis;
  if (auto failure = FitAxis(o, fit, max_tau, &report, &axis)) return failure;
  const estimators::AvarCurve& curve = axis.curve;
  const estimators::ModelFitSummary& fitted = axis.fitted;
  const estimators::FitSummary& summary = fitted.fit;
  const std::optional<sim::SensorModel>& fitted_model = axis.fitted_model;
  const estimators::BandwidthEstimate& bandwidth = axis.bandwidth;
  const Provenance& p = report.provenance = FitProvenance(o, report, summary, command_line);

  WriteTable(std::cout, o, fitted, bandwidth);
  std::cout.flush();
  if (json.is_open()) json.stream() << FitJson(o, fitted, bandwidth, p).dump(2) << "\n";
  if (kalibr.is_open()) kalibr.stream() << KalibrImuYaml(KalibrNoise(fitted, report.record.sample_clock.rate_hz()), p);
  if (png.is_open() && !RenderAllanPlot(FitPlot(report, curve, summary, fitted_model ? &*fitted_model : nullptr), &png, &why)) {
    return Failure{kExitRuntimeError, why};
  }
  for (AtomicFile* file : {&json, &kalibr, &png}) {
    if (file->is_open() && !file->Commit(&why)) return Failure{kExitRuntimeError, why};
  }
  if (o.strict && fitted.poor_fit) {
    return Failure{kExitRuntimeError, o.curve.path + ": poor fit (--strict): chi2 " + SignificantDigits(fitted.poor_chi2, 4) +
                                          " on " + std::to_string(fitted.poor_dof) + " dof"};
  }
  return std::nullopt;
}

}  // namespace

Subcommand AddFitCommand(CLI::App* parent) {
  auto options = std::make_shared<FitCommandOptions>();
  options->curve.taus = kFitTaus;
  CLI::App* cmd = parent->add_subcommand(
      kCommand,
      "IEEE 952 coefficients (Q, N, B, K, R) of a recorded gyro with uncertainties, from its "
      "overlapping Allan curve; the slope-method reading beside each, and the bandwidth.");
  AddRecordCurveOptions(cmd, &options->curve);
  // FILE is optional here: --curve replaces it.
  cmd->get_option("FILE")->required(false);
  AddCurveOptions(cmd, &options->published);
  cmd->add_option("--method", options->method,
                  "gls (default: generalised least squares with the model covariance), wls, "
                  "logwls or slope (the graphical method, no uncertainty)")
      ->type_name("gls|wls|logwls|slope");
  cmd->add_option("--terms", options->terms, "terms to fit, a comma list of Q,N,B,K,R (default all) and parametric terms H "
                  "(harmonic Omega0, f0), GM (Gauss-Markov sigma, Tc), BW or BW2 (band-limit fc, "
                  "first order or 2nd-order Butterworth; these are always kept, the subset choice is among Q,N,B,K,R)")
      ->type_name("LIST");
  cmd->add_option("--band-limit", options->band_limit,
                  "auto (default): when the short taus show a band-limit, fit it (BW or BW2, the "
                  "lower chi2) with the other terms, and say so; off: the IEEE 952 terms only")
      ->type_name("auto|off");
  cmd->add_option("--bw-sampling", options->bw_sampling,
                  "output of the band-limit chain assumed by BW/BW2: average (default: each output "
                  "the mean of L internal samples, N stays the long-tau white level) or point")
      ->type_name("average|point");
  cmd->add_option("--bw-oversampling", options->bw_oversampling,
                  "internal rate / output rate L of the assumed chain (default 8)")
      ->type_name("L");
  cmd->add_option("--min-tau", options->min_tau_s, "fit only taus >= S seconds")->type_name("S");
  cmd->add_option("--max-tau", options->max_tau_s, "fit only taus <= S seconds")->type_name("S");
  cmd->add_flag("--strict", options->strict,
                 "exit with status 1 on a poor fit (" + estimators::PoorFitRule() + "), after writing "
                 "the outputs");
  cmd->add_flag_callback("--no-select", [options] { options->select_terms = false; },
                         "keep every requested term (default: the subset of terms with the lowest AIC "
                         "among all subsets; a term left out is reported by its 95 % upper limit)");
  cmd->add_option("--uncertainty", options->uncertainty,
                  "covariance (default: from the fit's weight matrix) or bootstrap (the spread of "
                  "refits of records simulated from the fitted model: honest where the model "
                  "covariance is not, e.g. a harmonic's amplitude; costs one simulation, curve and "
                  "fit per replicate)")
      ->type_name("covariance|bootstrap");
  cmd->add_option("--bootstrap-trials", options->bootstrap_trials,
                  "replicates of the parametric bootstrap (default 100, at least 2)")
      ->type_name("N");
  cmd->add_option("--seed", options->seed,
                  "seed of the bootstrap's simulated records (default 1; same seed => same sigmas "
                  "for any thread count)")
      ->type_name("N");
  cmd->add_option("--json", options->json_path, "also write the coefficients as JSON with provenance")
      ->type_name("OUT.json");
  cmd->add_option("--kalibr", options->kalibr_path,
                  "also write gyroscope_noise_density / gyroscope_random_walk YAML (Kalibr, VINS, "
                  "OpenVINS); with several columns (--imu) one file for the IMU, with the "
                  "accelerometer_noise_density / accelerometer_random_walk keys, each the largest "
                  "of its axes")
      ->type_name("OUT.yaml");
  cmd->add_option("--plot", options->plot_path,
                  "also draw the data with intervals, the fitted total and each term (PNG, gnuplot)")
      ->type_name("OUT.png");
  cmd->footer("Units: Q urad, N deg/sqrt(h), B deg/h, K deg/h/sqrt(h), R deg/h^2; H Omega0 deg/h, "
              "f0 Hz; GM sigma deg/h, Tc s; BW fc Hz.\nExit status: 0 ok, "
              "1 bad file or failed fit, 2 usage error.");
  return {cmd, [options](const std::string& command_line) { return RunFit(*options, command_line); }};
}

int RunFit(const FitCommandOptions& options, const std::string& command_line) {
  return RunCommand(kCommand, "", [&] { return Fit(options, command_line); });
}

}  // namespace allanlab::app
