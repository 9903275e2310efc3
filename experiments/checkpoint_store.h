#pragma once
// The on-disk store of finished trial rows behind --resume. One file: a header naming the spec
// hash and the driver, then one record per finished batch (magic, length, rows, checksum), each
// appended with a single write and fsync'ed. A record torn by kill -9 or a crash mid-write fails
// its length or checksum; it and anything after it are dropped (and truncated away) on resume.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "experiments/runner.h"

namespace allanlab::experiments {

class CheckpointStore {
 public:
  CheckpointStore() = default;
  CheckpointStore(const CheckpointStore&) = delete;
  CheckpointStore& operator=(const CheckpointStore&) = delete;
  ~CheckpointStore();

  // A new store at `path` for this spec and driver. The header is written to a temporary and
  // renamed, so a crash leaves no store or a whole header. Fails when `path` already exists
  // (a run to resume must not be overwritten by mistake).
  bool Create(const std::string& path, std::uint64_t spec_hash, const std::string& driver,
              std::string* why);
  // Opens an existing store for appending after loading its intact records into *rows (in file
  // order). Fails when the file is not a store or belongs to another spec or driver.
  bool Resume(const std::string& path, std::uint64_t spec_hash, const std::string& driver,
              std::vector<TrialRow>* rows, std::string* why);
  // Appends one record holding `rows` and syncs it to disk.
  bool Append(std::span<const TrialRow> rows, std::string* why);
  void Close();

 private:
  int fd_ = -1;
  std::string path_;
};

}  // namespace allanlab::experiments
