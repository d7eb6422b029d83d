// PLY reading and writing on generated clouds: round trips, other formats and property orders,
// the f_rest layout, and elements around the vertex element.
#include <gtest/gtest.h>

#include <algorithm>

#include "io/io_test_helpers.hpp"
#include "io/ply_test_writer.hpp"
#include "vksplat/io/ply.hpp"

namespace vksplat::io::test {
namespace {

class PlyRoundTrip : public ::testing::TestWithParam<int> {};

TEST_P(PlyRoundTrip, BinaryWriteThenReadGivesTheSameCloud) {
    ScratchDir dir;
    const GaussianCloud cloud = random_cloud(257, GetParam());
    write_ply(cloud, dir / "cloud.ply");
    std::vector<std::string> notes;
    const GaussianCloud read = read_ply(dir / "cloud.ply", &notes);
    expect_same_cloud(cloud, read);
    ASSERT_EQ(notes.size(), 1u);  // the normals the writer adds
    EXPECT_NE(notes[0].find("nx, ny, nz"), std::string::npos) << notes[0];
}

INSTANTIATE_TEST_SUITE_P(ShDegrees, PlyRoundTrip, ::testing::Values(0, 1, 2, 3));

TEST(Ply, WriterUsesTheStandardPropertyOrder) {
    ScratchDir dir;
    write_ply(random_cloud(2, 1), dir / "cloud.ply");
    const std::string bytes = read_bytes(dir / "cloud.ply");
    std::vector<std::string> expected = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
    for (int i = 0; i < 9; ++i) expected.push_back("f_rest_" + std::to_string(i));
    for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
        expected.push_back(name);
    std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 2\n";
    for (const auto& name : expected) header += "property float " + name + "\n";
    header += "end_header\n";
    ASSERT_EQ(bytes.substr(0, header.size()), header);
    EXPECT_EQ(bytes.size(), header.size() + 2 * expected.size() * sizeof(float));
}

TEST(Ply, EmptyCloudRoundTrips) {
    ScratchDir dir;
    GaussianCloud empty;
    empty.sh_degree = 3;
    write_ply(empty, dir / "empty.ply");
    const GaussianCloud read = read_ply(dir / "empty.ply");
    EXPECT_EQ(read.size(), 0u);
    EXPECT_EQ(read.sh_degree, 3);
}

// The same cloud as ASCII and as big-endian binary, properties shuffled and of mixed types.
class PlyOtherFormats : public ::testing::TestWithParam<PlyFormat> {};

TEST_P(PlyOtherFormats, DecodeToTheSameCloud) {
    ScratchDir dir;
    GaussianCloud cloud = random_cloud(20, 2, 7);
    // Opacity stored as double and x as int: small integers survive every type exactly.
    for (size_t i = 0; i < cloud.size(); ++i) cloud.positions[i * 3] = static_cast<float>(static_cast<int>(i) - 10);

    std::vector<std::string> names = inria_names(2);
    names.push_back("nx");
    names.push_back("red");
    std::reverse(names.begin(), names.end());
    std::rotate(names.begin(), names.begin() + 7, names.end());
    std::vector<HandProperty> properties;
    for (const auto& name : names)
        properties.push_back({name == "opacity" ? "double"
                              : name == "x"     ? "int"
                              : name == "red"   ? "uchar"
                                                : "float",
                              name});
    std::vector<std::vector<double>> rows;
    for (size_t i = 0; i < cloud.size(); ++i) {
        auto values = inria_values(cloud, i);
        values["nx"] = 0.5;
        values["red"] = 200;
        std::vector<double> row;
        for (const auto& name : names) row.push_back(values.at(name));
        rows.push_back(row);
    }
    write_bytes(dir / "other.ply", hand_made_ply(GetParam(), properties, rows));

    std::vector<std::string> notes;
    const GaussianCloud read = read_ply(dir / "other.ply", &notes);
    expect_same_cloud(cloud, read);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("red, nx"), std::string::npos) << notes[0];
}

INSTANTIATE_TEST_SUITE_P(Formats, PlyOtherFormats, ::testing::Values(PlyFormat::ascii, PlyFormat::big_endian));

// f_rest_k = 100 + k for degree 1: red holds 100..102, green 103..105, blue 106..108.
TEST(Ply, FRestIsChannelMajorInTheFile) {
    ScratchDir dir;
    std::vector<HandProperty> properties;
    std::vector<double> row;
    for (const auto& name : inria_names(1)) {
        properties.push_back({"float", name});
        row.push_back(name.rfind("f_rest_", 0) == 0 ? 100 + std::stoi(name.substr(7)) : 0.0);
    }
    write_bytes(dir / "rest.ply", hand_made_ply(PlyFormat::little_endian, properties, {row}));
    const GaussianCloud cloud = read_ply(dir / "rest.ply");
    ASSERT_EQ(cloud.sh_degree, 1);
    ASSERT_EQ(cloud.sh.size(), 12u);
    // [coefficient][rgb], coefficient 0 the DC term.
    const std::vector<float> expected = {0, 0, 0, 100, 103, 106, 101, 104, 107, 102, 105, 108};
    EXPECT_EQ(cloud.sh, expected);
}

std::vector<HandProperty> degree0_properties() {
    std::vector<HandProperty> properties;
    for (const auto& name : inria_names(0)) properties.push_back({"float", name});
    return properties;
}

std::vector<std::vector<double>> degree0_rows(const GaussianCloud& cloud) {
    std::vector<std::vector<double>> rows;
    for (size_t i = 0; i < cloud.size(); ++i) {
        const auto values = inria_values(cloud, i);
        std::vector<double> row;
        for (const auto& name : inria_names(0)) row.push_back(values.at(name));
        rows.push_back(row);
    }
    return rows;
}

TEST(Ply, SkipsBinaryElementsBeforeAndAfterTheVertices) {
    ScratchDir dir;
    const GaussianCloud cloud = random_cloud(5, 0, 3);
    const auto properties = degree0_properties();
    std::string file =
        "ply\nformat binary_little_endian 1.0\n"
        "element camera 2\nproperty float a\nproperty uchar b\n"
        "element strip 2\nproperty list uchar int indices\nproperty short tag\n"
        "element vertex 5\n" +
        property_lines(properties) + "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 2; ++i) file += encode_value(1.5, "float", false) + encode_value(7, "uchar", false);
    file += encode_value(2, "uchar", false) + encode_value(1, "int", false) + encode_value(2, "int", false) +
            encode_value(9, "short", false);
    file += encode_value(0, "uchar", false) + encode_value(9, "short", false);
    file += body_of(PlyFormat::little_endian, properties, degree0_rows(cloud));
    file += encode_value(3, "uchar", false) + encode_value(0, "int", false) + encode_value(1, "int", false) +
            encode_value(2, "int", false);
    write_bytes(dir / "mesh.ply", file);

    std::vector<std::string> notes;
    expect_same_cloud(cloud, read_ply(dir / "mesh.ply", &notes));
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("camera (2), strip (2), face (1)"), std::string::npos) << notes[0];
}

TEST(Ply, SkipsAsciiElementsBeforeTheVertices) {
    ScratchDir dir;
    const GaussianCloud cloud = random_cloud(3, 0, 4);
    const auto properties = degree0_properties();
    const std::string file =
        "ply\r\nformat ascii 1.0\r\nelement material 2\r\nproperty list uchar float values\r\n"
        "element vertex 3\r\n" +
        property_lines(properties) + "end_header\r\n" + "3 1 2 3\n0\n" +
        body_of(PlyFormat::ascii, properties, degree0_rows(cloud));
    write_bytes(dir / "ascii.ply", file);
    expect_same_cloud(cloud, read_ply(dir / "ascii.ply"));
}

TEST(Ply, WriteRefusesToOverwriteUnlessAsked) {
    ScratchDir dir;
    const auto path = dir / "cloud.ply";
    write_ply(random_cloud(4, 0, 1), path);
    const std::string first = read_bytes(path);
    expect_input_error([&] { write_ply(random_cloud(4, 0, 2), path); }, {path.string(), "already exists"});
    EXPECT_EQ(read_bytes(path), first);

    const GaussianCloud second = random_cloud(6, 1, 2);
    write_ply(second, path, WriteMode::overwrite);
    expect_same_cloud(second, read_ply(path));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);  // no temporary left
}

TEST(Ply, WriteRejectsAnInconsistentCloud) {
    ScratchDir dir;
    GaussianCloud cloud = random_cloud(4, 1);
    cloud.sh.pop_back();
    expect_input_error([&] { write_ply(cloud, dir / "bad.ply"); }, {"bad.ply", "inconsistent"});
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.ply"));
}

}  // namespace
}  // namespace vksplat::io::test
