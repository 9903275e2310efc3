// TextRecordParser::ReadChunkInTwoThreads: a large chunk cut at line starts into a first part,
// which this thread reads, and pieces after it, which the helper thread reads into arrays (and
// this thread too, those the helper has not started when this one is done with its part: a
// helper kept waiting by a busy machine then costs at most the piece it holds). The rows are
// passed on in file order once every piece is read. Whatever one thread would do differently is
// kept: every line that is not a common row goes through FeedLines as in one thread, and a
// piece's rows are only passed on when the lines before it left rows readable as common rows.
#include <algorithm>

#include "app/input/text_record_parser.h"
#include "common/piece_sharing.h"

namespace allanlab::app {
namespace {

// The pieces' share of a chunk, in 64ths. This thread also passes the rows on (the record's
// checks run in the sink), which overlaps the helper's reading when the pieces are the larger part.
constexpr std::size_t kPiecesShare64 = 36;
// Pieces small enough that waiting for the one the helper holds costs little.
constexpr int kPieces = 8;

}  // namespace

void TextRecordParser::UseTwoThreads(std::size_t min_bytes) {
  two_thread_min_bytes_ = std::max<std::size_t>(min_bytes, 1);
}

bool TextRecordParser::ReadLinesInThisThread(std::string_view lines) {
  while (!lines.empty()) {
    if (!CommonRowsPossible()) return FeedLines(lines, false);
    lines.remove_prefix(ReadCommonRun(lines));
    if (failed_) return false;
    if (lines.empty()) break;
    const std::size_t line = lines.find('\n') + 1;
    if (!FeedLines(lines.substr(0, line), false)) return false;
    lines.remove_prefix(line);
  }
  return true;
}

std::size_t TextRecordParser::ReadChunkInTwoThreads(std::string_view chunk) {
  // Piece k is [starts[k], starts[k + 1]); all but the last end at a line start, the last at the
  // chunk's end (a partial line stays for FeedLines).
  const std::size_t whole = chunk.rfind('\n') + 1;  // 0 without a newline
  const std::size_t pieces_bytes = chunk.size() / 64 * kPiecesShare64;
  const std::size_t first_end = chunk.find('\n', chunk.size() - pieces_bytes) + 1;
  if (first_end == 0 || first_end >= whole) return 0;
  std::size_t starts[kPieces + 1];
  starts[0] = first_end;
  for (int k = 1; k < kPieces; ++k) {
    const std::size_t at =
        first_end + (whole - first_end) / kPieces * k;  // before the last newline
    starts[k] = std::max(starts[k - 1], chunk[at - 1] == '\n' ? at : chunk.find('\n', at) + 1);
  }
  starts[kPieces] = chunk.size();
  const auto piece = [chunk, &starts](int k) {
    return chunk.substr(starts[k], starts[k + 1] - starts[k]);
  };
  if (!helper_) helper_ = std::make_unique<PieceSharing>();
  helper_rows_.resize(kPieces);
  helper_->Start(
      kPieces, [this, piece](int k) { ReadCommonRows(common_shape_, piece(k), &helper_rows_[k]); });
  ++two_thread_chunks_;
  bool ok = false;
  {
    // The helper reads the chunk until Finish returns: here, or when the sink throws (the caller
    // may then free the chunk).
    struct FinishOnExit {
      PieceSharing& helper;
      ~FinishOnExit() { helper.Finish(); }
    } finish{*helper_};
    ok = ReadLinesInThisThread(chunk.substr(0, first_end));
  }
  for (int k = 0; ok && k < kPieces; ++k) {
    // A piece's rows are the rows one thread reads next unless a line before it changed what a
    // row is: an integer time stamp sets the origin of the times after it.
    std::string_view rest = piece(k);
    if (CommonRowsPossible()) {
      ok = PassCommonRows(helper_rows_[k]);
      rest.remove_prefix(helper_rows_[k].bytes);
    }
    if (k == kPieces - 1) return ok ? chunk.size() - rest.size() : 0;
    if (ok) ok = ReadLinesInThisThread(rest);
  }
  return 0;  // failed_ says why
}

}  // namespace allanlab::app
