#pragma once
// Work cut into independent pieces, shared by the calling thread and one helper thread: each takes
// the next piece nobody has taken until none is left, and Run returns when every piece has run.
// What a piece computes does not depend on which thread ran it, so neither does the result. The
// caller never waits for the helper to start (on a shared machine it may be kept waiting: it then
// costs at most the piece it holds), and the helper sleeps between runs (no spinning). Used for the
// octaves of a streamed block (estimators/streaming_avar.h), which the helper folds while the caller
// reads the next block (Start, Finish).
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace allanlab {

class PieceSharing {
 public:
  PieceSharing() = default;
  ~PieceSharing();
  PieceSharing(const PieceSharing&) = delete;
  PieceSharing& operator=(const PieceSharing&) = delete;

  // Runs piece(0) .. piece(count - 1), each once, in this thread and the helper; returns when all
  // have run. `piece` must not throw, and pieces must not touch each other's data.
  void Run(int count, const std::function<void(int)>& piece);

  // Run in two halves, for a caller with work of its own to overlap: Start hands the pieces to the
  // helper and returns at once; Finish takes, in the calling thread, those the helper has not
  // started and returns when all have run. Between the two the caller must touch no piece's data.
  // Start and Run finish a started run first; so does the destructor.
  void Start(int count, std::function<void(int)> piece);
  void Finish();

  // Whether a helper is worth having: more than one core, and OpenMP neither limited to one
  // thread (OMP_NUM_THREADS=1 runs everything in the calling thread) nor already running a team.
  static bool Useful();

 private:
  void Loop();
  struct Claims;
  // Hands take_pieces to the helper (starting it at the first run).
  void Offer(std::function<void()> take_pieces);

  // The run Start began, until Finish.
  std::shared_ptr<Claims> started_;
  std::function<void()> take_started_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::function<void()> job_;  // the helper's share of the latest Run, not yet started
  bool has_job_ = false;
  bool stop_ = false;
  std::thread thread_;  // started at the first Run
};

}  // namespace allanlab
