#pragma once
// PlayCanvas's compressed PLY, as its reader (compressed_ply.cpp) and writer
// (compressed_ply_write.cpp) both name it: splats in chunks of 256, each chunk giving the range of
// its positions and log scales (and, in all but the oldest files, colours), each splat packing its
// values into 32-bit words relative to its chunk's range.
#include <cstddef>

namespace vksplat::io::compressed_ply {

inline constexpr size_t kChunkSize = 256;
inline constexpr const char* kChunkGeometryFields[] = {"min_x",       "min_y",       "min_z",       "max_x",
                                                       "max_y",       "max_z",       "min_scale_x", "min_scale_y",
                                                       "min_scale_z", "max_scale_x", "max_scale_y", "max_scale_z"};
inline constexpr const char* kChunkColourFields[] = {"min_r", "min_g", "min_b", "max_r", "max_g", "max_b"};
inline constexpr const char* kVertexFields[] = {"packed_position", "packed_rotation", "packed_scale", "packed_color"};

}  // namespace vksplat::io::compressed_ply
