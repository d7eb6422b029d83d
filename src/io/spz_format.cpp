// Niantic's SPZ: each attribute of every splat in turn (positions, alphas, colours, scales,
// rotations, SH), quantised to bytes. Versions 2 and 3 are one gzip stream holding a 16-byte header
// and the attributes; version 4 is a plain 32-byte header, a table of contents and one zstd frame
// per attribute.
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string_view>
#include <utility>

#include "io/byte_order.hpp"
#include "io/formats_detail.hpp"
#include "io/zstd_frames.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

constexpr uint32_t kMagic = 0x5053474e;  // "NGSP" little-endian
constexpr size_t kHeaderBytes = 16;      // versions 2 and 3, inside the gzip stream
constexpr size_t kHeaderBytesV4 = 32;    // version 4, plain, then extensions and the table of contents
constexpr size_t kTocEntryBytes = 16;    // compressed size, decompressed size (u64 each)
// Niantic's library compresses each attribute at this level.
constexpr int kZstdLevel = 12;
// Version 4 extension records; the coordinate system is the one that changes what the bytes mean.
constexpr uint32_t kExtensionSafeOrbitCamera = 0xADBE0002;
constexpr uint32_t kExtensionCoordinateSystem = 0xADBE0003;
constexpr uint32_t kCoordinatesUnspecified = 0, kCoordinatesRub = 4, kCoordinatesRdf = 6;
constexpr uint8_t kFlagAntialiased = 0x1;
constexpr uint8_t kFlagHasExtensions = 0x2;
// SPZ scales the DC colour by this instead of SH_C0, so that colours a little outside [0, 1] fit.
constexpr double kColourScale = 0.15;
constexpr double kSqrtHalf = 0.70710678118654752440;
constexpr uint32_t kNineBits = (1u << 9) - 1;
constexpr int kDefaultFractionalBits = 12;
constexpr int32_t kMaxFixed24 = (1 << 23) - 1;

// SPZ stores its splats in RUB axes (x right, y up, z back: OpenGL, three.js); PLY files and the
// cloud use RDF (x right, y down, z forward: OpenCV, COLMAP). The change is a half turn about x,
// its own inverse: y and z change sign, and so do the quaternion's y and z and every SH
// coefficient whose basis function is odd in y and z together (Niantic's reference and
// splat-transform convert the same way).
constexpr float kFlipPosition[3] = {1, -1, -1};
constexpr float kFlipRotation[4] = {1, 1, -1, -1};  // w, x, y, z
constexpr float kFlipSh[15] = {-1, -1, 1,                  // degree 1: y, z, x
                               -1, 1, 1, -1, 1,            // degree 2: xy, yz, 3z^2-1, xz, x^2-y^2
                               -1, 1, -1, -1, 1, -1, 1};   // degree 3

struct Layout {
    uint64_t positions = 0, alphas = 0, colours = 0, scales = 0, rotations = 0, sh = 0, end = 0;

    // The attribute blocks in file order, as (offset, size); version 4 compresses each one that is
    // not empty as a stream of its own.
    std::array<std::pair<uint64_t, uint64_t>, 6> blocks() const {
        return {{{positions, alphas - positions},
                 {alphas, colours - alphas},
                 {colours, scales - colours},
                 {scales, rotations - scales},
                 {rotations, sh - rotations},
                 {sh, end - sh}}};
    }
};

// Byte offsets of each attribute block for n splats.
Layout layout_for(uint64_t n, uint32_t version, int sh_rest) {
    Layout layout;
    layout.positions = 0;
    layout.alphas = layout.positions + n * 9;
    layout.colours = layout.alphas + n;
    layout.scales = layout.colours + n * 3;
    layout.rotations = layout.scales + n * 3;
    layout.sh = layout.rotations + n * (version >= 3 ? 4 : 3);
    layout.end = layout.sh + n * static_cast<uint64_t>(sh_rest) * 3;
    return layout;
}

// Quaternion (x, y, z, w), unit length, from the 3-byte form of version 2 (w >= 0 implied).
std::array<double, 4> unpack_first_three(const uint8_t* bytes) {
    std::array<double, 4> q{};
    double sum = 0;
    for (size_t a = 0; a < 3; ++a) {
        q[a] = bytes[a] / 127.5 - 1.0;
        sum += q[a] * q[a];
    }
    q[3] = std::sqrt(std::max(0.0, 1.0 - sum));
    return q;
}

// Quaternion (x, y, z, w) from the "smallest three" form of version 3: the index of the largest
// component in the top two bits, then the other three (in order, first in the highest bits) as a
// sign bit and a 9-bit magnitude in units of sqrt(1/2) / 511.
std::array<double, 4> unpack_smallest_three(uint32_t packed) {
    std::array<double, 4> q{};
    const uint32_t largest = packed >> 30;
    double sum = 0;
    for (int a = 3; a >= 0; --a) {
        if (static_cast<uint32_t>(a) == largest) continue;
        const uint32_t magnitude = packed & kNineBits;
        const bool negative = (packed >> 9) & 1u;
        packed >>= 10;
        q[a] = kSqrtHalf * magnitude / kNineBits * (negative ? -1.0 : 1.0);
        sum += q[a] * q[a];
    }
    q[largest] = std::sqrt(std::max(0.0, 1.0 - sum));
    return q;
}

uint32_t pack_smallest_three(std::array<double, 4> q) {
    double norm = 0;
    for (double v : q) norm += v * v;
    norm = std::sqrt(norm);
    if (!(norm > 0) || !std::isfinite(norm)) {
        q = {0, 0, 0, 1};
        norm = 1;
    }
    for (double& v : q) v /= norm;
    uint32_t largest = 0;
    for (uint32_t a = 1; a < 4; ++a)
        if (std::abs(q[a]) > std::abs(q[largest])) largest = a;
    const bool negate = q[largest] < 0;  // q and -q are the same rotation: make the largest positive
    uint32_t packed = largest;
    for (uint32_t a = 0; a < 4; ++a) {
        if (a == largest) continue;
        const uint32_t negative = (q[a] < 0) != negate ? 1u : 0u;
        const uint32_t magnitude =
            std::min(kNineBits, static_cast<uint32_t>(kNineBits * (std::abs(q[a]) / kSqrtHalf) + 0.5));
        packed = (packed << 10) | (negative << 9) | magnitude;
    }
    return packed;
}

std::string hex(uint32_t value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08x", value);
    return text;
}

struct Header {
    uint32_t version = 0, count = 0;
    uint8_t sh_degree = 0, fractional_bits = 0, flags = 0;
};

// The fields every version's header starts with; `bytes` holds at least 16.
Header parse_header(const char* bytes, const std::string& where, const char* in_what) {
    const uint32_t magic = detail::load_little_endian<uint32_t>(bytes);
    if (magic != kMagic)
        throw InputError(where, "not an SPZ file: wrong magic " + hex(magic) + " in the " + in_what + " (expected " +
                                    hex(kMagic) + ", 'NGSP')");
    Header header;
    header.version = detail::load_little_endian<uint32_t>(bytes + 4);
    header.count = detail::load_little_endian<uint32_t>(bytes + 8);
    header.sh_degree = static_cast<uint8_t>(bytes[12]);
    header.fractional_bits = static_cast<uint8_t>(bytes[13]);
    header.flags = static_cast<uint8_t>(bytes[14]);
    if (header.version < 2 || header.version > 4)
        throw InputError(where, "unsupported SPZ version " + std::to_string(header.version) +
                                    " (versions 2, 3 and 4 are supported)");
    if (header.sh_degree > 3)
        throw InputError(where, "unsupported SH degree " + std::to_string(header.sh_degree) + " (0 to 3 are supported)");
    if (header.fractional_bits > 24)
        throw InputError(where, "has " + std::to_string(header.fractional_bits) +
                                    " fractional bits for 24-bit positions (at most 24 make sense)");
    return header;
}

Layout layout_of(const Header& header) {
    return layout_for(header.count, header.version, sh_coefficients_for_degree(header.sh_degree) - 1);
}

std::string expectation_of(const Header& header, const Layout& layout) {
    return "the header says " + std::to_string(header.count) + " splats of SH degree " +
           std::to_string(header.sh_degree) + " (" + std::to_string(layout.end) + " bytes of attributes)";
}

// Versions 2 and 3: the attributes follow the header in one gzip stream (or, accepted as well, in
// the file as it is). Files that use extensions are refused: they would follow the attributes.
std::string legacy_attributes(const std::string& file, bool gzipped, Header& header, const std::string& where) {
    std::string data;
    std::unique_ptr<detail::Inflater> inflater;
    if (gzipped) {
        inflater = std::make_unique<detail::Inflater>(file, detail::Inflater::Wrapping::gzip, where);
        inflater->read(data, kHeaderBytes);
    } else {
        data = file;
    }
    if (data.size() < kHeaderBytes)
        throw InputError(where, "truncated: the SPZ header needs 16 bytes but the data ends after " +
                                    std::to_string(data.size()));
    header = parse_header(data.data(), where, gzipped ? "decompressed header" : "header");
    if (header.version == 4)  // (a plain file of version 4 is read by v4_attributes)
        throw InputError(where, "says version 4 inside a gzip stream, but version 4 files are not gzipped");
    if (header.flags & kFlagHasExtensions)
        throw InputError(where, "uses SPZ extensions (flag 0x2), which this reader does not support before version 4");
    const Layout layout = layout_of(header);
    if (gzipped) inflater->read(data, layout.end);
    const uint64_t payload = data.size() - kHeaderBytes;
    if (payload < layout.end)
        throw InputError(where, "truncated: " + expectation_of(header, layout) + " but the " +
                                    (gzipped ? "decompressed " : "") + "data holds only " + std::to_string(payload));
    if ((gzipped && !inflater->at_end()) || payload > layout.end)
        throw InputError(where, "size does not match the header: " + expectation_of(header, layout) +
                                    " but more data follows");
    return data.substr(kHeaderBytes);
}

// Version 4's extension records ([u32 type][u32 length][payload], back to back): the coordinate
// system is honoured where it is one of the two this reader knows (RUB, SPZ's default, or RDF,
// the cloud's); the rest change nothing this reader keeps and are noted as ignored. Returns
// whether the axes are to be turned (RUB).
bool read_extensions(std::string_view records, const std::string& where, std::vector<std::string>* notes) {
    bool turn = true;
    while (!records.empty()) {
        if (records.size() < 8)
            throw InputError(where, "malformed SPZ extension records: " + std::to_string(records.size()) +
                                        " bytes left over");
        const uint32_t type = detail::load_little_endian<uint32_t>(records.data());
        const uint32_t length = detail::load_little_endian<uint32_t>(records.data() + 4);
        if (length > records.size() - 8)
            throw InputError(where, "SPZ extension " + hex(type) + " says " + std::to_string(length) +
                                        " bytes but only " + std::to_string(records.size() - 8) + " remain");
        const std::string_view payload = records.substr(8, length);
        records.remove_prefix(8 + size_t(length));
        if (type == kExtensionCoordinateSystem) {
            if (payload.size() != 4) throw InputError(where, "SPZ coordinate-system extension is not 4 bytes");
            const uint32_t system = detail::load_little_endian<uint32_t>(payload.data());
            if (system != kCoordinatesUnspecified && system != kCoordinatesRub && system != kCoordinatesRdf)
                throw InputError(where, "stores its splats in coordinate system " + std::to_string(system) +
                                            " (SPZ_ADOBE_coordinate_system); only RUB (4) and RDF (6) are read");
            turn = system != kCoordinatesRdf;
        } else if (notes) {
            notes->push_back(where + ": ignored SPZ extension " +
                             (type == kExtensionSafeOrbitCamera ? std::string("SPZ_ADOBE_safe_orbit_camera") : hex(type)));
        }
    }
    return turn;
}

// Version 4: the header, extension records up to the table of contents, the table (one entry per
// attribute block that is not empty) and the blocks' zstd frames, back to back to the file's end.
std::string v4_attributes(const std::string& file, Header& header, bool& turn, const std::string& where,
                          std::vector<std::string>* notes) {
    if (file.size() < kHeaderBytesV4)
        throw InputError(where, "truncated: the SPZ version 4 header needs 32 bytes but the file has " +
                                    std::to_string(file.size()));
    header = parse_header(file.data(), where, "header");
    const uint8_t streams = static_cast<uint8_t>(file[15]);
    const uint32_t toc = detail::load_little_endian<uint32_t>(file.data() + 16);
    if (toc < kHeaderBytesV4 || toc > file.size())
        throw InputError(where, "its table of contents starts at byte " + std::to_string(toc) + ", outside [32, " +
                                    std::to_string(file.size()) + "]");
    turn = (header.flags & kFlagHasExtensions)
               ? read_extensions(std::string_view(file).substr(kHeaderBytesV4, toc - kHeaderBytesV4), where, notes)
               : true;
    const Layout layout = layout_of(header);
    std::vector<std::pair<uint64_t, uint64_t>> blocks;
    for (const auto& block : layout.blocks())
        if (block.second) blocks.push_back(block);
    if (streams != blocks.size())
        throw InputError(where, "has " + std::to_string(streams) + " attribute streams but " +
                                    expectation_of(header, layout) + ", which are " + std::to_string(blocks.size()));
    if (uint64_t(file.size()) - toc < uint64_t(streams) * kTocEntryBytes)
        throw InputError(where, "truncated: the table of contents needs " + std::to_string(streams * kTocEntryBytes) +
                                    " bytes after byte " + std::to_string(toc));
    uint64_t offset = toc + uint64_t(streams) * kTocEntryBytes;
    std::string attributes;
    for (size_t s = 0; s < blocks.size(); ++s) {
        const char* entry = file.data() + toc + s * kTocEntryBytes;
        const auto compressed = detail::load_little_endian<uint64_t>(entry);
        const auto size = detail::load_little_endian<uint64_t>(entry + 8);
        const std::string stream = "attribute stream " + std::to_string(s);
        if (size != blocks[s].second)
            throw InputError(where, stream + " holds " + std::to_string(size) + " bytes but " +
                                        expectation_of(header, layout) + ", " + std::to_string(blocks[s].second) +
                                        " of them in this stream");
        if (compressed > file.size() - offset)
            throw InputError(where, "truncated: " + stream + " needs " + std::to_string(compressed) +
                                        " bytes but only " + std::to_string(file.size() - offset) + " remain");
        attributes += detail::zstd_decompress(std::string_view(file).substr(offset, compressed), size,
                                              where + ": " + stream);
        offset += compressed;
    }
    if (offset != file.size())
        throw InputError(where, "size does not match the table of contents: " + std::to_string(file.size() - offset) +
                                    " bytes follow the last attribute stream");
    return attributes;
}

}  // namespace

GaussianCloud read_spz(const std::filesystem::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    const std::string file = detail::read_file_bytes(path, where);

    // SPZ 2 and 3 are gzip (an uncompressed stream is accepted as well); 4 starts with its magic.
    const bool gzipped = file.size() >= 2 && static_cast<uint8_t>(file[0]) == 0x1f && static_cast<uint8_t>(file[1]) == 0x8b;
    const bool plain = file.size() >= 8 && detail::load_little_endian<uint32_t>(file.data()) == kMagic;
    if (!gzipped && !plain) {
        if (file.size() < 8)
            throw InputError(where, "truncated: " + std::to_string(file.size()) + " bytes are too few for an SPZ file");
        throw InputError(where, "not an SPZ file: wrong magic (neither gzip 1f 8b nor SPZ 'NGSP' "
                                "0x5053474e; the file starts with " +
                                    hex(detail::load_little_endian<uint32_t>(file.data())) + ")");
    }
    Header header;
    bool turn = true;  // from SPZ's RUB to the cloud's RDF
    const std::string attributes = gzipped || detail::load_little_endian<uint32_t>(file.data() + 4) != 4
                                       ? legacy_attributes(file, gzipped, header, where)
                                       : v4_attributes(file, header, turn, where, notes);

    const int sh_rest = sh_coefficients_for_degree(header.sh_degree) - 1;
    const Layout layout = layout_for(header.count, header.version, sh_rest);
    const auto* body = reinterpret_cast<const uint8_t*>(attributes.data());
    const size_t count = header.count;
    const int fractional_bits = header.fractional_bits;
    const auto flip = [turn](float sign) { return turn ? sign : 1.0f; };
    GaussianCloud cloud;
    cloud.sh_degree = header.sh_degree;
    cloud.resize(count);
    const size_t coefficients = static_cast<size_t>(sh_rest + 1);
    for (size_t i = 0; i < count; ++i) {
        for (size_t a = 0; a < 3; ++a) {
            const uint8_t* p = body + layout.positions + i * 9 + a * 3;
            int32_t fixed = static_cast<int32_t>(p[0] | (p[1] << 8) | (p[2] << 16));
            if (fixed & 0x800000) fixed -= 0x1000000;  // sign extension
            cloud.positions[i * 3 + a] =
                flip(kFlipPosition[a]) * static_cast<float>(std::ldexp(static_cast<double>(fixed), -fractional_bits));
            cloud.log_scales[i * 3 + a] = static_cast<float>(body[layout.scales + i * 3 + a] / 16.0 - 10.0);
            cloud.sh[i * coefficients * 3 + a] =
                static_cast<float>((body[layout.colours + i * 3 + a] / 255.0 - 0.5) / kColourScale);
        }
        cloud.opacity_logits[i] = detail::logit_of(body[layout.alphas + i] / 255.0);
        const std::array<double, 4> q =
            header.version >= 3 ? unpack_smallest_three(detail::load_little_endian<uint32_t>(
                                      reinterpret_cast<const char*>(body + layout.rotations + i * 4)))
                                : unpack_first_three(body + layout.rotations + i * 3);
        cloud.rotations[i * 4 + 0] = static_cast<float>(q[3]);  // SPZ is x, y, z, w; the cloud w, x, y, z
        for (size_t a = 0; a < 3; ++a)
            cloud.rotations[i * 4 + 1 + a] = flip(kFlipRotation[1 + a]) * static_cast<float>(q[a]);
        // SPZ's SH are [coefficient][rgb] without the DC term, like the cloud's after it.
        const uint8_t* sh = body + layout.sh + i * static_cast<size_t>(sh_rest) * 3;
        for (size_t k = 0; k < static_cast<size_t>(sh_rest) * 3; ++k)
            cloud.sh[i * coefficients * 3 + 3 + k] = flip(kFlipSh[k / 3]) * static_cast<float>((sh[k] - 128.0) / 128.0);
    }
    if (notes && (header.flags & kFlagAntialiased))
        notes->push_back(where + ": flagged antialiased (trained with an anti-aliasing filter); it is rendered "
                                 "without one");
    return cloud;
}

void write_spz(const GaussianCloud& cloud, const std::filesystem::path& path, WriteMode mode, int version) {
    const std::string where = path.string();
    if (version != 3 && version != 4)
        throw InputError(where, "cannot write SPZ version " + std::to_string(version) + " (3 and 4 are written)");
    detail::check_writable(cloud, where);
    if (cloud.size() > UINT32_MAX)
        throw InputError(where, "cannot write " + std::to_string(cloud.size()) + " splats (SPZ holds at most 2^32 - 1)");

    double largest = 0;
    for (size_t i = 0; i < cloud.positions.size(); ++i) {
        const double v = cloud.positions[i];
        if (!std::isfinite(v))
            throw InputError(where, "cannot write Gaussian " + std::to_string(i / 3) +
                                        ": its position is not finite (sanitize() the cloud first)");
        largest = std::max(largest, std::abs(v));
    }
    int fractional_bits = kDefaultFractionalBits;
    while (fractional_bits > 0 && std::round(std::ldexp(largest, fractional_bits)) > kMaxFixed24) --fractional_bits;
    if (std::round(largest) > kMaxFixed24)
        throw InputError(where, "cannot write a coordinate of magnitude " + std::to_string(largest) +
                                    ": SPZ positions are 24-bit fixed point (at most 2^23 - 1)");

    const size_t n = cloud.size();
    const int sh_rest = cloud.sh_coefficients() - 1;
    const size_t coefficients = static_cast<size_t>(sh_rest + 1);
    const Layout layout = layout_for(n, static_cast<uint32_t>(version), sh_rest);
    std::string attributes(layout.end, '\0');
    auto* body = reinterpret_cast<uint8_t*>(attributes.data());
    for (size_t i = 0; i < n; ++i) {
        for (size_t a = 0; a < 3; ++a) {
            const auto fixed = static_cast<int32_t>(
                std::round(std::ldexp(double(kFlipPosition[a] * cloud.positions[i * 3 + a]), fractional_bits)));
            uint8_t* p = body + layout.positions + i * 9 + a * 3;
            p[0] = static_cast<uint8_t>(fixed & 0xff);
            p[1] = static_cast<uint8_t>((fixed >> 8) & 0xff);
            p[2] = static_cast<uint8_t>((fixed >> 16) & 0xff);
            body[layout.scales + i * 3 + a] = detail::to_byte((cloud.log_scales[i * 3 + a] + 10.0) * 16.0);
            body[layout.colours + i * 3 + a] =
                detail::to_byte(cloud.sh[i * coefficients * 3 + a] * (kColourScale * 255.0) + 0.5 * 255.0);
        }
        body[layout.alphas + i] = detail::to_byte(detail::sigmoid(cloud.opacity_logits[i]) * 255.0);
        const float* r = cloud.rotations.data() + i * 4;
        const uint32_t packed = pack_smallest_three(
            {kFlipRotation[1] * r[1], kFlipRotation[2] * r[2], kFlipRotation[3] * r[3], r[0]});
        for (size_t b = 0; b < 4; ++b) body[layout.rotations + i * 4 + b] = static_cast<uint8_t>(packed >> (8 * b));
        uint8_t* sh = body + layout.sh + i * static_cast<size_t>(sh_rest) * 3;
        for (size_t k = 0; k < static_cast<size_t>(sh_rest) * 3; ++k)
            sh[k] = detail::to_byte(kFlipSh[k / 3] * cloud.sh[i * coefficients * 3 + 3 + k] * 128.0 + 128.0);
    }

    std::string header;
    detail::store_little_endian(header, kMagic);
    detail::store_little_endian(header, static_cast<uint32_t>(version));
    detail::store_little_endian(header, static_cast<uint32_t>(n));
    header += static_cast<char>(cloud.sh_degree);
    header += static_cast<char>(fractional_bits);
    header += '\0';  // flags: not antialiased, no extensions
    std::string file;
    if (version == 3) {
        header += '\0';  // reserved
        file = detail::deflate_bytes(header + attributes, detail::Inflater::Wrapping::gzip, where);
    } else {
        std::vector<std::string> streams;
        for (const auto& [offset, size] : layout.blocks())
            if (size) streams.push_back(detail::zstd_compress(std::string_view(attributes).substr(offset, size), kZstdLevel, where));
        header += static_cast<char>(streams.size());
        detail::store_little_endian(header, static_cast<uint32_t>(kHeaderBytesV4));  // no extensions: the table follows
        header.resize(kHeaderBytesV4, '\0');                                         // reserved
        file = header;
        size_t stream = 0;
        for (const auto& [offset, size] : layout.blocks()) {
            if (!size) continue;
            detail::store_little_endian(file, static_cast<uint64_t>(streams[stream++].size()));
            detail::store_little_endian(file, static_cast<uint64_t>(size));
        }
        for (const auto& compressed : streams) file += compressed;
    }
    write_file_atomically(path, mode, [&](std::ostream& out) {
        out.write(file.data(), static_cast<std::streamsize>(file.size()));
    });
}

}  // namespace vksplat::io
