#pragma once
// Loading scalars of either byte order from unaligned bytes: PLY bodies may be big-endian, and
// binary formats pack fields with no alignment.
#include <bit>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace vksplat::io::detail {

template <typename T>
T load_scalar(const char* bytes, bool swap) {
    static_assert(std::is_arithmetic_v<T>);
    if (!swap) {
        T value;
        std::memcpy(&value, bytes, sizeof(T));
        return value;
    }
    char reversed[sizeof(T)];
    for (size_t i = 0; i < sizeof(T); ++i) reversed[i] = bytes[sizeof(T) - 1 - i];
    T value;
    std::memcpy(&value, reversed, sizeof(T));
    return value;
}

// Files we write and most we read are little-endian; loads from them swap on big-endian hosts.
inline constexpr bool kHostIsLittleEndian = std::endian::native == std::endian::little;

template <typename T>
T load_little_endian(const char* bytes) {
    return load_scalar<T>(bytes, !kHostIsLittleEndian);
}

}  // namespace vksplat::io::detail
