// Binary glTF with KHR_gaussian_splatting: what we write reads back exactly where the format holds
// our values as they are, the file has the extension's layout, quantised attributes other writers
// may use decode as glTF defines them, and damaged files are refused with a message that names the
// file and the problem. (tests/io/gltf_validator_test.sh runs the Khronos validator on our .glb.)
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>

#include "io/io_test_helpers.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io::test {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

uint32_t u32_at(const std::string& bytes, size_t offset) {
    uint32_t value;
    std::memcpy(&value, bytes.data() + offset, 4);
    return value;
}

void append_u32(std::string& bytes, uint32_t value) { bytes.append(reinterpret_cast<const char*>(&value), 4); }

// A GLB of `document` and `bin`, each chunk padded as the container asks.
std::string make_glb(const Json& document, std::string bin) {
    std::string json = document.dump();
    json.resize((json.size() + 3) / 4 * 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    std::string glb;
    append_u32(glb, 0x46546C67);
    append_u32(glb, 2);
    append_u32(glb, uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
    append_u32(glb, uint32_t(json.size()));
    append_u32(glb, 0x4E4F534A);
    glb += json;
    if (!bin.empty()) {
        append_u32(glb, uint32_t(bin.size()));
        append_u32(glb, 0x004E4942);
        glb += bin;
    }
    return glb;
}

// The JSON and BIN chunks of a GLB we wrote (JSON first, then BIN, as write_gltf lays them out).
std::pair<Json, std::string> split_glb(const std::string& glb) {
    const uint32_t json_length = u32_at(glb, 12);
    const Json document = Json::parse(glb.substr(20, json_length));
    const size_t bin_at = 20 + json_length;
    return {document, glb.substr(bin_at + 8, u32_at(glb, bin_at))};
}

// Writes `cloud`, lets `edit` change its JSON, and writes the result as `name`.
fs::path edited_glb(const ScratchDir& dir, const std::string& name, const std::function<void(Json&)>& edit) {
    GaussianCloud cloud = random_cloud(5, 1, 11);
    write_gltf(cloud, dir / "good.glb", WriteMode::overwrite);
    auto [document, bin] = split_glb(read_bytes(dir / "good.glb"));
    edit(document);
    write_bytes(dir / name, make_glb(document, bin));
    return dir / name;
}

Json& primitive_of(Json& document) { return document["meshes"][0]["primitives"][0]; }

TEST(FormatsGltf, RoundTripKeepsEveryAttributeForEachShDegree) {
    for (int degree = 0; degree <= 3; ++degree) {
        SCOPED_TRACE("SH degree " + std::to_string(degree));
        ScratchDir dir;
        const GaussianCloud original = random_cloud(300, degree, 20 + degree);
        write_gltf(original, dir / "scene.glb");
        const GaussianCloud back = read_gltf(dir / "scene.glb");
        ASSERT_EQ(back.sh_degree, degree);
        ASSERT_EQ(back.size(), original.size());
        // Positions and SH are floats in both: bit-exact.
        EXPECT_EQ(back.positions, original.positions);
        EXPECT_EQ(back.sh, original.sh);
        for (size_t i = 0; i < original.size(); ++i) {
            // Scales are stored linear (exp then log, each rounded to float): |log error| < 1e-6.
            for (size_t a = 0; a < 3; ++a)
                EXPECT_NEAR(back.log_scales[i * 3 + a], original.log_scales[i * 3 + a], 1e-6);
            // Opacity is stored after the sigmoid: within a float's rounding of it (6e-8), which
            // for logits in [-3, 3] puts the logit within 2e-6.
            EXPECT_NEAR(sigmoid(back.opacity_logits[i]), sigmoid(original.opacity_logits[i]), 6e-8);
            EXPECT_NEAR(back.opacity_logits[i], original.opacity_logits[i], 2e-6);
            // Quaternions come back as written, normalised: within a float's rounding (1.2e-7).
            double norm = 0;
            for (size_t a = 0; a < 4; ++a) norm += double(original.rotations[i * 4 + a]) * original.rotations[i * 4 + a];
            for (size_t a = 0; a < 4; ++a)
                EXPECT_NEAR(back.rotations[i * 4 + a], original.rotations[i * 4 + a] / std::sqrt(norm), 1.2e-7);
        }
    }
}

TEST(FormatsGltf, WrittenFileHasTheExtensionsLayout) {
    ScratchDir dir;
    GaussianCloud cloud = random_cloud(3, 2, 5);
    cloud.rotations[0] = 0.5f, cloud.rotations[1] = 0.5f, cloud.rotations[2] = -0.5f, cloud.rotations[3] = 0.5f;
    cloud.sh[0] = 0.0f;  // DC 0: colour 0.5, linear 0.214 -> byte 55
    cloud.opacity_logits[0] = 0.0f;
    write_scene(cloud, dir / "scene.GLB");  // chosen by extension, in any case
    const std::string glb = read_bytes(dir / "scene.GLB");
    ASSERT_EQ(u32_at(glb, 0), 0x46546C67u);
    EXPECT_EQ(u32_at(glb, 8), glb.size());
    const auto [document, bin] = split_glb(glb);
    EXPECT_EQ(document["extensionsUsed"], Json{"KHR_gaussian_splatting"});
    const Json primitive = document["meshes"][0]["primitives"][0];
    EXPECT_EQ(primitive["mode"], 0);
    EXPECT_EQ(primitive["extensions"]["KHR_gaussian_splatting"]["kernel"], "ellipse");
    EXPECT_EQ(primitive["extensions"]["KHR_gaussian_splatting"]["colorSpace"], "srgb_rec709_display");
    const Json& attributes = primitive["attributes"];
    EXPECT_EQ(attributes.size(), 5u + 9u);  // POSITION, COLOR_0, ROTATION, SCALE, OPACITY, 9 SH
    for (const char* name : {"POSITION", "COLOR_0", "KHR_gaussian_splatting:ROTATION", "KHR_gaussian_splatting:SCALE",
                             "KHR_gaussian_splatting:OPACITY", "KHR_gaussian_splatting:SH_DEGREE_0_COEF_0",
                             "KHR_gaussian_splatting:SH_DEGREE_1_COEF_2", "KHR_gaussian_splatting:SH_DEGREE_2_COEF_4"})
        EXPECT_TRUE(attributes.contains(name)) << name;
    const auto first_float = [&, &document = document, &bin = bin](const char* name, size_t component) {
        const Json& view = document["bufferViews"][document["accessors"][attributes[name].get<size_t>()]["bufferView"].get<size_t>()];
        float value;
        std::memcpy(&value, bin.data() + view["byteOffset"].get<size_t>() + 4 * component, 4);
        return value;
    };
    // glTF's axes are the PLY's turned half a turn about z: x and y change sign, and so do the
    // quaternion's x and y and the SH odd in x and y together (degree 1: y, z, x).
    EXPECT_EQ(first_float("POSITION", 0), -cloud.positions[0]);
    EXPECT_EQ(first_float("POSITION", 1), -cloud.positions[1]);
    EXPECT_EQ(first_float("POSITION", 2), cloud.positions[2]);
    EXPECT_EQ(first_float("KHR_gaussian_splatting:SH_DEGREE_1_COEF_0", 0), -cloud.sh[3]);
    EXPECT_EQ(first_float("KHR_gaussian_splatting:SH_DEGREE_1_COEF_1", 0), cloud.sh[6]);
    EXPECT_EQ(first_float("KHR_gaussian_splatting:SH_DEGREE_1_COEF_2", 0), -cloud.sh[9]);
    EXPECT_EQ(first_float("KHR_gaussian_splatting:SH_DEGREE_2_COEF_0", 0), cloud.sh[12]);
    // glTF's quaternion order is x, y, z, w; ours w, x, y, z. (w, x, y, z) = (0.5, 0.5, -0.5, 0.5)
    // turned, t q with t = (w 0; 0, 0, 1), is (-0.5; 0.5, 0.5, 0.5).
    EXPECT_EQ(first_float("KHR_gaussian_splatting:ROTATION", 0), 0.5f);
    EXPECT_EQ(first_float("KHR_gaussian_splatting:ROTATION", 1), 0.5f);
    EXPECT_EQ(first_float("KHR_gaussian_splatting:ROTATION", 2), 0.5f);
    EXPECT_EQ(first_float("KHR_gaussian_splatting:ROTATION", 3), -0.5f);
    EXPECT_FLOAT_EQ(first_float("KHR_gaussian_splatting:SCALE", 0), std::exp(cloud.log_scales[0]));
    EXPECT_EQ(first_float("KHR_gaussian_splatting:OPACITY", 0), 0.5f);
    const Json& color = document["accessors"][attributes["COLOR_0"].get<size_t>()];
    EXPECT_EQ(color["componentType"], 5121);
    EXPECT_EQ(color["normalized"], true);
    const size_t color_at = document["bufferViews"][color["bufferView"].get<size_t>()]["byteOffset"];
    EXPECT_EQ(uint8_t(bin[color_at]), 55);       // sRGB 0.5 decoded to linear
    EXPECT_EQ(uint8_t(bin[color_at + 3]), 128);  // opacity 0.5
    EXPECT_EQ(scene_format_of(dir / "scene.GLB"), "gltf");
    expect_same_cloud(read_scene(dir / "scene.GLB"), read_gltf(dir / "scene.GLB"));
}

TEST(FormatsGltf, QuantisedAttributesDecodeAsGltfDefinesThem) {
    ScratchDir dir;
    // One splat: position as floats, rotation as normalised bytes (0, 0, 0, 127: w = 1), scale as
    // normalised shorts (65535: 1.0), opacity as a normalised byte (255: fully opaque).
    std::string bin;
    for (float v : {1.0f, 2.0f, 3.0f}) bin.append(reinterpret_cast<const char*>(&v), 4);       // 0: 12 bytes
    for (float v : {0.1f, 0.2f, 0.3f}) bin.append(reinterpret_cast<const char*>(&v), 4);       // 12: SH DC
    bin += std::string{0, 0, 0, 127};                                                          // 24: rotation
    bin += std::string("\xff\xff\x00\x80\x00\x00", 6) + std::string(2, '\0');                // 28: scale
    bin += '\xff';                                                                             // 36: opacity
    const auto view = [](size_t offset, size_t length) { return Json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}}; };
    const Json document = {
        {"asset", {{"version", "2.0"}}},
        {"buffers", {{{"byteLength", 40}}}},
        {"bufferViews", {view(0, 12), view(12, 12), view(24, 4), view(28, 6), view(36, 1)}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", 1}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 1}, {"type", "VEC3"}},
          {{"bufferView", 2}, {"componentType", 5120}, {"normalized", true}, {"count", 1}, {"type", "VEC4"}},
          {{"bufferView", 3}, {"componentType", 5123}, {"normalized", true}, {"count", 1}, {"type", "VEC3"}},
          {{"bufferView", 4}, {"componentType", 5121}, {"normalized", true}, {"count", 1}, {"type", "SCALAR"}}}},
        {"meshes",
         {{{"primitives",
            {{{"mode", 0},
              {"attributes",
               {{"POSITION", 0}, {"KHR_gaussian_splatting:SH_DEGREE_0_COEF_0", 1}, {"KHR_gaussian_splatting:ROTATION", 2},
                {"KHR_gaussian_splatting:SCALE", 3}, {"KHR_gaussian_splatting:OPACITY", 4}}},
              {"extensions", {{"KHR_gaussian_splatting", {{"kernel", "ellipse"}, {"colorSpace", "srgb_rec709_display"}}}}}}}}}}},
    };
    write_bytes(dir / "quantised.glb", make_glb(document, bin));
    const GaussianCloud cloud = read_gltf(dir / "quantised.glb");
    ASSERT_EQ(cloud.size(), 1u);
    EXPECT_EQ(cloud.positions, (std::vector<float>{-1, -2, 3}));  // glTF's axes turned back
    EXPECT_EQ(cloud.sh, (std::vector<float>{0.1f, 0.2f, 0.3f}));
    EXPECT_EQ(cloud.rotations, (std::vector<float>{0, 0, 0, -1}));  // glTF's identity, turned back: a half turn
    EXPECT_FLOAT_EQ(cloud.log_scales[0], 0.0f);
    EXPECT_FLOAT_EQ(cloud.log_scales[1], static_cast<float>(std::log(32768 / 65535.0)));
    EXPECT_EQ(cloud.log_scales[2], kMinLogScale);  // a scale of 0
    EXPECT_EQ(cloud.opacity_logits[0], kMaxOpacityLogit);
}

TEST(FormatsGltf, SplatPrimitivesAreJoinedIntoOneScene) {
    ScratchDir dir;
    // The same splats twice, the second time without their degree-1 SH.
    const fs::path path = edited_glb(dir, "two.glb", [](Json& d) {
        Json second = primitive_of(d);
        for (int order = 0; order < 3; ++order)
            second["attributes"].erase("KHR_gaussian_splatting:SH_DEGREE_1_COEF_" + std::to_string(order));
        d["meshes"][0]["primitives"].push_back(second);
    });
    std::vector<std::string> notes;
    const GaussianCloud joined = read_gltf(path, &notes);
    const GaussianCloud one = read_gltf(dir / "good.glb");
    ASSERT_EQ(joined.size(), 2 * one.size());
    EXPECT_EQ(joined.sh_degree, 1);
    EXPECT_EQ(std::vector<float>(joined.positions.begin() + 15, joined.positions.end()), one.positions);
    for (size_t i = one.size(); i < joined.size(); ++i) {
        EXPECT_EQ(joined.sh[i * 12], one.sh[(i - one.size()) * 12]);  // the DC term kept
        for (size_t k = 3; k < 12; ++k) EXPECT_EQ(joined.sh[i * 12 + k], 0.0f);
    }
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("2 splat primitives joined"), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("padded with zeros"), std::string::npos) << notes[0];
}

TEST(FormatsGltf, DamagedFilesAreRefusedNamingTheFileAndTheProblem) {
    ScratchDir dir;
    const GaussianCloud cloud = random_cloud(5, 1, 11);
    write_gltf(cloud, dir / "good.glb");
    const std::string good = read_bytes(dir / "good.glb");
    const auto refused = [&](const fs::path& path, const std::vector<std::string>& parts) {
        std::vector<std::string> expected = parts;
        expected.push_back(path.string());
        expect_input_error([&] { read_gltf(path); }, expected);
    };

    write_bytes(dir / "magic.glb", "PLY\n" + good.substr(4));
    refused(dir / "magic.glb", {"wrong magic"});
    write_bytes(dir / "short.glb", good.substr(0, 7));
    refused(dir / "short.glb", {"truncated", "12-byte GLB header"});
    // Header length and BIN chunk length both promise more than the file holds.
    const std::string cut = good.substr(0, good.size() - 16);
    write_bytes(dir / "cut.glb", cut);
    refused(dir / "cut.glb", {"truncated", "the header says " + std::to_string(good.size())});
    std::string cut_chunk = cut;
    const uint32_t size = uint32_t(cut_chunk.size());
    std::memcpy(cut_chunk.data() + 8, &size, 4);
    write_bytes(dir / "cut_chunk.glb", cut_chunk);
    refused(dir / "cut_chunk.glb", {"truncated", "chunk at byte", "are left"});

    refused(edited_glb(dir, "plain.glb", [](Json& d) { primitive_of(d).erase("extensions"); }),
            {"no mesh primitive with the KHR_gaussian_splatting extension"});
    refused(edited_glb(dir, "range.glb", [](Json& d) { d["bufferViews"][0]["byteLength"] = 40; }),
            {"attribute POSITION", "out of range"});
    refused(edited_glb(dir, "view.glb", [](Json& d) { d["bufferViews"][2]["byteOffset"] = 1u << 30; }),
            {"out of range"});
    // A stride whose product with the count passes 2^64 is out of range too, not wrapped into it.
    refused(edited_glb(dir, "stride.glb", [](Json& d) { d["bufferViews"][0]["byteStride"] = uint64_t(1) << 62; }),
            {"attribute POSITION", "out of range"});
    refused(edited_glb(dir, "count.glb", [](Json& d) { d["accessors"][3]["count"] = 4; }),
            {"holds 4 elements where POSITION holds 5"});
    refused(edited_glb(dir, "missing.glb", [](Json& d) { primitive_of(d)["attributes"].erase("KHR_gaussian_splatting:SCALE"); }),
            {"lacks the attribute KHR_gaussian_splatting:SCALE"});
    refused(edited_glb(dir, "partial.glb", [](Json& d) { primitive_of(d)["attributes"].erase("KHR_gaussian_splatting:SH_DEGREE_1_COEF_1"); }),
            {"SH degree 1 in part", "SH_DEGREE_1_COEF_1"});
    refused(edited_glb(dir, "mode.glb", [](Json& d) { primitive_of(d)["mode"] = 4; }), {"mode 4", "POINTS"});
    refused(edited_glb(dir, "moved.glb", [](Json& d) { d["nodes"][0]["translation"] = {1, 0, 0}; }),
            {"node 0's transform"});
    refused(edited_glb(dir, "accessor.glb", [](Json& d) { primitive_of(d)["attributes"]["POSITION"] = 99; }),
            {"accessors 99, which does not exist"});
    refused(edited_glb(dir, "typed.glb", [](Json& d) { d["accessors"][0]["count"] = "five"; }),
            {"malformed glTF JSON"});
    expect_input_error([&] { read_scene(dir / "scene.gltf"); }, {"scene.gltf", "use binary glTF (.glb)"});
    expect_input_error([&] { write_scene(cloud, dir / "scene.gltf"); }, {"scene.gltf", ".glb"});
}

TEST(FormatsGltf, OpacitiesThatRoundToOneComeBackAtTheClamp) {
    ScratchDir dir;
    GaussianCloud cloud = random_cloud(2, 0, 4);
    cloud.opacity_logits = {17.0f, 20.0f};  // sigmoid(17) is still below 1 as a float, sigmoid(20) is not
    write_gltf(cloud, dir / "opaque.glb");
    const GaussianCloud back = read_gltf(dir / "opaque.glb");
    EXPECT_NEAR(back.opacity_logits[0], 17.0f, 0.5f);
    EXPECT_EQ(back.opacity_logits[1], kMaxOpacityLogit);
}

TEST(FormatsGltf, WriterRefusesWhatGltfCannotHold) {
    ScratchDir dir;
    GaussianCloud cloud = random_cloud(2, 0, 3);
    cloud.positions[4] = NAN;
    expect_input_error([&] { write_gltf(cloud, dir / "nan.glb"); }, {"nan.glb", "Gaussian 1", "not finite"});
    cloud = random_cloud(2, 0, 3);
    std::fill(cloud.rotations.begin(), cloud.rotations.end(), 0.0f);
    expect_input_error([&] { write_gltf(cloud, dir / "zero.glb"); }, {"zero.glb", "length 0"});
    expect_input_error([&] { write_gltf(GaussianCloud{}, dir / "empty.glb"); }, {"empty.glb", "empty scene"});
    EXPECT_FALSE(fs::exists(dir / "nan.glb"));
}

}  // namespace
}  // namespace vksplat::io::test
