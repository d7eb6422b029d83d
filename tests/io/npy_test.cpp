// .npy files: round trips for every dtype and shape, the header NumPy expects, and bad files.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/npy.hpp"

namespace vksplat::io::test {
namespace {

template <typename T>
void expect_round_trip(const std::vector<size_t>& shape) {
    ScratchDir dir;
    size_t count = 1;
    for (size_t extent : shape) count *= extent;
    std::vector<T> values(count);
    for (size_t i = 0; i < count; ++i) values[i] = static_cast<T>(i * 7 % 251) - static_cast<T>(i % 3);
    write_npy(dir / "a.npy", values.data(), shape);
    const NpyArray array = read_npy(dir / "a.npy");
    EXPECT_EQ(array.dtype, NpyDtypeOf<T>::value);
    EXPECT_EQ(array.shape, shape);
    EXPECT_EQ(array.element_count(), count);
    EXPECT_EQ(array.values<T>(), values);
}

TEST(Npy, RoundTripsEveryDtypeAndShape) {
    for (const std::vector<size_t>& shape :
         std::vector<std::vector<size_t>>{{}, {0}, {5}, {2, 3, 4}, {1, 1, 1, 1, 3}}) {
        SCOPED_TRACE(shape.size());
        expect_round_trip<float>(shape);
        expect_round_trip<int32_t>(shape);
        expect_round_trip<int16_t>(shape);
        expect_round_trip<uint8_t>(shape);
        expect_round_trip<uint32_t>(shape);
    }
}

TEST(Npy, HeaderIsWhatNumPyWrites) {
    ScratchDir dir;
    const float values[6] = {1, 2, 3, 4, 5, 6};
    write_npy(dir / "a.npy", values, {2, 3});
    const std::string bytes = read_bytes(dir / "a.npy");
    ASSERT_GE(bytes.size(), 10u);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
    const size_t header_length = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
    EXPECT_EQ((10 + header_length) % 64, 0u);  // data aligned as NumPy aligns it
    const std::string header = bytes.substr(10, header_length);
    EXPECT_EQ(header.rfind("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", 0), 0u) << header;
    EXPECT_EQ(header.back(), '\n');
    EXPECT_EQ(bytes.size(), 10 + header_length + sizeof values);

    const uint8_t bytes_in[2] = {1, 2};
    write_npy(dir / "u.npy", bytes_in, {2});
    EXPECT_NE(read_bytes(dir / "u.npy").find("{'descr': '|u1', 'fortran_order': False, 'shape': (2,), }"),
              std::string::npos);
}

// A file as NumPy 1.x writes np.arange(3, dtype='<i2'), plus variations of its header.
std::string numpy_file(const std::string& dict, const std::string& data) {
    std::string header = dict;
    header.append(63 - (10 + header.size()) % 64, ' ');
    header += '\n';
    return std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(header.size() & 0xff) +
           static_cast<char>(header.size() >> 8) + header + data;
}

const std::string kShortData("\x00\x00\x01\x00\x02\x00", 6);

TEST(Npy, ReadsAFileWrittenByNumPy) {
    ScratchDir dir;
    write_bytes(dir / "n.npy", numpy_file("{'descr': '<i2', 'fortran_order': False, 'shape': (3,), }", kShortData));
    const NpyArray array = read_npy(dir / "n.npy");
    EXPECT_EQ(array.dtype, NpyDtype::int16);
    EXPECT_EQ(array.values<int16_t>(), (std::vector<int16_t>{0, 1, 2}));
    expect_input_error([&] { array.values<float>(); }, {"n.npy", "holds int16 values, expected float32"});
}

TEST(Npy, Errors) {
    ScratchDir dir;
    const auto path = dir / "bad.npy";
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "no such file"});

    write_bytes(path, "PK\x03\x04 not numpy at all");
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "bad magic"});

    write_bytes(path, numpy_file("{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }", std::string(24, '\0')));
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "unsupported dtype '<f8'"});

    write_bytes(path, numpy_file("{'descr': '>f4', 'fortran_order': False, 'shape': (3,), }", std::string(12, '\0')));
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "big-endian"});

    write_bytes(path, numpy_file("{'descr': '<i2', 'fortran_order': True, 'shape': (3,), }", kShortData));
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "Fortran order"});

    write_bytes(path, numpy_file("{'descr': '<i2', 'fortran_order': False, 'shape': (3, 2), }", kShortData));
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "truncated", "(3, 2)", "needs 12 bytes", "has 6"});

    write_bytes(path,
                numpy_file("{'descr': '<i2', 'fortran_order': False, 'shape': (99999999999, 99999999999), }", ""));
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "overflows"});

    write_bytes(path, numpy_file("{'descr': '<i2', 'fortran_order': False, }", kShortData));
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "no 'shape' entry"});

    std::string version9 = numpy_file("{'descr': '<i2', 'fortran_order': False, 'shape': (3,), }", kShortData);
    version9[6] = 9;
    write_bytes(path, version9);
    expect_input_error([&] { read_npy(path); }, {"bad.npy", "version 9.0"});
}

TEST(Npy, WriteRefusesToOverwriteUnlessAsked) {
    ScratchDir dir;
    const int32_t first[1] = {1}, second[2] = {2, 3};
    write_npy(dir / "a.npy", first, {1});
    expect_input_error([&] { write_npy(dir / "a.npy", second, {2}); }, {"a.npy", "already exists"});
    EXPECT_EQ(read_npy(dir / "a.npy").values<int32_t>(), std::vector<int32_t>{1});
    write_npy(dir / "a.npy", second, {2}, WriteMode::overwrite);
    EXPECT_EQ(read_npy(dir / "a.npy").values<int32_t>(), (std::vector<int32_t>{2, 3}));
}

}  // namespace
}  // namespace vksplat::io::test
