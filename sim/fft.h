#pragma once
// Thin, thread-safe use of FFTW for real convolutions. Plans are made once per size under a lock
// (FFTW's planner is not thread-safe) with FFTW_ESTIMATE (measured plans at 2^21 take minutes),
// then executed through the new-array interface, which is safe from many threads at once.
#include <complex>
#include <cstddef>
#include <memory>
#include <vector>

namespace allanlab::sim {

// An FFTW-aligned buffer of doubles (aligned like fftw_malloc, so cached plans apply to it).
class FftBuffer {
 public:
  explicit FftBuffer(std::size_t size);
  ~FftBuffer();
  FftBuffer(const FftBuffer&) = delete;
  FftBuffer& operator=(const FftBuffer&) = delete;
  FftBuffer(FftBuffer&& other) noexcept;
  FftBuffer& operator=(FftBuffer&& other) noexcept;
  double* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::complex<double>* complex_data() const {
    return reinterpret_cast<std::complex<double>*>(data_);
  }

 private:
  double* data_ = nullptr;
  std::size_t size_ = 0;
};

// a * b without the inf/NaN recovery of std::complex's operator* (a libgcc call per product
// unless -fcx-limited-range): hot FFT loops multiply finite numbers only.
inline std::complex<double> MulFinite(std::complex<double> a, std::complex<double> b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

// The smallest size >= n of the form 2^a 3^b 5^c 7^d (fast for FFTW). Real transforms need an
// even length: use 2 * GoodFftSize(m) for m >= n / 2.
std::size_t GoodFftSize(std::size_t n);

// In-place real <-> half-complex transforms of even length n on n + 2 doubles at `data` (any
// 16-byte-aligned allocation), laid out as FFTW's r2c: X_0..X_{n/2} as complex pairs. Inverse is
// unnormalised (FFTW convention): Inverse(Forward(x)) = n x.
void ForwardRealFft(std::size_t n, double* data);
void InverseRealFft(std::size_t n, double* data);

// W^k = e^{-2 pi i k / n} for k = 0..n/4 as the real transforms' split uses them: by rotation from
// k = 1, re-anchored with sin/cos every 512 steps. The rotation is a serial chain of complex
// products (a sixth of a 2^14-point PSD segment's transform, each time), so the values are made
// once per n and kept; the same chain, so the same bits. Thread-safe; never modified. nullptr
// for n / 4 beyond 2^20 (those are not kept: the transforms rotate as they go).
std::shared_ptr<const std::vector<std::complex<double>>> RealFftTwiddles(std::size_t n);

}  // namespace allanlab::sim
