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

void HelperThread::Run(std::function<void()> job) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    job_ = std::move(job);
    pending_ = true;
  }
  if (!thread_.joinable()) {
    thread_ = std::thread([this] { Loop(); });
  } else {
    wake_.notify_one();
  }
}

void HelperThread::Wait() {
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return !pending_; });
}

bool HelperThread::Useful() { return std::thread::hardware_concurrency() > 1 && omp_get_max_threads() > 1; }

void HelperThread::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || pending_; });
    if (pending_) {
      std::function<void()> job = std::move(job_);
      lock.unlock();
      job();
      lock.lock();
      pending_ = false;
      done_.notify_one();
    }
    if (stop_) return;
  }
}

}  // namespace allanlab::app
