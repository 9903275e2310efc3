#include "common/piece_sharing.h"

#include <omp.h>

#include <atomic>
#include <memory>
#include <utility>

namespace allanlab {

// The counters of one run alone: a helper that starts after the run has returned finds every
// piece taken and calls nothing.
struct PieceSharing::Claims {
  std::atomic<int> next{0}, done{0};
  int count = 0;
  // Takes pieces until none is left.
  void Take(const std::function<void(int)>& piece) {
    for (int p; (p = next.fetch_add(1)) < count;) {
      piece(p);
      done.fetch_add(1);
      done.notify_one();
    }
  }
  void Wait() {
    for (int d = done.load(); d < count; d = done.load()) done.wait(d);
  }
};

PieceSharing::~PieceSharing() {
  Finish();
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

void PieceSharing::Offer(std::function<void()> take_pieces) {
  {
    // A share given before and not yet started is replaced: its pieces were all taken by the caller.
    const std::lock_guard<std::mutex> lock(mutex_);
    job_ = std::move(take_pieces);
    has_job_ = true;
  }
  if (!thread_.joinable()) {
    thread_ = std::thread([this] { Loop(); });
  } else {
    wake_.notify_one();
  }
}

void PieceSharing::Run(int count, const std::function<void(int)>& piece) {
  Finish();
  const auto claims = std::make_shared<Claims>();
  claims->count = count;
  if (count > 1) Offer([claims, &piece] { claims->Take(piece); });
  claims->Take(piece);
  claims->Wait();
}

void PieceSharing::Start(int count, std::function<void(int)> piece) {
  Finish();
  if (count <= 0) return;
  const auto claims = std::make_shared<Claims>();
  claims->count = count;
  // The helper's copy of the job owns the piece function: it may still be taking its last claim
  // (and find none left) after Finish has returned.
  const auto shared_piece = std::make_shared<std::function<void(int)>>(std::move(piece));
  take_started_ = [claims, shared_piece] { claims->Take(*shared_piece); };
  started_ = claims;
  Offer(take_started_);
}

void PieceSharing::Finish() {
  if (!started_) return;
  take_started_();
  started_->Wait();
  started_.reset();
  take_started_ = nullptr;
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
