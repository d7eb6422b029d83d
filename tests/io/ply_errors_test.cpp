// Malformed PLY files: each error names the file and says what is wrong.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "io/ply_test_writer.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

std::vector<HandProperty> float_properties(const std::vector<std::string>& names) {
    std::vector<HandProperty> properties;
    for (const auto& name : names) properties.push_back({"float", name});
    return properties;
}

std::vector<std::vector<double>> zero_rows(size_t count, size_t values, double value = 0.0) {
    return std::vector<std::vector<double>>(count, std::vector<double>(values, value));
}

std::string standard_ply(PlyFormat format, size_t count, double value = 0.0) {
    const auto names = inria_names(0);
    return hand_made_ply(format, float_properties(names), zero_rows(count, names.size(), value));
}

TEST(PlyErrors, MissingFile) {
    ScratchDir dir;
    expect_input_error([&] { read_ply(dir / "absent.ply"); }, {"absent.ply", "no such file"});
}

TEST(PlyErrors, BadMagic) {
    ScratchDir dir;
    write_bytes(dir / "bad.ply", "plx\nformat ascii 1.0\nend_header\n");
    expect_input_error([&] { read_ply(dir / "bad.ply"); }, {"bad.ply", "not a PLY file"});
}

TEST(PlyErrors, MissingEndHeader) {
    ScratchDir dir;
    write_bytes(dir / "open.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n");
    expect_input_error([&] { read_ply(dir / "open.ply"); }, {"open.ply", "no end_header"});
}

TEST(PlyErrors, UnsupportedFormat) {
    ScratchDir dir;
    write_bytes(dir / "odd.ply", "ply\nformat binary_middle_endian 1.0\nelement vertex 0\nend_header\n");
    expect_input_error([&] { read_ply(dir / "odd.ply"); }, {"odd.ply", "unsupported format 'binary_middle_endian'"});
}

TEST(PlyErrors, MissingRequiredPropertyIsNamed) {
    ScratchDir dir;
    auto names = inria_names(0);
    names.erase(std::find(names.begin(), names.end(), "rot_3"));
    write_bytes(dir / "norot.ply",
                hand_made_ply(PlyFormat::little_endian, float_properties(names), zero_rows(2, names.size())));
    expect_input_error([&] { read_ply(dir / "norot.ply"); },
                       {"norot.ply", "element 'vertex'", "missing required property rot_3"});
}

TEST(PlyErrors, WrongFRestCountIsNamed) {
    ScratchDir dir;
    auto names = inria_names(0);
    for (int i = 0; i < 7; ++i) names.push_back("f_rest_" + std::to_string(i));
    write_bytes(dir / "rest7.ply",
                hand_made_ply(PlyFormat::little_endian, float_properties(names), zero_rows(1, names.size())));
    expect_input_error([&] { read_ply(dir / "rest7.ply"); }, {"rest7.ply", "7 f_rest_* properties", "0, 9, 24 or 45"});
}

TEST(PlyErrors, GapInFRestIndices) {
    ScratchDir dir;
    auto names = inria_names(1);
    *std::find(names.begin(), names.end(), "f_rest_4") = "f_rest_12";
    write_bytes(dir / "gap.ply",
                hand_made_ply(PlyFormat::little_endian, float_properties(names), zero_rows(1, names.size())));
    expect_input_error([&] { read_ply(dir / "gap.ply"); }, {"gap.ply", "f_rest_12"});
}

TEST(PlyErrors, TruncatedBinaryBody) {
    ScratchDir dir;
    std::string file = standard_ply(PlyFormat::little_endian, 10);
    file.resize(file.size() - 100);
    write_bytes(dir / "cut.ply", file);
    // 14 floats = 56 bytes a vertex: 460 bytes remain, the file ends inside vertex 8.
    expect_input_error([&] { read_ply(dir / "cut.ply"); }, {"cut.ply", "element 'vertex'", "truncated",
                                                            "10 vertices expected", "only 460 bytes", "vertex 8"});
}

TEST(PlyErrors, TruncatedAsciiBody) {
    ScratchDir dir;
    std::string file = standard_ply(PlyFormat::ascii, 4);
    file.resize(file.rfind('\n', file.size() - 2) + 1);  // drop the last line
    write_bytes(dir / "cut.ply", file);
    expect_input_error([&] { read_ply(dir / "cut.ply"); }, {"cut.ply", "truncated", "4 vertices expected", "84 bytes"});
}

// A header that declares fewer vertices than the body holds: reading only those would lose the
// rest with no word.
TEST(PlyErrors, MoreVerticesThanTheHeaderDeclares) {
    ScratchDir dir;
    for (const auto format : {PlyFormat::little_endian, PlyFormat::ascii}) {
        std::string file = standard_ply(format, 5);
        const std::string declared = "element vertex 5\n";
        file.replace(file.find(declared), declared.size(), "element vertex 2\n");
        write_bytes(dir / "more.ply", file);
        // 14 floats = 56 bytes a vertex; ASCII: one line each.
        const std::string amount = format == PlyFormat::ascii ? "3 more lines (from line 22)" : "168 bytes";
        expect_input_error([&] { read_ply(dir / "more.ply"); },
                           {"more.ply", amount, "follow the end of the body the header declares (2 vertices)"});
    }
    std::string file = standard_ply(PlyFormat::little_endian, 5);
    file.replace(file.find("element vertex 5\n"), 17, "element vertex 2\n");
    write_bytes(dir / "more.ply", file + "xy");
    expect_input_error([&] { read_ply(dir / "more.ply"); },
                       {"more.ply", "170 bytes", "room for 3 more vertices of 56 bytes and 2 bytes more"});
}

TEST(PlyErrors, AbsurdVertexCount) {
    ScratchDir dir;
    for (const auto format : {PlyFormat::little_endian, PlyFormat::ascii}) {
        std::string file = standard_ply(format, 3);
        const std::string declared = "element vertex 3\n";
        file.replace(file.find(declared), declared.size(), "element vertex 123456789012345\n");
        write_bytes(dir / "huge.ply", file);
        expect_input_error([&] { read_ply(dir / "huge.ply"); }, {"huge.ply", "123456789012345", "absurd"});
    }
}

TEST(PlyErrors, VertexCountOverflowingSixtyFourBits) {
    ScratchDir dir;
    std::string file = standard_ply(PlyFormat::little_endian, 1);
    const std::string declared = "element vertex 1\n";
    file.replace(file.find(declared), declared.size(), "element vertex 99999999999999999999999\n");
    write_bytes(dir / "overflow.ply", file);
    expect_input_error([&] { read_ply(dir / "overflow.ply"); }, {"overflow.ply", "element 'vertex'", "64 bits"});
}

TEST(PlyErrors, AsciiLineWithTooFewValuesGivesItsLineNumber) {
    ScratchDir dir;
    std::string file = standard_ply(PlyFormat::ascii, 3, 0.125);
    // The third vertex loses its last value. Header: ply, format, comment, element, 14 properties,
    // end_header = 19 lines, so the vertices are lines 20 to 22.
    file.resize(file.rfind(' '));
    file += "\n";
    write_bytes(dir / "short.ply", file);
    expect_input_error([&] { read_ply(dir / "short.ply"); },
                       {"short.ply", "line 22", "vertex 2", "13 values, expected 14", "too few values"});
}

TEST(PlyErrors, AsciiValueThatIsNotANumber) {
    ScratchDir dir;
    std::string file = standard_ply(PlyFormat::ascii, 1);
    file.replace(file.rfind("0 "), 1, "zero");
    write_bytes(dir / "word.ply", file);
    expect_input_error([&] { read_ply(dir / "word.ply"); }, {"word.ply", "line 20", "'zero' is not a number"});
}

TEST(PlyErrors, NoVertexElement) {
    ScratchDir dir;
    write_bytes(dir / "faces.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int v\nend_header\n");
    expect_input_error([&] { read_ply(dir / "faces.ply"); }, {"faces.ply", "no 'vertex' element"});
}

TEST(PlyErrors, ListPropertyInTheVertices) {
    ScratchDir dir;
    const std::string file = "ply\nformat ascii 1.0\nelement vertex 1\n" +
                             property_lines(float_properties(inria_names(0))) +
                             "property list uchar int neighbours\nend_header\n";
    write_bytes(dir / "list.ply", file);
    expect_input_error([&] { read_ply(dir / "list.ply"); },
                       {"list.ply", "list property 'neighbours' is not supported"});
}

TEST(PlyErrors, TruncatedElementBeforeTheVertices) {
    ScratchDir dir;
    const auto names = inria_names(0);
    const std::string file =
        "ply\nformat binary_little_endian 1.0\nelement strip 3\nproperty list uchar int i\n"
        "element vertex 1\n" +
        property_lines(float_properties(names)) + "end_header\n" + encode_value(200, "uchar", false) +
        std::string(40, '\0');
    write_bytes(dir / "strip.ply", file);
    expect_input_error([&] { read_ply(dir / "strip.ply"); },
                       {"strip.ply", "element 'strip'", "truncated", "item 0 of 3"});
}

}  // namespace
}  // namespace vksplat::io::test
