#include "experiments/row_codec.h"

#include <cstring>

namespace allanlab::experiments {
namespace {

template <typename T>
void Put(const T& value, std::vector<unsigned char>* out) {
  const auto* p = reinterpret_cast<const unsigned char*>(&value);
  out->insert(out->end(), p, p + sizeof(T));
}

class Reader {
 public:
  explicit Reader(std::span<const unsigned char> bytes) : bytes_(bytes) {}
  template <typename T>
  bool Get(T* value) {
    if (bytes_.size() - pos_ < sizeof(T)) return false;
    std::memcpy(value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool GetString(std::size_t size, std::string* text) {
    if (bytes_.size() - pos_ < size) return false;
    text->assign(reinterpret_cast<const char*>(bytes_.data() + pos_), size);
    pos_ += size;
    return true;
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }

 private:
  std::span<const unsigned char> bytes_;
  std::size_t pos_ = 0;
};

}  // namespace

void EncodeRows(std::span<const TrialRow> rows, std::vector<unsigned char>* out) {
  Put<std::uint64_t>(rows.size(), out);
  for (const TrialRow& row : rows) {
    Put<std::int32_t>(row.point, out);
    Put<std::int64_t>(row.trial, out);
    Put<std::uint8_t>(row.ok ? 1 : 0, out);
    Put<std::uint32_t>(static_cast<std::uint32_t>(row.status.size()), out);
    out->insert(out->end(), row.status.begin(), row.status.end());
    Put<double>(row.runtime_s, out);
    Put<std::uint32_t>(static_cast<std::uint32_t>(row.values.size()), out);
    for (double v : row.values) Put<double>(v, out);
  }
}

bool DecodeRows(std::span<const unsigned char> bytes, std::vector<TrialRow>* rows) {
  Reader in(bytes);
  std::uint64_t count = 0;
  if (!in.Get(&count)) return false;
  // Every row takes at least 33 bytes: a corrupt count cannot make us allocate wildly.
  if (count > in.remaining() / 33) return false;
  for (std::uint64_t i = 0; i < count; ++i) {
    TrialRow row;
    std::int32_t point = 0;
    std::uint8_t ok = 0;
    std::uint32_t status_size = 0;
    std::uint32_t value_count = 0;
    if (!in.Get(&point) || !in.Get(&row.trial) || !in.Get(&ok) || !in.Get(&status_size) ||
        !in.GetString(status_size, &row.status) || !in.Get(&row.runtime_s) ||
        !in.Get(&value_count) || value_count > in.remaining() / sizeof(double)) {
      return false;
    }
    row.point = point;
    row.ok = ok != 0;
    row.values.resize(value_count);
    for (double& v : row.values) {
      if (!in.Get(&v)) return false;
    }
    rows->push_back(std::move(row));
  }
  return in.remaining() == 0;
}

std::uint64_t Fnv1a64(std::span<const unsigned char> bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

}  // namespace allanlab::experiments
