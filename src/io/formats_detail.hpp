#pragma once
// Shared by the readers and writers of io/formats.hpp: whole-file reads, zlib (gzip and raw
// deflate) in both directions, little-endian stores, and the conversions the packed formats share.
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>

#include "vksplat/error.hpp"
#include "vksplat/scene/scene.hpp"

namespace vksplat::io::detail {

// The zeroth-order SH basis constant: colour = 0.5 + kShC0 * f_dc.
inline constexpr double kShC0 = 0.28209479177387814;

inline std::string read_file_bytes(const std::filesystem::path& path, const std::string& where) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(where, std::filesystem::exists(path) ? "cannot be opened" : "no such file");
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) throw InputError(where, "cannot be read (size unknown)");
    std::string bytes(static_cast<size_t>(size), '\0');
    in.seekg(0);
    if (!in.read(bytes.data(), size)) throw InputError(where, "reading " + std::to_string(size) + " bytes failed");
    return bytes;
}

template <typename T>
void store_little_endian(std::string& out, T value) {
    static_assert(std::is_arithmetic_v<T>);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

inline uint8_t to_byte(double value) {
    if (!(value == value)) return 0;  // NaN
    return static_cast<uint8_t>(std::clamp(std::round(value), 0.0, 255.0));
}

inline double sigmoid(double logit) { return 1.0 / (1.0 + std::exp(-logit)); }

// The logit of an opacity in [0, 1]; 0 and 1 (whose logits are infinite) give -/+kMaxOpacityLogit,
// which sanitize() would clamp them to anyway.
inline float logit_of(double opacity) {
    if (opacity <= 0.0) return -kMaxOpacityLogit;
    if (opacity >= 1.0) return kMaxOpacityLogit;
    return static_cast<float>(std::clamp(std::log(opacity / (1.0 - opacity)), double(-kMaxOpacityLogit),
                                         double(kMaxOpacityLogit)));
}

// Throws InputError naming `where` if the cloud's arrays disagree.
inline void check_writable(const GaussianCloud& cloud, const std::string& where) {
    try {
        cloud.check_consistent();
    } catch (const std::exception& error) {
        throw InputError(where, std::string("cannot write an inconsistent cloud: ") + error.what());
    }
}

// Pulls bytes out of a deflate stream as they are asked for, so that a header can be checked before
// the body is inflated, and memory only grows with data that is really there.
class Inflater {
public:
    enum class Wrapping { gzip, raw };

    Inflater(std::string_view compressed, Wrapping wrapping, std::string where)
        : where_(std::move(where)) {
        stream_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
        stream_.avail_in = 0;
        remaining_in_ = compressed.size();
        const int bits = wrapping == Wrapping::gzip ? 16 + MAX_WBITS : -MAX_WBITS;
        if (inflateInit2(&stream_, bits) != Z_OK) throw InputError(where_, "zlib could not be initialised");
    }
    ~Inflater() { inflateEnd(&stream_); }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;

    // Appends up to `count` bytes to `out`; returns how many came (fewer only at the stream's end).
    uint64_t read(std::string& out, uint64_t count) {
        uint64_t got = 0;
        constexpr uint64_t kPiece = uint64_t{1} << 24;
        while (got < count && !finished_) {
            const uint64_t want = std::min(count - got, kPiece);
            const size_t start = out.size();
            out.resize(start + want);
            stream_.next_out = reinterpret_cast<Bytef*>(out.data() + start);
            stream_.avail_out = static_cast<uInt>(want);
            while (stream_.avail_out > 0 && !finished_) {
                if (stream_.avail_in == 0 && remaining_in_ > 0) {
                    const uint64_t feed = std::min<uint64_t>(remaining_in_, std::numeric_limits<uInt>::max() / 2);
                    stream_.avail_in = static_cast<uInt>(feed);
                    remaining_in_ -= feed;
                }
                const int status = inflate(&stream_, Z_NO_FLUSH);
                if (status == Z_STREAM_END) {
                    finished_ = true;
                } else if (status == Z_BUF_ERROR && stream_.avail_in == 0 && remaining_in_ == 0) {
                    throw InputError(where_, "truncated: the compressed data ends early (after " +
                                                 std::to_string(stream_.total_out) + " bytes decompressed)");
                } else if (status != Z_OK && status != Z_BUF_ERROR) {
                    throw InputError(where_, std::string("corrupt compressed data (zlib: ") +
                                                 (stream_.msg ? stream_.msg : "error " + std::to_string(status)) +
                                                 ")");
                }
            }
            const uint64_t produced = want - stream_.avail_out;
            out.resize(start + produced);
            got += produced;
        }
        return got;
    }

    // True if the stream ends here. When it does not, one byte is consumed to find out: callers
    // treat more data as an error.
    bool at_end() {
        if (finished_) return true;
        std::string probe;
        return read(probe, 1) == 0;
    }

private:
    z_stream stream_{};
    uint64_t remaining_in_ = 0;
    bool finished_ = false;
    std::string where_;
};

// Compresses `data` as a gzip member (wrapping gzip) or raw deflate.
inline std::string deflate_bytes(std::string_view data, Inflater::Wrapping wrapping, const std::string& where,
                                 int level = Z_DEFAULT_COMPRESSION) {
    z_stream stream{};
    const int bits = wrapping == Inflater::Wrapping::gzip ? 16 + MAX_WBITS : -MAX_WBITS;
    if (deflateInit2(&stream, level, Z_DEFLATED, bits, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw InputError(where, "zlib could not be initialised for compression");
    std::string out;
    out.resize(deflateBound(&stream, static_cast<uLong>(std::min<size_t>(data.size(), 1u << 30))) + 64);
    size_t in_offset = 0, out_offset = 0;
    int status = Z_OK;
    do {
        const size_t feed = std::min<size_t>(data.size() - in_offset, 1u << 30);
        stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + in_offset));
        stream.avail_in = static_cast<uInt>(feed);
        in_offset += feed;
        const int flush = in_offset == data.size() ? Z_FINISH : Z_NO_FLUSH;
        do {
            if (out.size() - out_offset < (1u << 16)) out.resize(out.size() * 2 + (1u << 16));
            stream.next_out = reinterpret_cast<Bytef*>(out.data() + out_offset);
            const size_t space = std::min<size_t>(out.size() - out_offset, 1u << 30);
            stream.avail_out = static_cast<uInt>(space);
            status = deflate(&stream, flush);
            out_offset += space - stream.avail_out;
        } while (stream.avail_in > 0 || (flush == Z_FINISH && status != Z_STREAM_END));
    } while (in_offset < data.size());
    deflateEnd(&stream);
    if (status != Z_STREAM_END) throw InputError(where, "compression failed");
    out.resize(out_offset);
    return out;
}

inline uint32_t crc32_of(std::string_view data) {
    uLong crc = ::crc32(0L, Z_NULL, 0);
    for (size_t offset = 0; offset < data.size();) {
        const size_t piece = std::min<size_t>(data.size() - offset, 1u << 30);
        crc = ::crc32(crc, reinterpret_cast<const Bytef*>(data.data() + offset), static_cast<uInt>(piece));
        offset += piece;
    }
    return static_cast<uint32_t>(crc);
}

}  // namespace vksplat::io::detail
