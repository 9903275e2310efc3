#pragma once
// One more thread for a caller that shares its work with it: the caller posts a job that takes
// pieces of the work while the caller takes pieces too, until none is left. The caller never
// waits for the helper to start (a helper the shared machine keeps waiting costs at most the
// piece it holds), so a job may run late, or not at all when a newer one replaces it: a job must
// only touch what it has claimed. The thread starts at the first job and sleeps between jobs (no
// spinning: the machine may be shared).
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace allanlab::app {

class HelperThread {
 public:
  HelperThread() = default;
  ~HelperThread();  // a job not yet started is dropped; a running one is waited for
  HelperThread(const HelperThread&) = delete;
  HelperThread& operator=(const HelperThread&) = delete;

  // Gives the helper `job` (which must not throw); it replaces a job given before and not yet
  // started.
  void Post(std::function<void()> job);

  // Whether a second thread is worth starting: more than one core, and OpenMP not limited to one
  // thread (OMP_NUM_THREADS=1 runs everything in the calling thread).
  static bool Useful();

 private:
  void Loop();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::function<void()> job_;
  bool has_job_ = false;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace allanlab::app
