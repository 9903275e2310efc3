#include "sim/fft.h"

#include <fftw3.h>

#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>

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

const PlanPair& PlansFor(std::size_t n) {
  static std::map<std::size_t, PlanPair> plans;  // plans live for the whole process
  std::lock_guard<std::mutex> lock(PlannerMutex());
  auto it = plans.find(n);
  if (it != plans.end()) return it->second;
  FftBuffer scratch(n + 2);
  PlanPair pair;
  const int size = static_cast<int>(n);
  pair.forward = fftw_plan_dft_r2c_1d(size, scratch.data(),
                                      reinterpret_cast<fftw_complex*>(scratch.data()),
                                      FFTW_ESTIMATE);
  pair.inverse = fftw_plan_dft_c2r_1d(size, reinterpret_cast<fftw_complex*>(scratch.data()),
                                      scratch.data(), FFTW_ESTIMATE);
  if (!pair.forward || !pair.inverse) throw std::runtime_error("FFTW could not plan a transform");
  return plans.emplace(n, pair).first->second;
}

}  // namespace

FftBuffer::FftBuffer(std::size_t size) : size_(size) {
  data_ = static_cast<double*>(fftw_malloc(sizeof(double) * size));
  if (!data_) throw std::bad_alloc();
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

void ForwardRealFft(std::size_t n, FftBuffer& buffer) {
  fftw_execute_dft_r2c(PlansFor(n).forward, buffer.data(),
                       reinterpret_cast<fftw_complex*>(buffer.data()));
}

void InverseRealFft(std::size_t n, FftBuffer& buffer) {
  fftw_execute_dft_c2r(PlansFor(n).inverse, reinterpret_cast<fftw_complex*>(buffer.data()),
                       buffer.data());
}

}  // namespace allanlab::sim
