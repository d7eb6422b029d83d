#pragma once
// What the SOG reader and writer share: PlayCanvas's SOG version 2, a meta.json and WebP textures
// (in a folder, or in a zip named .sog), as splat-transform 2.x and the PlayCanvas engine read and
// write it. Every per-splat texture holds splat i at texel i (row-major), 4 bytes a texel:
//   means_l.webp, means_u.webp  low and high bytes of x, y, z in 16 bits (alpha 255): each axis
//                               log-encoded, v = sign(x) ln(|x| + 1), then spread over
//                               meta.means.mins .. maxs
//   quats.webp                  the quaternion (w, x, y, z), unit length with its largest component
//                               positive, as the other three times sqrt(2) in [-1, 1] to bytes
//                               (255 (v + 1) / 2) and alpha 252 + the largest's index
//   scales.webp                 indices into meta.scales.codebook (256 log scales) for x, y, z
//   sh0.webp                    indices into meta.sh0.codebook (256 f_dc values) for r, g, b, and
//                               the opacity, sigmoid(logit) * 255, in alpha
//   shN_labels.webp             (SH degree above 0) the splat's palette entry, 16 bits in r and g
// and one texture per palette:
//   shN_centroids.webp          64 entries a row, each entry `coefficients` texels wide (3, 8 or 15:
//                               degree 1 to 3 without the DC term), each texel the r, g, b of one
//                               coefficient as indices into meta.shN.codebook (256 values)
// Positions, rotations and SH are in the PLY's axes: no axis is turned, unlike SPZ.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace vksplat::io::detail::sog {

inline constexpr int kVersion = 2;
inline constexpr const char* kMetaName = "meta.json";
// Every texture a SOG may have, in the order above.
inline constexpr const char* kTextureNames[] = {"means_l.webp", "means_u.webp", "quats.webp", "scales.webp",
                                                "sh0.webp", "shN_labels.webp", "shN_centroids.webp"};
inline constexpr int kCodebookSize = 256;
inline constexpr int kPaletteEntriesPerRow = 64;
// The alpha of quats.webp: 252 plus the index (w, x, y, z) of the component left out.
inline constexpr int kQuaternionTagBase = 252;
inline constexpr double kSqrt2 = 1.4142135623730951;

// The per-splat textures' side, as splat-transform chooses it: both sides multiples of 4 (the
// engine's texture blocks), near square. An empty scene still gets 4x4: WebP has no empty image.
struct TextureSize {
    int width = 4;
    int height = 4;
};
inline TextureSize texture_size(size_t splats) {
    if (splats == 0) return {};
    const size_t width = (static_cast<size_t>(std::ceil(std::sqrt(double(splats)) / 4.0))) * 4;
    const size_t height = ((splats + width - 1) / width + 3) / 4 * 4;
    return {static_cast<int>(width), static_cast<int>(height)};
}

// SH coefficients a colour has above the DC term, for SH degree (bands) 1 to 3.
inline constexpr int rest_coefficients(int bands) { return (bands + 1) * (bands + 1) - 1; }

// A path named meta.json (any case) is a SOG's folder layout: its textures beside it. Any other
// name is the zip.
inline bool is_meta_json(const std::filesystem::path& path) {
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    return name == kMetaName;
}

// The files a SOG written to `path` may take: the .sog, or meta.json and every texture beside it.
inline std::vector<std::filesystem::path> output_files(const std::filesystem::path& path) {
    std::vector<std::filesystem::path> files{path};
    if (is_meta_json(path))
        for (const char* name : kTextureNames) files.push_back(path.parent_path() / name);
    return files;
}

inline double log_encode(double x) { return std::copysign(std::log1p(std::abs(x)), x); }
inline double log_decode(double v) { return std::copysign(std::expm1(std::abs(v)), v); }

}  // namespace vksplat::io::detail::sog
