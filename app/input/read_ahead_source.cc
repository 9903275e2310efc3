#include "app/input/read_ahead_source.h"

#include <algorithm>
#include <array>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace allanlab::app {
namespace {

// One buffer of the ring: what one Read of the wrapped source gave.
struct Filled {
  std::vector<char> bytes;
  std::size_t got = 0;
  bool ok = true;
  std::string why;
};

class ReadAheadSource : public ByteSource {
 public:
  explicit ReadAheadSource(std::unique_ptr<ByteSource> source)
      : source_(std::move(source)), compression_(source_->compression()) {
    for (Filled& f : ring_) f.bytes.resize(kReadAheadBufferBytes);
    thread_ = std::thread([this] { Produce(); });
  }
  ~ReadAheadSource() override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    space_.notify_one();
    thread_.join();
  }
  ReadAheadSource(const ReadAheadSource&) = delete;
  ReadAheadSource& operator=(const ReadAheadSource&) = delete;

  bool Read(std::span<char> out, std::size_t* got, std::string* why) override {
    *got = 0;
    if (out.empty() || ended_) return true;
    if (!holding_) {
      std::unique_lock<std::mutex> lock(mutex_);
      data_.wait(lock, [this] { return filled_ > 0; });
      holding_ = true;
      offset_ = 0;
    }
    Filled& f = ring_[static_cast<std::size_t>(consumer_)];
    if (!f.ok || f.got == 0) {
      // The end or the error stays where it is: the producer has stopped after it.
      ended_ = true;
      if (!f.ok && why) *why = f.why;
      return f.ok;
    }
    const std::size_t n = std::min(out.size(), f.got - offset_);
    std::memcpy(out.data(), f.bytes.data() + offset_, n);
    offset_ += n;
    *got = n;
    if (offset_ == f.got) Release();
    return true;
  }
  Compression compression() const override { return compression_; }

 private:
  void Release() {
    holding_ = false;
    consumer_ = (consumer_ + 1) % kReadAheadBuffers;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      --filled_;
    }
    space_.notify_one();
  }

  void Produce() {
    int producer = 0;
    while (true) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        space_.wait(lock, [this] { return stop_ || filled_ < kReadAheadBuffers; });
        if (stop_) return;
      }
      // The consumer never touches a buffer until it is counted in filled_.
      Filled& f = ring_[static_cast<std::size_t>(producer)];
      f.got = 0;
      f.ok = source_->Read(f.bytes, &f.got, &f.why);
      const bool last = !f.ok || f.got == 0;
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        ++filled_;
      }
      data_.notify_one();
      if (last) return;
      producer = (producer + 1) % kReadAheadBuffers;
    }
  }

  std::unique_ptr<ByteSource> source_;
  const Compression compression_;
  std::array<Filled, kReadAheadBuffers> ring_;
  std::mutex mutex_;
  std::condition_variable data_, space_;
  int filled_ = 0;      // buffers filled and not yet consumed (guarded by mutex_)
  bool stop_ = false;   // guarded by mutex_
  // The consumer's side, touched only by Read.
  int consumer_ = 0;
  bool holding_ = false;
  std::size_t offset_ = 0;
  bool ended_ = false;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace

std::unique_ptr<ByteSource> ReadAhead(std::unique_ptr<ByteSource> source) {
  return std::make_unique<ReadAheadSource>(std::move(source));
}

}  // namespace allanlab::app
