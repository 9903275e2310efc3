#include "sim/fft.h"

#include <fftw3.h>

#include <algorithm>
#include <map>
#include <numbers>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "common/huge_pages.h"

namespace allanlab::sim {
namespace {

struct PlanPair {
  fftw_plan forward = nullptr;
  fftw_plan inverse = nullptr;
};

std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

// In-place complex plans of length `half` for the alignment of `data`: new-array execution needs
// an array aligned like the one planned on, and planning on the caller's array (FFTW_ESTIMATE
// does not touch it) avoids a record-sized scratch copy. Complex in-place plans are used instead
// of FFTW's r2c/c2r because, at 2^23 points, planning those costs about one extra record of
// memory each, and peak memory per sample is a target.
const PlanPair& PlansFor(std::size_t half, double* data) {
  static std::map<std::pair<std::size_t, int>, PlanPair> plans;  // live for the whole process
  const std::pair<std::size_t, int> key{half, fftw_alignment_of(data)};
  std::lock_guard<std::mutex> lock(PlannerMutex());
  auto it = plans.find(key);
  if (it != plans.end()) return it->second;
  PlanPair pair;
  const int size = static_cast<int>(half);
  auto* z = reinterpret_cast<fftw_complex*>(data);
  pair.forward = fftw_plan_dft_1d(size, z, z, FFTW_FORWARD, FFTW_ESTIMATE);
  pair.inverse = fftw_plan_dft_1d(size, z, z, FFTW_BACKWARD, FFTW_ESTIMATE);
  if (!pair.forward || !pair.inverse) throw std::runtime_error("FFTW could not plan a transform");
  return plans.emplace(key, pair).first->second;
}

// e^{-2 pi i k / n} for k = 0.. by rotation, re-anchored with sin/cos every 512 steps so the
// rounding drift stays near 1e-14.
class Twiddle {
 public:
  explicit Twiddle(std::size_t n) : n_(n) {}
  std::complex<double> operator()(std::size_t k) {
    if (k % 512 == 0 || k != next_) {
      current_ = std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(k) / n_);
    } else {
      current_ = MulFinite(current_, step_);
    }
    next_ = k + 1;
    return current_;
  }

 private:
  std::size_t n_;
  std::size_t next_ = 0;
  std::complex<double> current_ = 1.0;
  std::complex<double> step_ = std::polar(1.0, -2.0 * std::numbers::pi / n_);
};

// Twiddles kept up to this many (16 MB: records of a few million samples); longer transforms
// rotate as they go, so memory per sample stays as it was.
constexpr std::size_t kMaxKeptTwiddles = std::size_t{1} << 20;

}  // namespace

std::shared_ptr<const std::vector<std::complex<double>>> RealFftTwiddles(std::size_t n) {
  using Table = std::shared_ptr<const std::vector<std::complex<double>>>;
  if (n / 4 > kMaxKeptTwiddles) return nullptr;
  thread_local std::size_t last_n = 0;
  thread_local Table last;
  if (last && last_n == n) return last;
  static std::mutex mutex;
  static std::map<std::size_t, Table> tables;  // a few sizes per process
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = tables.find(n); it != tables.end()) {
      last_n = n;
      last = it->second;
      return last;
    }
  }
  auto table = std::make_shared<std::vector<std::complex<double>>>(n / 4 + 1, std::complex<double>(1.0, 0.0));
  Twiddle twiddle(n);
  for (std::size_t k = 1; k <= n / 4; ++k) (*table)[k] = twiddle(k);
  const std::lock_guard<std::mutex> lock(mutex);
  last = tables.emplace(n, std::move(table)).first->second;
  last_n = n;
  return last;
}

FftBuffer::FftBuffer(std::size_t size) : size_(size) {
  data_ = static_cast<double*>(fftw_malloc(sizeof(double) * size));
  if (!data_) throw std::bad_alloc();
  // A record-sized transform buffer is written once per use (app/large_allocations.cc: the page
  // faults of such blocks were a quarter of diagnose's CPU on 1e7 samples).
  AdviseHugePages(data_, sizeof(double) * size);
}
FftBuffer::~FftBuffer() { fftw_free(data_); }
FftBuffer::FftBuffer(FftBuffer&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}
FftBuffer& FftBuffer::operator=(FftBuffer&& other) noexcept {
  std::swap(data_, other.data_);
  std::swap(size_, other.size_);
  return *this;
}

std::size_t GoodFftSize(std::size_t n) {
  for (std::size_t candidate = std::max<std::size_t>(n, 1);; ++candidate) {
    std::size_t r = candidate;
    for (std::size_t p : {2, 3, 5, 7}) {
      while (r % p == 0) r /= p;
    }
    if (r == 1) return candidate;
  }
}

// Real transform of even length n through one complex transform of length n/2 of the packed
// samples z_k = x_{2k} + i x_{2k+1}, then the split X_k = E_k + W^k O_k, X_{n/2-k} =
// conj(E_k - W^k O_k) with E_k = (Z_k + conj Z_{n/2-k})/2, O_k = (Z_k - conj Z_{n/2-k})/(2i).
void ForwardRealFft(std::size_t n, double* data) {
  const std::size_t half = n / 2;
  fftw_execute_dft(PlansFor(half, data).forward, reinterpret_cast<fftw_complex*>(data),
                   reinterpret_cast<fftw_complex*>(data));
  auto* x = reinterpret_cast<std::complex<double>*>(data);
  const std::complex<double> z0 = x[0];
  x[0] = z0.real() + z0.imag();
  x[half] = z0.real() - z0.imag();
  const auto twiddles = RealFftTwiddles(n);
  Twiddle rotating(n);  // beyond the kept sizes
  auto twiddle = [&](std::size_t k) { return twiddles ? (*twiddles)[k] : rotating(k); };
  for (std::size_t k = 1; k <= half / 2; ++k) {
    const std::complex<double> zk = x[k], zc = std::conj(x[half - k]);
    const std::complex<double> even = 0.5 * (zk + zc);
    const std::complex<double> d = zk - zc;  // odd = W^k (-i/2) d
    const std::complex<double> odd = MulFinite(twiddle(k), {0.5 * d.imag(), -0.5 * d.real()});
    x[k] = even + odd;
    x[half - k] = std::conj(even - odd);
  }
}

void InverseRealFft(std::size_t n, double* data) {
  const std::size_t half = n / 2;
  auto* x = reinterpret_cast<std::complex<double>*>(data);
  const double x0 = x[0].real(), xn = x[half].real();
  x[0] = std::complex<double>(x0 + xn, x0 - xn);
  const auto twiddles = RealFftTwiddles(n);
  Twiddle rotating(n);  // beyond the kept sizes
  auto twiddle = [&](std::size_t k) { return twiddles ? (*twiddles)[k] : rotating(k); };
  for (std::size_t k = 1; k <= half / 2; ++k) {
    const std::complex<double> xk = x[k], xc = std::conj(x[half - k]);
    const std::complex<double> even = xk + xc;                        // 2 E_k
    const std::complex<double> odd = MulFinite(std::conj(twiddle(k)), xk - xc);  // 2 W^k O_k / W^k
    const std::complex<double> i_odd(-odd.imag(), odd.real());
    x[k] = even + i_odd;
    x[half - k] = std::conj(even - i_odd);
  }
  fftw_execute_dft(PlansFor(half, data).inverse, reinterpret_cast<fftw_complex*>(data),
                   reinterpret_cast<fftw_complex*>(data));
}

}  // namespace allanlab::sim
