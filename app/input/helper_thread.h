#pragma once
// One more thread for a caller that splits its work in two: the helper runs one job while the
// caller does its own share, and Wait() returns when the job is done. The thread starts at the
// first job and sleeps between jobs (no spinning: the machine may be shared), so a caller that
// hands it thousands of jobs pays one thread start.
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace allanlab::app {

class HelperThread {
 public:
  HelperThread() = default;
  ~HelperThread();
  HelperThread(const HelperThread&) = delete;
  HelperThread& operator=(const HelperThread&) = delete;

  // Starts `job` on the helper; the previous job must have been waited for. The job must not
  // throw.
  void Run(std::function<void()> job);
  // Returns once the job given to Run has finished (at once when there is none).
  void Wait();

  // Whether a second thread is worth starting: more than one core, and OpenMP not limited to one
  // thread (OMP_NUM_THREADS=1 runs everything in the calling thread).
  static bool Useful();

 private:
  void Loop();

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::function<void()> job_;
  bool pending_ = false;  // a job is given and not finished
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace allanlab::app
