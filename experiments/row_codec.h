#pragma once
// Trial rows as bytes, exactly (doubles bit for bit, NaN included), for the checkpoint store and
// the MPI gather. Little-endian host layout: a checkpoint is read back on the machine (or the
// cluster of identical machines) that wrote it.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "experiments/runner.h"

namespace allanlab::experiments {

// Appends rows: u64 count, then per row i32 point, i64 trial, u8 ok, u32 status length, status,
// f64 runtime, u32 value count, f64 values.
void EncodeRows(std::span<const TrialRow> rows, std::vector<unsigned char>* out);
// Reads what EncodeRows wrote; false when the bytes are short or inconsistent.
bool DecodeRows(std::span<const unsigned char> bytes, std::vector<TrialRow>* rows);

// FNV-1a 64 of bytes (the checkpoint's record checksum, the spec hash).
std::uint64_t Fnv1a64(std::span<const unsigned char> bytes);

}  // namespace allanlab::experiments
