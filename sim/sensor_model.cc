#include "sim/sensor_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>

#include "sim/band_limited_avar.h"
#include "sim/kasdin_finite_record.h"
#include "sim/section_period.h"

namespace allanlab::sim {
namespace {

template <typename T>
concept HasAutocovariance = requires(const T& t, std::span<double> r) {
  t.FillAutocovariance(1.0, r);
};
template <typename T>
concept HasFirstIndex = requires(const T& t, Engine& e, std::span<double> r) {
  t.AddTo(e, 1.0, r, std::int64_t{0});
};

// Kasdin flicker's own exact expected AVAR (zero state at the first sample), for a list of m.
std::vector<double> UnfilteredFlickerAvar(const FlickerNoise& t, std::span<const std::int64_t> ms,
                                          const RecordShape& shape) {
  const double b2 = t.bias_instability_rad_per_s * t.bias_instability_rad_per_s;
  std::vector<double> out;
  if (shape.estimator == AvarEstimatorKind::kOverlapping) {
    // O(log N) per m (kasdin_finite_record.h) instead of the record-sized direct sum.
    for (std::int64_t m : ms) out.push_back(b2 * KasdinOverlappingAvar(m, shape.num_samples));
    return out;
  }
  const std::vector<double> cumulative = CumulativeSum(KasdinCoefficients(shape.num_samples));
  for (std::int64_t m : ms) out.push_back(FiniteRecordAvar(cumulative, b2, m, 0, shape));
  return out;
}

// The band-limited Kasdin flicker's exact E[AVAR(m)] is B^2 times a sum that depends only on the
// chain, the record's shape and m (FiniteRecordAvarSum). Its set-up is O(N len(q)) and each m O(N),
// and refits and exact views ask for it at the same few shapes with many B, from several threads:
// the sums are kept per (chain, shape) and scaled, the same bits as computing them anew.
class FlickerChainSums {
 public:
  std::vector<double> Avar(const BandLimitChain& chain, double sample_period_s, std::span<const std::int64_t> ms,
                           const RecordShape& shape, double b2) {
    const Key key{static_cast<int>(chain.limit().kind), chain.limit().cutoff_hz, chain.limit().oversampling,
                  static_cast<int>(chain.limit().sampling), sample_period_s, shape.num_samples,
                  static_cast<int>(shape.estimator)};
    std::vector<std::int64_t> missing;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto it = sums_.find(key);
      for (std::int64_t m : ms) {
        if (it == sums_.end() || !it->second.contains(m)) missing.push_back(m);
      }
    }
    std::map<std::int64_t, FiniteRecordSum> computed;
    if (!missing.empty()) {
      // p = q * h: the Kasdin filter (zero state before the first output sample) followed by the
      // held-path filter.
      const std::vector<double> h = KasdinCoefficients(shape.num_samples);
      const auto& q = chain.held_response();
      std::vector<double> p(h.size(), 0.0);
      for (std::size_t i = 0; i < h.size(); ++i) {
        for (std::size_t j = 0; j < q.size() && j <= i; ++j) p[i] += q[j] * h[i - j];
      }
      const std::vector<double> cumulative = CumulativeSum(p);
      for (std::int64_t m : missing) computed[m] = FiniteRecordAvarSum(cumulative, m, 0, shape);
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!computed.empty()) {
      if (sums_.size() >= kMaxShapes && !sums_.contains(key)) sums_.clear();
      sums_[key].insert(computed.begin(), computed.end());
    }
    const auto& by_m = sums_.at(key);
    std::vector<double> out;
    out.reserve(ms.size());
    for (std::int64_t m : ms) out.push_back(ScaledFiniteRecordAvar(by_m.at(m), b2));
    return out;
  }

 private:
  static constexpr std::size_t kMaxShapes = 64;
  using Key = std::tuple<int, double, int, int, double, std::int64_t, int>;
  std::mutex mutex_;
  std::map<Key, std::map<std::int64_t, FiniteRecordSum>> sums_;
};

FlickerChainSums& SharedFlickerChainSums() {
  static FlickerChainSums sums;
  return sums;
}

// Expected AVAR of one term after the band-limit chain (docs/theory.md §2.9, generalised), at every
// averaging factor of a list (set-up work such as the flicker impulse response is done once).
struct ChainTheory {
  const BandLimitChain& chain;
  double tau0_s;
  std::span<const std::int64_t> ms;
  const RecordShape& shape;
  FlickerBandLimit flicker;

  template <typename F>
  std::vector<double> ForEachM(F&& avar_at) const {
    std::vector<double> out;
    out.reserve(ms.size());
    for (std::int64_t m : ms) out.push_back(avar_at(m));
    return out;
  }

  // The term's own exact AVAR (`own`, at each m) plus the band-limit's change
  // (band_limited_avar.h), O(len(q)) per m. The direct quadratic form over the 2m lags of the
  // chain's output autocovariance cost O(m len(q)) per m: minutes per diagnosis of a 1e6-sample
  // record with a low cutoff; tests/sim/band_limited_avar_test.cc checks the change against it.
  std::vector<double> OwnPlusChange(const NoiseTerm& term, std::vector<double> own) const {
    std::vector<double> change;
    if (!BandLimitAvarChange(term, chain, tau0_s, ms, &change)) {
      throw std::logic_error(std::string("no band-limit change for ") + std::string(TermId(term)));
    }
    for (std::size_t k = 0; k < ms.size(); ++k) own[k] += change[k];
    return own;
  }
  template <typename T>
  std::vector<double> OwnPlusChange(const T& t) const {
    return OwnPlusChange(NoiseTerm{t}, ForEachM([&](std::int64_t m) { return t.ExpectedAvar(m, tau0_s, shape); }));
  }

  std::vector<double> operator()(const WhiteRateNoise& t) const { return OwnPlusChange(t); }
  std::vector<double> operator()(const Harmonic& t) const {
    const std::complex<double> gain = chain.WidebandGain(t.frequency_hz);
    std::optional<double> phase;
    if (t.phase_rad) phase = *t.phase_rad + std::arg(gain);
    return ForEachM([&](std::int64_t m) {
      return SampledSinusoidAvar(t.amplitude_rad_per_s * std::abs(gain), t.frequency_hz, tau0_s,
                                 phase, m, shape);
    });
  }
  std::vector<double> operator()(const FlickerNoise& t) const {
    if (flicker == FlickerBandLimit::kStationaryChange) {
      return OwnPlusChange(NoiseTerm{t}, UnfilteredFlickerAvar(t, ms, shape));
    }
    const double b2 = t.bias_instability_rad_per_s * t.bias_instability_rad_per_s;
    return SharedFlickerChainSums().Avar(chain, tau0_s, ms, shape, b2);
  }
  std::vector<double> operator()(const ExponentialDrift& t) const {
    return ForEachM(
        [&](std::int64_t m) { return t.ExpectedAvar(m, tau0_s, shape, chain.held_response()); });
  }
  std::vector<double> operator()(const BiasStep& t) const {
    return ForEachM(
        [&](std::int64_t m) { return t.ExpectedAvar(m, tau0_s, shape, chain.held_response()); });
  }
  template <typename T>
  std::vector<double> operator()(const T& t) const {
    if constexpr (T::kPath == SignalPath::kDigital || std::is_same_v<T, RateRamp>) {
      // After the filter, or filter-invariant.
      return ForEachM([&](std::int64_t m) { return t.ExpectedAvar(m, tau0_s, shape); });
    } else {
      static_assert(HasAutocovariance<T>, "held stochastic terms need FillAutocovariance");
      return OwnPlusChange(t);
    }
  }
};

// Without a band-limit every term's own exact theory applies.
struct DirectTheory {
  double tau0_s;
  std::span<const std::int64_t> ms;
  const RecordShape& shape;

  std::vector<double> operator()(const FlickerNoise& t) const { return UnfilteredFlickerAvar(t, ms, shape); }
  template <typename T>
  std::vector<double> operator()(const T& t) const {
    std::vector<double> out;
    for (std::int64_t m : ms) out.push_back(t.ExpectedAvar(m, tau0_s, shape));
    return out;
  }
};

}  // namespace

bool SensorModel::IsValid(std::string* why) const {
  auto fail = [&](const std::string& msg) {
    if (why) *why = msg;
    return false;
  };
  if (!sample_clock.IsValid()) {
    return fail("sample rate must be a finite number > 0 Hz");
  }
  if (!std::isfinite(bias_rad_per_s)) return fail("bias must be finite");
  const double tau0 = sample_clock.period_s();
  for (const NoiseTerm& term : terms) {
    std::string reason;
    const bool ok = std::visit([&](const auto& t) { return t.IsValid(&reason); }, term);
    if (!ok) return fail(std::string(TermId(term)) + ": " + reason);
    if (const auto* o = std::get_if<Outliers>(&term); o && o->rate_hz * tau0 > 1.0) {
      std::ostringstream os;
      os << "outliers: rate " << o->rate_hz << " Hz exceeds the sample rate " << sample_clock.rate_hz()
         << " Hz (at most one spike per sample)";
      return fail(os.str());
    }
  }
  if (!band_limit.IsValid(sample_clock.rate_hz(), why)) return false;
  if (angle_quantizer && !angle_quantizer->IsValid(why)) return false;
  if (rate_quantizer && !rate_quantizer->IsValid(why)) return false;
  return true;
}

std::vector<double> SensorModel::Generate(std::uint64_t seed, std::uint64_t trial,
                                          std::int64_t n) const {
  return Generate(seed, trial, n, GenerateOptions{});
}

std::vector<double> SensorModel::Generate(std::uint64_t seed, std::uint64_t trial, std::int64_t n,
                                          const GenerateOptions& options) const {
  const double tau0 = sample_clock.period_s();
  auto engine_for = [&](std::size_t i) { return MakeEngine(seed, trial, i); };
  std::shared_ptr<const BandLimitChain> chain;
  if (band_limit.enabled()) chain = SharedBandLimitChain(band_limit, sample_clock.rate_hz());
  const std::int64_t burn_in = chain ? chain->burn_in_samples() : 0;
  const std::int64_t total = n + burn_in;
  // The record starts as the FFT work space of the first Kasdin flicker term (when there is one),
  // so a whole simulation holds one record-sized buffer besides the cached filter spectrum.
  // Flicker starts from its zero state at the first output sample (its burn-in samples are the
  // zero state itself), which keeps its FFT length at 2n: a power of two when n is.
  std::vector<double> out;
  std::size_t in_place_term = terms.size();
  for (std::size_t i = 0; i < terms.size(); ++i) {
    if (const auto* f = std::get_if<FlickerNoise>(&terms[i])) {
      const auto samples = static_cast<std::size_t>(n);
      const std::uint64_t stream_seed = options.flicker_cache != nullptr
                                            ? StreamSeed(options.flicker_seed, trial, kSharedFlickerStream)
                                            : StreamSeed(seed, trial, i);
      // A kept flicker record needs no FFT work space: the record alone (zeroing twice its size
      // was a tenth of an envelope record's cost).
      if (options.flicker_cache != nullptr) {
        out.assign(static_cast<std::size_t>(total), 0.0);
        if (f->WriteKept(samples, std::span<double>(out).subspan(static_cast<std::size_t>(burn_in)),
                         *options.flicker_cache, stream_seed)) {
          in_place_term = i;
          break;
        }
      }
      out.resize(std::max(FlickerNoise::WorkSize(samples), static_cast<std::size_t>(total)));
      Engine engine(stream_seed);
      f->SynthesizeInPlace(engine, samples, out, options.flicker_cache, stream_seed);
      std::copy_backward(out.begin(), out.begin() + n, out.begin() + total);
      std::fill(out.begin(), out.begin() + burn_in, 0.0);
      in_place_term = i;
      break;
    }
  }
  out.resize(static_cast<std::size_t>(total), 0.0);
  if (!chain) {
    for (std::size_t i = 0; i < terms.size(); ++i) {
      if (i == in_place_term) continue;
      Engine engine = engine_for(i);
      std::visit([&](const auto& t) { t.AddTo(engine, tau0, out); }, terms[i]);
    }
  } else {
    const int l = chain->oversampling();
    const double tau_internal = chain->internal_period_s();
    // Held terms at the output rate, starting burn_in samples before the record.
    std::vector<Engine> wide_engines;
    std::vector<std::pair<const Harmonic*, double>> harmonics;
    std::vector<const WhiteRateNoise*> whites;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      if (i == in_place_term) continue;
      Engine engine = engine_for(i);
      std::visit(
          [&](const auto& t) {
            using T = std::decay_t<decltype(t)>;
            if constexpr (T::kPath != SignalPath::kHeld) {
              if constexpr (std::is_same_v<T, Harmonic>) harmonics.emplace_back(&t, t.DrawPhase(engine));
              if constexpr (std::is_same_v<T, WhiteRateNoise>) {
                whites.push_back(&t);
                wide_engines.push_back(engine);
              }
            } else if constexpr (HasFirstIndex<T>) {
              t.AddTo(engine, tau0, out, -burn_in);
            } else if constexpr (std::is_same_v<T, FlickerNoise>) {
              t.AddTo(engine, tau0, std::span<double>(out).subspan(burn_in));  // zero state at 0
            } else {
              t.AddTo(engine, tau0, out);
            }
          },
          terms[i]);
    }
    // Internal-rate chain, in chunks so the wideband buffer stays small; filtering in place is
    // safe because output k - burn_in is written after input k has been read.
    Biquad filter = chain->MakeFilter();
    // A first-order section has a one-multiply-add recursion; running it as a full biquad would
    // triple the latency of the internal loop. Same arithmetic, so the same bits.
    struct OnePole {
      double b0, a1, y = 0.0;
      double Step(double x) { return y = b0 * x + -(a1 * y); }
    } pole{filter.b0, filter.a1};
    const bool first_order = filter.b1 == 0.0 && filter.b2 == 0.0 && filter.a2 == 0.0;
    // The box kinds (moving average, CIC): running boxes in cascade, O(1) per internal sample.
    std::vector<BoxFilter> cascade;
    const std::vector<double>& boxes = chain->box_lengths();
    for (double w : boxes) cascade.emplace_back(w);
    constexpr std::int64_t kChunk = 4096;
    const bool average = band_limit.sampling == OutputSampling::kAverage;
    const bool per_period = options.white_per_output_period && boxes.empty() && harmonics.empty();
    if (per_period) {
      double internal_variance = 0.0;
      for (const WhiteRateNoise* w : whites) {
        internal_variance += w->arw_rad_per_sqrt_s * w->arw_rad_per_sqrt_s / tau_internal;
      }
      SectionPeriod period(filter, l, internal_variance, average);
      boost::random::normal_distribution<double> normal(0.0, 1.0);
      Engine* engine = wide_engines.empty() ? nullptr : &wide_engines.front();
      std::array<double, 3> z{};
      for (std::int64_t k = 0; k < total; ++k) {
        for (int d = 0; d < period.draws(); ++d) z[static_cast<std::size_t>(d)] = normal(*engine);
        const double y = period.Step(out[k], z);
        if (k >= burn_in) out[k - burn_in] = y;
      }
    }
    std::vector<double> wide(per_period ? 0 : static_cast<std::size_t>(kChunk * l));
    for (std::int64_t k0 = 0; k0 < (per_period ? 0 : total); k0 += kChunk) {
      const std::int64_t k1 = std::min(total, k0 + kChunk);
      std::span<double> chunk(wide.data(), static_cast<std::size_t>((k1 - k0) * l));
      std::fill(chunk.begin(), chunk.end(), 0.0);
      for (std::size_t w = 0; w < whites.size(); ++w) {
        whites[w]->AddTo(wide_engines[w], tau_internal, chunk);
      }
      for (const auto& [h, phase] : harmonics) {
        h->AddSamples(phase, tau_internal, (k0 - burn_in - 1) * l + 1, chunk);
      }
      auto run = [&](auto& section) {
        for (std::int64_t k = k0; k < k1; ++k) {
          const double held = out[k];
          const double* u = chunk.data() + (k - k0) * l;
          double f = 0.0, acc = 0.0;
          for (int i = 0; i < l; ++i) {
            f = section.Step(held + u[i]);
            acc += f;
          }
          if (k >= burn_in) out[k - burn_in] = average ? acc / l : f;
        }
      };
      if (!boxes.empty()) {
        // Box by box over the whole chunk: each box is causal, so its outputs are those of the
        // sample-by-sample cascade, with its state in registers (FilterInPlace).
        for (std::int64_t k = k0; k < k1; ++k) {
          const double held = out[k];
          double* u = chunk.data() + (k - k0) * l;
          for (int i = 0; i < l; ++i) u[i] = held + u[i];
        }
        for (BoxFilter& box : cascade) box.FilterInPlace(chunk);
        for (std::int64_t k = k0; k < k1; ++k) {
          const double* f = chunk.data() + (k - k0) * l;
          double acc = 0.0;
          for (int i = 0; i < l; ++i) acc += f[i];
          if (k >= burn_in) out[k - burn_in] = average ? acc / l : f[l - 1];
        }
      } else if (first_order) {
        run(pole);
      } else {
        run(filter);
      }
    }
    out.resize(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < terms.size(); ++i) {
      std::visit(
          [&](const auto& t) {
            if constexpr (std::decay_t<decltype(t)>::kPath == SignalPath::kDigital) {
              Engine engine = engine_for(i);
              t.AddTo(engine, tau0, out);
            }
          },
          terms[i]);
    }
  }
  if (bias_rad_per_s != 0.0) {
    for (double& v : out) v += bias_rad_per_s;
  }
  if (angle_quantizer) {
    Engine engine = engine_for(kQuantizerStream);
    angle_quantizer->Apply(engine, tau0, out);
  }
  if (rate_quantizer && rate_quantizer->subtractive_dither) {
    Engine engine = engine_for(kRateQuantizerStream);
    rate_quantizer->ApplySubtractiveDither(engine, out);
  } else if (rate_quantizer) {
    double offset = 0.0;
    if (rate_quantizer->random_offset) {
      Engine engine = engine_for(kRateQuantizerStream);
      offset = boost::random::uniform_real_distribution<double>(0.0, 1.0)(engine);
    }
    rate_quantizer->Apply(out, offset);
  }
  return out;
}

double SensorModel::ExpectedAvar(std::int64_t m, const RecordShape& shape) const {
  const std::int64_t ms[] = {m};
  return ExpectedAvar(ms, shape)[0];
}

std::vector<double> SensorModel::ExpectedAvar(std::span<const std::int64_t> ms,
                                              const RecordShape& shape, FlickerBandLimit flicker) const {
  const double tau0 = sample_clock.period_s();
  std::vector<double> result(ms.size(), 0.0);
  std::shared_ptr<const BandLimitChain> chain;
  if (band_limit.enabled()) chain = SharedBandLimitChain(band_limit, sample_clock.rate_hz());
  for (const NoiseTerm& term : terms) {
    const std::vector<double> part = chain ? std::visit(ChainTheory{*chain, tau0, ms, shape, flicker}, term)
                                           : std::visit(DirectTheory{tau0, ms, shape}, term);
    for (std::size_t k = 0; k < ms.size(); ++k) result[k] += part[k];
  }
  std::int64_t max_m = 0;
  for (std::int64_t m : ms) max_m = std::max(max_m, m);
  std::vector<double> error;  // the rate quantizer's error autocovariance
  if (rate_quantizer) error = rate_quantizer->ErrorAutocovariance(SignalAutocovariance(2 * max_m));
  std::vector<double> angle_error;  // the angle quantizer's (angle domain)
  if (angle_quantizer) angle_error = AngleErrorAutocovariance(2 * max_m + 1);
  for (std::size_t k = 0; k < ms.size(); ++k) {
    if (angle_quantizer) result[k] += AngleQuantizer::AvarFromError(ms[k], tau0, angle_error);
    if (rate_quantizer) result[k] += AvarFromAutocovariance(ms[k], error);
  }
  return result;
}

std::vector<double> SensorModel::AngleErrorAutocovariance(std::int64_t lags) const {
  const double tau0 = sample_clock.period_s();
  const double lsb2 = angle_quantizer->lsb_rad * angle_quantizer->lsb_rad;
  for (std::int64_t length = std::min<std::int64_t>(lags, 256);; length = std::min(lags, 4 * length)) {
    const std::vector<double> r = SignalAutocovariance(length);
    // D(j) = Var(theta_{k+j} - theta_k) = tau0^2 sum_{a,b<j} R(a - b), by D(j+1) = D(j) +
    // tau0^2 (R(0) + 2 sum_{l=1..j} R(l)).
    std::vector<double> d(static_cast<std::size_t>(length), 0.0);
    double tail = 0.0;  // sum_{l=1..j} R(l)
    for (std::size_t j = 0; j + 1 < d.size(); ++j) {
      if (j > 0) tail += r[j];
      d[j + 1] = d[j] + tau0 * tau0 * (r[0] + 2.0 * tail);
    }
    // Stop once the last quarter has decorrelated (2 pi^2 D / q^2 > 40, the series' cut-off).
    bool decorrelated = true;
    for (std::size_t j = d.size() * 3 / 4; j < d.size() && decorrelated; ++j) {
      decorrelated = d[j] > 40.0 / (2.0 * M_PI * M_PI) * lsb2;
    }
    if (length == lags || decorrelated) {
      return angle_quantizer->ErrorAutocovariance(d, bias_rad_per_s * tau0);
    }
  }
}

std::vector<double> SensorModel::GaussianAutocovariance(std::int64_t lags) const {
  std::vector<double> total = SignalAutocovariance(lags);
  if (angle_quantizer) {
    const std::vector<double> e = AngleErrorAutocovariance(lags + 1);
    const std::vector<double> rate_error = AngleQuantizer::RateErrorAutocovariance(sample_clock.period_s(), e);
    for (std::size_t j = 0; j < std::min(total.size(), rate_error.size()); ++j) total[j] += rate_error[j];
  }
  if (rate_quantizer) {
    const std::vector<double> error = rate_quantizer->ErrorAutocovariance(total);
    for (std::size_t j = 0; j < total.size(); ++j) total[j] += error[j];
  }
  return total;
}

std::vector<double> SensorModel::SignalAutocovariance(std::int64_t lags) const {
  const double tau0 = sample_clock.period_s();
  std::vector<double> total(static_cast<std::size_t>(lags), 0.0);
  std::shared_ptr<const BandLimitChain> chain;
  if (band_limit.enabled()) chain = SharedBandLimitChain(band_limit, sample_clock.rate_hz());
  // One term's autocovariance at a time, in a buffer shared by the terms (each fill writes every
  // lag): a fresh record-sized vector per term cost a zeroing pass and its page faults each.
  std::vector<double> r;
  for (const NoiseTerm& term : terms) {
    std::visit(
        [&](const auto& t) {
          using T = std::decay_t<decltype(t)>;
          if constexpr (HasAutocovariance<T>) {
            r.resize(static_cast<std::size_t>(lags));
            if (!chain || T::kPath == SignalPath::kDigital) {
              t.FillAutocovariance(tau0, r);
            } else if constexpr (std::is_same_v<T, WhiteRateNoise>) {
              r = chain->WhiteOutputAutocovariance(
                  t.arw_rad_per_sqrt_s * t.arw_rad_per_sqrt_s / chain->internal_period_s(), lags);
            } else {
              std::vector<double> r_in(r.size() + chain->held_response().size());
              t.FillAutocovariance(tau0, r_in);
              r = chain->HeldOutputAutocovariance(r_in, lags);
            }
            for (std::size_t j = 0; j < total.size(); ++j) total[j] += r[j];
          }
        },
        term);
  }
  return total;
}

double SensorModel::AsymptoticAvar(double tau_s) const {
  const double tau0 = sample_clock.period_s();
  double sum = 0.0;
  const RecordShape long_record{std::int64_t{1} << 40, AvarEstimatorKind::kOverlapping};
  for (const NoiseTerm& term : terms) {
    sum += std::visit(
        [&](const auto& t) -> double {
          using T = std::decay_t<decltype(t)>;
          if constexpr (std::is_same_v<T, Outliers>) {
            return t.AsymptoticAvar(tau_s, tau0);
          } else if constexpr (std::is_same_v<T, ExponentialDrift> || std::is_same_v<T, BiasStep>) {
            (void)long_record;
            return 0.0;  // transients have no tau-only asymptote
          } else {
            return t.AsymptoticAvar(tau_s);
          }
        },
        term);
  }
  return sum;
}

}  // namespace allanlab::sim
