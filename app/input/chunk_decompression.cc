#include "app/input/chunk_decompression.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

namespace allanlab::app {

bool DecompressChunk(const std::string& compression, std::span<const std::uint8_t> in, std::vector<std::uint8_t>* out,
                     std::string* why) {
  bool ok = false;
  if (compression == "zstd") {
    const std::size_t got = ZSTD_decompress(out->data(), out->size(), in.data(), in.size());
    ok = !ZSTD_isError(got) && got == out->size();
  } else if (compression == "bz2") {
    auto size = static_cast<unsigned int>(out->size());
    std::vector<char> source(in.begin(), in.end());  // bzlib takes a non-const source
    ok = BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out->data()), &size, source.data(),
                                    static_cast<unsigned int>(source.size()), 0, 0) == BZ_OK &&
         size == out->size();
  } else if (compression == "lz4") {
    LZ4F_dctx* context = nullptr;
    if (!LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
      std::size_t in_pos = 0, out_pos = 0, status = 1;
      while (status != 0 && in_pos < in.size()) {
        std::size_t in_size = in.size() - in_pos, out_size = out->size() - out_pos;
        status = LZ4F_decompress(context, out->data() + out_pos, &out_size, in.data() + in_pos, &in_size, nullptr);
        if (LZ4F_isError(status) || (in_size == 0 && out_size == 0)) break;
        in_pos += in_size;
        out_pos += out_size;
      }
      ok = !LZ4F_isError(status) && status == 0 && out_pos == out->size();
    }
    LZ4F_freeDecompressionContext(context);
  } else {
    *why = "chunk compression '" + compression + "' is not one allanlab reads (zstd, lz4, bz2)";
    return false;
  }
  if (!ok) *why = "a " + compression + " chunk does not decompress to its stated size (a damaged file)";
  return ok;
}

}  // namespace allanlab::app
