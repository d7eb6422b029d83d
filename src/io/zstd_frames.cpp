#include "io/zstd_frames.hpp"

#include <zstd.h>

#include <algorithm>
#include <memory>

#include "vksplat/error.hpp"

namespace vksplat::io::detail {
namespace {

struct FreeDecompressor {
    void operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }
};
struct FreeCompressor {
    void operator()(ZSTD_CCtx* context) const { ZSTD_freeCCtx(context); }
};

}  // namespace

std::string zstd_decompress(std::string_view frame, uint64_t expected, const std::string& where) {
    const std::unique_ptr<ZSTD_DCtx, FreeDecompressor> context(ZSTD_createDCtx());
    if (!context) throw InputError(where, "zstd could not be initialised");
    ZSTD_inBuffer in{frame.data(), frame.size(), 0};
    std::string out;
    constexpr uint64_t kPiece = uint64_t{1} << 24;
    size_t status = 1;  // not 0: the frame has not ended
    // One byte past `expected` is asked for, so that a frame holding more is found out.
    while (status != 0 && out.size() <= expected) {
        const size_t start = out.size();
        out.resize(start + std::min<uint64_t>(expected + 1 - start, kPiece));
        ZSTD_outBuffer piece{out.data() + start, out.size() - start, 0};
        status = ZSTD_decompressStream(context.get(), &piece, &in);
        out.resize(start + piece.pos);
        if (ZSTD_isError(status))
            throw InputError(where, std::string("corrupt compressed data (zstd: ") + ZSTD_getErrorName(status) + ")");
        // Room left over with no input left: the decoder waits for bytes the file does not have.
        if (status != 0 && in.pos == in.size && piece.pos < piece.size) break;
    }
    if (out.size() < expected)
        throw InputError(where, "truncated: the compressed data gives " + std::to_string(out.size()) + " of the " +
                                    std::to_string(expected) + " bytes the header says");
    if (out.size() > expected || in.pos != in.size)
        throw InputError(where, "holds more than the " + std::to_string(expected) + " bytes the header says");
    return out;
}

std::string zstd_compress(std::string_view data, int level, const std::string& where) {
    const std::unique_ptr<ZSTD_CCtx, FreeCompressor> context(ZSTD_createCCtx());
    if (!context) throw InputError(where, "zstd could not be initialised for compression");
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, level);
    std::string out(ZSTD_compressBound(data.size()), '\0');
    const size_t size = ZSTD_compress2(context.get(), out.data(), out.size(), data.data(), data.size());
    if (ZSTD_isError(size)) throw InputError(where, std::string("compression failed (zstd: ") + ZSTD_getErrorName(size) + ")");
    out.resize(size);
    return out;
}

}  // namespace vksplat::io::detail
