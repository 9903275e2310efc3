#include "app/input/helper_thread.h"

#include <omp.h>

#include <utility>

namespace allanlab::app {

HelperThread::~HelperThread() {
  if (!thread_.joinable()) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void HelperThread::Post(std::function<void()> job) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    job_ = std::move(job);
    has_job_ = true;
  }
  if (!thread_.joinable()) {
    thread_ = std::thread([this] { Loop(); });
  } else {
    wake_.notify_one();
  }
}

bool HelperThread::Useful() { return std::thread::hardware_concurrency() > 1 && omp_get_max_threads() > 1; }

void HelperThread::Loop() {
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

}  // namespace allanlab::app
