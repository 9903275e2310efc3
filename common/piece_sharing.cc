#include "common/piece_sharing.h"

#include <omp.h>

#include <atomic>
#include <memory>
#include <utility>

namespace allanlab {

PieceSharing::~PieceSharing() {
  if (!thread_.joinable()) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

bool PieceSharing::Useful() {
  return std::thread::hardware_concurrency() > 1 && omp_get_max_threads() > 1 && !omp_in_parallel();
}

void PieceSharing::Run(int count, const std::function<void(int)>& piece) {
  // The counters of this run alone: a helper that starts after the run has returned finds every
  // piece taken and calls nothing.
  struct Claims {
    std::atomic<int> next{0}, done{0};
  };
  const auto claims = std::make_shared<Claims>();
  const auto take_pieces = [claims, count, &piece] {
    for (int p; (p = claims->next.fetch_add(1)) < count;) {
      piece(p);
      claims->done.fetch_add(1);
      claims->done.notify_one();
    }
  };
  if (count > 1) {
    {
      // A share given before and not yet started is replaced: its pieces were all taken here.
      const std::lock_guard<std::mutex> lock(mutex_);
      job_ = take_pieces;
      has_job_ = true;
    }
    if (!thread_.joinable()) {
      thread_ = std::thread([this] { Loop(); });
    } else {
      wake_.notify_one();
    }
  }
  take_pieces();
  for (int done = claims->done.load(); done < count; done = claims->done.load()) claims->done.wait(done);
}

void PieceSharing::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || has_job_; });
    if (stop_) return;
    std::function<void()> job = std::move(job_);
    has_job_ = false;
    lock.unlock();
    job();
    lock.lock();
  }
}

}  // namespace allanlab
