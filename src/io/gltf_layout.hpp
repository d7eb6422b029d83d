#pragma once
// What the .glb reader and writer share: the GLB container's constants and the attribute names of
// glTF's KHR_gaussian_splatting (Khronos draft, ellipse kernel). The extension stores linear
// scales, opacities after the sigmoid, unit quaternions in glTF's x, y, z, w order and the raw SH
// coefficients (f_dc, f_rest) per degree and order, one VEC3 (r, g, b) attribute each.
#include <array>
#include <cstdint>
#include <string>

namespace vksplat::io::detail::gltf {

inline constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
inline constexpr uint32_t kVersion = 2;
inline constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
inline constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
inline constexpr size_t kHeaderBytes = 12, kChunkHeaderBytes = 8;

inline constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kFloat = 5126;
inline constexpr int kModePoints = 0;
inline constexpr int kTargetArrayBuffer = 34962;

inline constexpr const char* kExtension = "KHR_gaussian_splatting";
inline constexpr const char* kRotation = "KHR_gaussian_splatting:ROTATION";
inline constexpr const char* kScale = "KHR_gaussian_splatting:SCALE";
inline constexpr const char* kOpacity = "KHR_gaussian_splatting:OPACITY";

// glTF's axes are y up, z forward (x left as the viewer sees the front), where the PLY and the cloud
// hold COLMAP's RDF (x right, y down, z forward): the extension asks for glTF's axes, and
// splat-transform writes them, PlayCanvas reads them, so. The change is a half turn about z, its
// own inverse for positions and SH: x and y change sign, and so does every SH coefficient whose
// basis function is odd in x and y together. Each quaternion q becomes t q, t the half turn
// (0, 0, 1; 0), as splat-transform turns them (t q t* would describe the same Gaussian, with its
// own axes turned), and t* q' turns it back.
inline constexpr float kTurnPosition[3] = {-1, -1, 1};
// Our q = (w, x, y, z) to glTF's (x, y, z, w) of t q.
inline std::array<float, 4> turned_to_gltf(float w, float x, float y, float z) { return {-y, x, w, -z}; }
// glTF's q' = (x, y, z, w) to our (w, x, y, z) of t* q'.
inline std::array<float, 4> turned_from_gltf(float x, float y, float z, float w) { return {z, y, -x, -w}; }
inline constexpr float kTurnSh[15] = {-1, 1, -1,                 // degree 1: y, z, x
                                      1, -1, 1, -1, 1,           // degree 2: xy, yz, 3z^2-1, xz, x^2-y^2
                                      -1, 1, -1, 1, -1, 1, -1};  // degree 3

// SH coefficient `order` (0 .. 2 * degree, that is m = order - degree) of `degree`: the cloud's
// coefficient degree * degree + order, as in the INRIA PLY (whose band order is the same m order).
inline std::string sh_attribute(int degree, int order) {
    return "KHR_gaussian_splatting:SH_DEGREE_" + std::to_string(degree) + "_COEF_" + std::to_string(order);
}

}  // namespace vksplat::io::detail::gltf
