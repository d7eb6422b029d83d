#pragma once
// NumPy .npy files (format version 1.0, C order, little-endian) for stage outputs, so that Python
// users can open them with one call to numpy.load.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "vksplat/error.hpp"
#include "vksplat/io/write_mode.hpp"

namespace vksplat::io {

enum class NpyDtype { float32, int32, int16, uint8, uint32 };

// "float32", "int32", ...
std::string to_string(NpyDtype dtype);
size_t npy_dtype_size(NpyDtype dtype);

template <typename T>
struct NpyDtypeOf;
template <>
struct NpyDtypeOf<float> {
    static constexpr NpyDtype value = NpyDtype::float32;
};
template <>
struct NpyDtypeOf<int32_t> {
    static constexpr NpyDtype value = NpyDtype::int32;
};
template <>
struct NpyDtypeOf<int16_t> {
    static constexpr NpyDtype value = NpyDtype::int16;
};
template <>
struct NpyDtypeOf<uint8_t> {
    static constexpr NpyDtype value = NpyDtype::uint8;
};
template <>
struct NpyDtypeOf<uint32_t> {
    static constexpr NpyDtype value = NpyDtype::uint32;
};

// The element types a .npy file may hold here.
template <typename T>
concept NpyElement = requires {
    NpyDtypeOf<T>::value;
};

struct NpyArray {
    std::filesystem::path path;  // the file it came from, for messages
    NpyDtype dtype = NpyDtype::float32;
    std::vector<size_t> shape;    // empty for a scalar
    std::vector<std::byte> data;  // C order, host byte order

    size_t element_count() const {
        size_t count = 1;
        for (size_t extent : shape) count *= extent;
        return count;
    }

    // The elements as T; throws InputError naming the file if the array holds another type.
    template <NpyElement T>
    std::vector<T> values() const {
        if (dtype != NpyDtypeOf<T>::value)
            throw InputError(path.string(),
                             "holds " + to_string(dtype) + " values, expected " + to_string(NpyDtypeOf<T>::value));
        std::vector<T> result(element_count());
        if (!result.empty()) std::memcpy(result.data(), data.data(), result.size() * sizeof(T));
        return result;
    }
};

// Writes `data`, which holds the product of `shape` elements in C order.
void write_npy_bytes(const std::filesystem::path& path, NpyDtype dtype, const void* data,
                     const std::vector<size_t>& shape, WriteMode mode = WriteMode::refuse_existing);

template <NpyElement T>
void write_npy(const std::filesystem::path& path, const T* data, const std::vector<size_t>& shape,
               WriteMode mode = WriteMode::refuse_existing) {
    write_npy_bytes(path, NpyDtypeOf<T>::value, data, shape, mode);
}

// Reads format versions 1.0 to 3.0 of the dtypes above. Throws InputError naming the file for a bad
// magic string, an unsupported dtype, Fortran order, big-endian data or a truncated body.
NpyArray read_npy(const std::filesystem::path& path);

}  // namespace vksplat::io
